#pragma once
// Writing a file never leaves a half-written or emptied file behind: the contents go
// to a temporary file in the same folder, are flushed to disk, and the temporary is
// renamed over the target. On any failure the old file (if any) is untouched and the
// temporary is removed.

#include <filesystem>
#include <string_view>

namespace libcam {

// Throws FileError naming the path and the reason.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// The whole file as a string; throws FileError naming the path and the reason.
std::string read_text_file(const std::filesystem::path& path);

}  // namespace libcam
