// Every format libcam reads, against every kind of damage a file meets: a table of formats
// x damages, so that a new format gets the whole table. The valid file each row starts from
// is the format's first seed of the fuzz corpus (tests/fuzz/corpus/<name>/) that reads; each
// damage is made from it under the same file name (detection by extension sees the same
// format). For every damaged file, what `libcam info` reads (read_camera_set) and, for a
// format that holds observations, what `libcam reproject` reads (read_observations):
//   - either reads, every camera valid, or is refused with a libcam error;
//   - a refusal is one line that starts with the file's path (or, for a model of several
//     files, its folder's), shows no byte that is not printable text, and is short enough
//     to read;
//   - the two readers agree: a file whose observations read has cameras that read.
// The fuzz targets (tests/fuzz) try far more inputs, with the sanitizers; this table runs in
// every build and says which format and damage failed.

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <functional>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/camera_formats.hpp"
#include "libcam/io/observations.hpp"
#include "temp_dir.hpp"

namespace fs = std::filesystem;
using libcam::test::TempDir;

namespace {

struct Damage {
    const char* name;
    // The damaged bytes, or nullopt where the damage does not apply to this file.
    std::function<std::optional<std::string>(const std::string&)> apply;
};

bool is_text(const std::string& bytes) {
    return std::none_of(bytes.begin(), bytes.end(), [](char c) { return c == '\0'; });
}

// The first number in the text (not inside a word) replaced by `with`.
std::optional<std::string> first_number_replaced(const std::string& text, const std::string& with) {
    if (!is_text(text)) return std::nullopt;
    static const std::regex number(R"((^|[^\w.])(-?\d+\.\d+(?:[eE][-+]?\d+)?))");
    std::smatch match;
    if (!std::regex_search(text, match, number)) return std::nullopt;
    const auto at = static_cast<std::size_t>(match.position(2));
    return text.substr(0, at) + with + text.substr(at + static_cast<std::size_t>(match.length(2)));
}

std::string random_bytes(std::size_t count, unsigned seed) {
    std::mt19937 generator(seed);
    std::string bytes(count, '\0');
    for (char& c : bytes) c = static_cast<char>(generator() & 0xff);
    return bytes;
}

const std::vector<Damage>& damages() {
    static const std::vector<Damage> all = {
        {"empty", [](const std::string&) { return std::string(); }},
        {"blank lines", [](const std::string&) { return std::string(" \n\n\t\n"); }},
        {"cut in half", [](const std::string& t) { return t.substr(0, t.size() / 2); }},
        {"cut one byte short", [](const std::string& t) { return t.substr(0, t.size() - 1); }},
        {"random bytes", [](const std::string& t) { return random_bytes(std::max<std::size_t>(t.size(), 64), 7); }},
        {"random bytes appended", [](const std::string& t) { return t + random_bytes(64, 11); }},
        {"a NUL byte inside", [](const std::string& t) { return t.substr(0, t.size() / 2) + '\0' + t.substr(t.size() / 2); }},
        {"UTF-16", [](const std::string& t) -> std::optional<std::string> {
             if (!is_text(t)) return std::nullopt;
             std::string wide = "\xff\xfe";
             for (const char c : t) wide += std::string(1, c) + '\0';
             return wide;
         }},
        {"twice over", [](const std::string& t) { return t + "\n" + t; }},
        {"a number overflowing", [](const std::string& t) { return first_number_replaced(t, "1e999"); }},
        {"a subnormal number", [](const std::string& t) { return first_number_replaced(t, "5e-324"); }},
        {"a number NaN", [](const std::string& t) { return first_number_replaced(t, "nan"); }},
        {"a number huge", [](const std::string& t) { return first_number_replaced(t, "1e30"); }},
        {"a number negative", [](const std::string& t) { return first_number_replaced(t, "-7.5"); }},
    };
    return all;
}

// Whether every byte is printable text: no control characters, valid UTF-8.
bool printable(const std::string& message) {
    for (std::size_t i = 0; i < message.size();) {
        const auto c = static_cast<unsigned char>(message[i]);
        if (c < 0x20 || c == 0x7f) return false;
        std::size_t length = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
        if (length == 0 || i + length > message.size()) return false;
        for (std::size_t k = 1; k < length; ++k) {
            if ((static_cast<unsigned char>(message[i + k]) >> 6) != 0x2) return false;
        }
        i += length;
    }
    return true;
}

struct Seed {
    fs::path file;
    // What the damaged files are read with: nothing where detection finds the format (as
    // `libcam info FILE` reads), the format where only naming it does (--from-format).
    std::optional<libcam::CameraFormat> named;
    // And what `libcam info` is given for a file that does not record it (--image-size,
    // a lens database's --focal-mm).
    libcam::ReadOptions options;
};

std::vector<libcam::ReadOptions> read_options_to_try() {
    libcam::ReadOptions sized;
    sized.size = libcam::ImageSize{1500, 1000};
    libcam::ReadOptions lens = sized;
    lens.focal_mm = 30.0;
    return {{}, sized, lens};
}

// The first seed of the format's corpus folder that reads as that format.
std::optional<Seed> readable_seed(const libcam::CameraFormatInfo& format) {
    const fs::path folder = fs::path(LIBCAM_FUZZ_CORPUS) / std::string(format.name);
    std::error_code error;
    if (!fs::is_directory(folder, error)) return std::nullopt;
    std::vector<fs::path> seeds;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
        if (entry.is_regular_file()) seeds.push_back(entry.path());
    }
    std::sort(seeds.begin(), seeds.end());
    for (const std::optional<libcam::CameraFormat> named : {std::optional<libcam::CameraFormat>(), std::optional(format.format)}) {
        for (const libcam::ReadOptions& options : read_options_to_try()) {
            for (const fs::path& seed : seeds) {
                try {
                    if (libcam::read_camera_set(seed, named, options).format == format.format) return Seed{seed, named, options};
                } catch (const libcam::Error&) {
                }
            }
        }
    }
    return std::nullopt;
}

// A refusal as the table expects it; `file` the damaged file.
void check_refusal(const std::string& message, const fs::path& file) {
    INFO("message: " << message);
    CHECK((message.starts_with(file.string() + ": ") || message.starts_with(file.parent_path().string())));
    CHECK(message.find('\n') == std::string::npos);
    CHECK(printable(message));
    CHECK(message.size() < 600);
}

struct Outcome {
    bool read = false;
    std::string message;
};

template <class Read>
Outcome attempt(Read&& read, const fs::path& file) {
    Outcome outcome;
    try {
        read();
        outcome.read = true;
    } catch (const libcam::Error& error) {
        outcome.message = error.what();
        check_refusal(outcome.message, file);
    }
    return outcome;
}

}  // namespace

TEST_CASE("Damaged files: each format x each damage reads or is refused in one clean line, info and reproject alike",
          "[files][damage]") {
    std::size_t tried = 0;
    for (const libcam::CameraFormatInfo& format : libcam::camera_formats()) {
        if (!format.reads || !format.available) continue;
        const std::optional<Seed> seed = readable_seed(format);
        CAPTURE(format.name);
        CHECK(seed);  // every format libcam reads has a seed that reads (the fuzz corpus's rule)
        if (!seed) continue;
        const std::string original = libcam::read_text_file(seed->file);
        for (const Damage& damage : damages()) {
            const std::optional<std::string> bytes = damage.apply(original);
            if (!bytes) continue;
            CAPTURE(damage.name);
            TempDir dir;
            const fs::path file = dir / seed->file.filename().string();
            libcam::write_file_atomically(file, *bytes);
            ++tried;
            const Outcome cameras = attempt(
                [&] {
                    for (const libcam::NamedCamera& camera : libcam::read_camera_set(file, seed->named, seed->options).cameras) camera.file.camera.validate();
                },
                file);
            if (!format.observations) continue;
            const Outcome observations = attempt([&] { (void)libcam::read_observations(file); }, file);
            if (observations.read) CHECK(cameras.read);  // reproject takes no file that info refuses
        }
    }
    CHECK(tried > 300);
}

TEST_CASE("Damaged files: a symlink loop and a folder in a camera file's place are refused naming them", "[files][damage]") {
    TempDir dir;
    const fs::path loop = dir / "cameras.json";
    fs::create_symlink(dir / "other.json", loop);
    fs::create_symlink(loop, dir / "other.json");
    CHECK_THROWS_WITH(libcam::read_camera_set(loop), Catch::StartsWith(loop.string() + ": ") &&
                                                         Catch::Contains("symbolic links"));
    const fs::path folder = dir / "folder.yaml";
    fs::create_directory(folder);
    CHECK_THROWS_WITH(libcam::read_camera_set(folder), Catch::StartsWith(folder.string() + ": "));
}
