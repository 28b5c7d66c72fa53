// How much libcam reads of a file: never more than the limit of what it reads it as, from
// regular files, pipes and FIFOs alike; a device is no file. The limits are asserted on
// their messages (no timing): a read that did not stop would not return at all.

#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "error_message.hpp"
#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/camera_file.hpp"
#include "temp_dir.hpp"

using namespace libcam;
using libcam::test::file_error_of;
using libcam::test::write_file;

namespace {

constexpr ReadLimit kHundredBytes{100, "test"};

// A pipe holding `bytes`, its writing end closed, named as a process substitution names
// it (/dev/fd/N); the reading end is closed when it goes.
class FilledPipe {
public:
    explicit FilledPipe(const std::string& bytes) {
        REQUIRE(::pipe(ends_) == 0);
        REQUIRE(::write(ends_[1], bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size()));
        ::close(ends_[1]);
    }
    ~FilledPipe() { ::close(ends_[0]); }
    std::filesystem::path path() const { return "/dev/fd/" + std::to_string(ends_[0]); }

private:
    int ends_[2] = {-1, -1};
};

}  // namespace

TEST_CASE("read_text_file reads a file up to its limit and refuses one a byte past it", "[limits]") {
    const test::TempDir dir;
    CHECK(read_text_file(write_file(dir, "at.txt", std::string(100, 'a')), kHundredBytes) == std::string(100, 'a'));
    const auto past = write_file(dir, "past.txt", std::string(101, 'a'));
    CHECK(file_error_of([&] { (void)read_text_file(past, kHundredBytes); }) ==
          past.string() + ": larger than 100 bytes, more than libcam reads of any test file");
    // A pipe has no size to refuse it by: it is read up to the limit, and one byte more tells.
    CHECK(read_text_file(FilledPipe(std::string(100, 'b')).path(), kHundredBytes) == std::string(100, 'b'));
    const FilledPipe long_pipe(std::string(1000, 'b'));
    CHECK(file_error_of([&] { (void)read_text_file(long_pipe.path(), kHundredBytes); }) ==
          long_pipe.path().string() + ": larger than 100 bytes, more than libcam reads of any test file");
}

TEST_CASE("A camera file that is /dev/zero, a FIFO no one writes or too large for its format is refused, saying so",
          "[limits]") {
    const test::TempDir dir;
    // A transforms.json that is a symlink to /dev/zero: a device, refused before any read.
    std::filesystem::create_symlink("/dev/zero", dir / "transforms.json");
    CHECK(file_error_of([&] { (void)read_camera_set(dir / "transforms.json"); }) ==
          (dir / "transforms.json").string() +
              ": a device (/dev/zero), not a file: libcam reads camera files from files and pipes");
    // A FIFO that no process writes to reads as empty rather than waiting for one.
    REQUIRE(::mkfifo((dir / "fifo.json").c_str(), 0600) == 0);
    CHECK(file_error_of([&] { (void)read_camera_set(dir / "fifo.json"); }) == (dir / "fifo.json").string() + ": file is empty");
    // One byte past a NeRF transforms.json's 64 MiB (a sparse file: nothing is written or read).
    const auto large = write_file(dir, "large.json", "{");
    std::filesystem::resize_file(large, 64 * kMiB + 1);
    CHECK(file_error_of([&] { (void)read_camera_set(large, CameraFormat::Nerf); }) ==
          large.string() + ": larger than 64 MiB, more than libcam reads of any NeRF transforms.json file");
    // A .cameramodel's limit is its own (256 MiB, for its optimization inputs).
    const auto model = write_file(dir, "large.cameramodel", "{");
    std::filesystem::resize_file(model, 256 * kMiB + 1);
    CHECK(file_error_of([&] { (void)read_camera_set(model); }) ==
          model.string() + ": larger than 256 MiB, more than libcam reads of any mrcal .cameramodel file");
    // A camera file given through a pipe is read as any other.
    const FilledPipe pipe(R"({"model": "PINHOLE", "image_size": [640, 480], "K": [[500, 0, 319.5], [0, 500, 239.5], [0, 0, 1]],)"
                          R"( "rvec": [0, 0, 0], "t": [0, 0, 0]})");
    CHECK(read_camera_set(pipe.path(), CameraFormat::Json).cameras.front().file.camera.intrinsics.fx == 500);
}

TEST_CASE("byte_size_text: limits as messages and the docs write them", "[limits]") {
    CHECK(byte_size_text(64 * kMiB) == "64 MiB");
    CHECK(byte_size_text(2 * kGiB) == "2 GiB");
    CHECK(byte_size_text(3072) == "3 KiB");
    CHECK(byte_size_text(1536) == "1536 bytes");
    CHECK(byte_size_text(100) == "100 bytes");
    CHECK(byte_size_text(1) == "1 byte");
    CHECK(byte_size_text(kMiB + 1) == "1048577 bytes");
}
