#include "libcam/io/detail/cameramodel_text.hpp"

#include <algorithm>

#include "libcam/error.hpp"

namespace libcam::detail {

namespace {

// The line is counted only for the message: counting as the check goes made a string for
// every byte.
[[noreturn]] void refuse_at(std::string_view text, std::size_t offset, const std::string& source,
                            const std::string& what) {
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n');
    throw FileError(source + ": line " + std::to_string(line) + ": " + what);
}

}  // namespace

void check_cameramodel_size(std::uintmax_t bytes, const std::string& source) {
    if (bytes <= kLargestCameramodel) return;
    throw FileError(source + ": " + std::to_string(bytes) + " bytes: larger than the " +
                    std::to_string(kLargestCameramodel >> 20) + " MiB libcam reads as a .cameramodel");
}

void check_cameramodel_lexically(std::string_view text, const std::string& source) {
    constexpr int kMaxDepth = 8;
    check_cameramodel_size(text.size(), source);
    if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
        refuse_at(text, nul, source, "contains a NUL byte");
    }
    int depth = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '#') {
            i = std::min(text.find('\n', i), text.size()) - 1;  // the comment, up to its newline
        } else if (c == '\'' || c == '"') {
            std::size_t end = i + 1;
            while (end < text.size() && text[end] != c && text[end] != '\n') end += text[end] == '\\' ? 2 : 1;
            if (end >= text.size() || text[end] != c) refuse_at(text, i, source, "unterminated string");
            i = end;
        } else if (c == '{' || c == '[' || c == '(') {
            if (++depth > kMaxDepth) {
                refuse_at(text, i, source, "nested more than " + std::to_string(kMaxDepth) + " deep");
            }
        } else if (c == '}' || c == ']' || c == ')') {
            if (--depth < 0) refuse_at(text, i, source, "unbalanced '" + std::string(1, c) + "'");
        }
    }
    if (depth != 0) throw FileError(source + ": unbalanced brackets (truncated file?)");
}

}  // namespace libcam::detail
