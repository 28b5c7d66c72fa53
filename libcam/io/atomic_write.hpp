#pragma once
// Writing a file never leaves a half-written or emptied file behind: the contents go
// to a temporary file in the same folder, are flushed to disk, and the temporary is
// renamed over the target. On any failure the old file (if any) is untouched and the
// temporary is removed.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace libcam {

// Throws FileError naming the path and the reason.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// A process killed while writing leaves its temporary file (".<name>.tmp-<number>" beside
// the target). Removes every such file under `folder`, at any depth, and returns how many:
// for a folder only libcam writes into (a dataset's output), before writing into it again.
std::size_t remove_stopped_writes(const std::filesystem::path& folder);

// The whole file as a string; throws FileError naming the path and the reason.
std::string read_text_file(const std::filesystem::path& path);

}  // namespace libcam
