#pragma once
// Writing a file never leaves a half-written or emptied file behind: the contents go
// to a temporary file in the same folder, are flushed to disk, and the temporary is
// renamed over the target. On any failure the old file (if any) is untouched and the
// temporary is removed.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace libcam {

// Throws FileError naming the path and the reason. The folder is flushed too, so that the
// rename itself survives a power cut (sync_folder).
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// Flushes a folder's entries to disk (fsync on the folder): a file renamed or moved into it
// is then there after a power cut, not only its contents. Best effort: a file system that
// cannot flush a folder (EINVAL, EROFS) is left as it is; other failures throw FileError.
void sync_folder(const std::filesystem::path& folder);

// A process killed while writing leaves its temporary file (".<name>.tmp-<number>" beside
// the target). Removes every such file under `folder`, at any depth, and returns how many:
// for a folder only libcam writes into (a dataset's output), before writing into it again.
std::size_t remove_stopped_writes(const std::filesystem::path& folder);

// The most libcam reads of one file, by kind, so that a file that is not what its name
// says (a symlink to /dev/zero named transforms.json, a FIFO that never ends) is refused
// at that size rather than read until memory runs out. Each is the largest such file
// seen from the tools that write it, with a wide margin (docs/reliability.md lists them
// per format).
struct ReadLimit {
    std::uint64_t max_bytes = 0;
    std::string_view kind;  // for the message: "NeRF transforms.json", "COLMAP images or points3D"
};
constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;
constexpr std::uint64_t kGiB = std::uint64_t{1} << 30;
// A camera file: one camera, a rig, a calibration with its per-view results, a lens
// database, a project (the largest real ones are a few hundred KB).
constexpr ReadLimit kCameraFileLimit{64 * kMiB, "camera"};
// A text reconstruction with its points and observations (OpenSfM, OpenMVG, AliceVision,
// VisualSfM, Bundler; tracks, tables of observations): hundreds of MB for large scenes.
constexpr ReadLimit kReconstructionLimit{2 * kGiB, "reconstruction"};
// COLMAP's images and points3D files, binary or text: a few GB for large scenes.
constexpr ReadLimit kColmapModelPartLimit{16 * kGiB, "COLMAP images or points3D"};
// The largest of all: what a read that names no kind takes.
constexpr ReadLimit kAnyFileLimit{16 * kGiB, "file"};

// "64 MiB", "2 GiB", "100 bytes": a limit as messages and docs write it.
std::string byte_size_text(std::uint64_t bytes);

// The whole file as a string, at most `limit.max_bytes` of it: a larger file is refused,
// "<file>: larger than 64 MiB, more than libcam reads of any <kind> file". A FIFO (a
// process substitution) is read as a stream up to the limit; a device (/dev/zero, a
// terminal) is refused, as it is no file. Throws FileError naming the path and the reason
// (the system's words: "No such file or directory", "Too many levels of symbolic links").
std::string read_text_file(const std::filesystem::path& path, const ReadLimit& limit = kAnyFileLimit);

// Whether a regular file is at `path` (through symlinks): false where nothing is there or
// something else is (a folder); throws FileError with the system's words where the path
// cannot be followed ("Too many levels of symbolic links", "Permission denied"), rather
// than taking that for a file that is not there.
bool regular_file_exists(const std::filesystem::path& path);

// Throws the FileError read_text_file throws for a file larger than the limit.
[[noreturn]] void throw_larger_than(const std::filesystem::path& path, const ReadLimit& limit);

}  // namespace libcam
