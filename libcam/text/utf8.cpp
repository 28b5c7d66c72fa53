#include "libcam/text/utf8.hpp"

namespace libcam {

Utf8Character utf8_character_at(std::string_view text, std::size_t at) {
    const auto byte = static_cast<unsigned char>(text[at]);
    // The length of the sequence this byte starts, and its smallest code point (so
    // overlong encodings are refused too).
    const std::size_t length = byte < 0x80           ? 1
                               : (byte >> 5) == 0x6  ? 2
                               : (byte >> 4) == 0xE  ? 3
                               : (byte >> 3) == 0x1E ? 4
                                                     : 0;
    if (length == 0 || at + length > text.size()) return {};
    std::uint32_t code = length == 1 ? byte : byte & (0x7F >> length);
    for (std::size_t k = 1; k < length; ++k) {
        const auto next = static_cast<unsigned char>(text[at + k]);
        if ((next >> 6) != 0x2) return {};
        code = (code << 6) | (next & 0x3F);
    }
    constexpr std::uint32_t kSmallest[] = {0, 0, 0x80, 0x800, 0x10000};
    if (code < kSmallest[length] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return {};
    return {code, length};
}

namespace {

using namespace std::string_view_literals;

// The code unit of `width` bytes (2 or 4) at byte `at`.
std::uint32_t unit_at(std::string_view bytes, std::size_t at, std::size_t width, bool little_endian) {
    std::uint32_t unit = 0;
    for (std::size_t k = 0; k < width; ++k) {
        const auto byte = static_cast<unsigned char>(bytes[at + (little_endian ? width - 1 - k : k)]);
        unit = (unit << 8) | byte;
    }
    return unit;
}

// Whether the first units from `at` (at most 16 looked at) all pass `test`, and there
// are at least `least` of them.
template <class Test>
bool units_pass(std::string_view bytes, std::size_t at, std::size_t width, bool little_endian, std::size_t least,
                Test&& test) {
    std::size_t count = 0;
    for (; count < 16 && at + (count + 1) * width <= bytes.size(); ++count) {
        if (!test(unit_at(bytes, at + count * width, width, little_endian))) return false;
    }
    return count >= least;
}

bool printable_ascii(std::uint32_t unit) {
    return unit == '\t' || unit == '\n' || unit == '\r' || (unit >= 0x20 && unit < 0x7F);
}
bool not_nul(std::uint32_t unit) { return unit != 0; }

}  // namespace

std::string_view wide_text_encoding(std::string_view bytes) {
    for (const std::size_t width : {std::size_t{4}, std::size_t{2}}) {
        const std::string_view name = width == 4 ? "UTF-32" : "UTF-16";
        for (const bool little_endian : {true, false}) {
            // A byte-order mark followed by characters (none NUL: a count of 65279 in a
            // binary file starts with UTF-32's mark, then zeros), or by nothing.
            const bool marked = bytes.size() >= width && unit_at(bytes, 0, width, little_endian) == 0xFEFF;
            const bool characters_after = units_pass(bytes, width, width, little_endian, 1, not_nul);
            if (marked && (bytes.size() == width || characters_after)) return name;
            // Without a mark: ASCII text, each character widened with NUL bytes.
            if (units_pass(bytes, 0, width, little_endian, 2, printable_ascii)) return name;
        }
    }
    return {};
}

}  // namespace libcam
