#pragma once
// UTF-8, the one text encoding libcam reads camera files in: each character decoded by one
// function (the check that a file is text, and the messages that show a file's words),
// and the other Unicode encodings told apart, so that a file saved in them is refused
// for what it is.

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace libcam {

// The character that starts at byte `at` of `text`: its code point and its length in
// bytes; length 0 where the bytes there are not UTF-8 (a stray continuation byte, a
// sequence cut short, an overlong form, a surrogate, past U+10FFFF).
struct Utf8Character {
    std::uint32_t code = 0;
    std::size_t length = 0;
};
Utf8Character utf8_character_at(std::string_view text, std::size_t at);

// The byte-order mark some editors write first in UTF-8 text (EF BB BF).
constexpr std::string_view kUtf8ByteOrderMark = "\xEF\xBB\xBF";

// "UTF-16" or "UTF-32" when the bytes are text in that encoding (a byte-order mark, or
// ASCII characters each followed or preceded by NUL bytes, as Windows' "Unicode" files
// are); empty otherwise. Binary files whose first bytes are small counts (COLMAP's
// cameras.bin) are not taken for text: the characters must be printable.
std::string_view wide_text_encoding(std::string_view bytes);

}  // namespace libcam
