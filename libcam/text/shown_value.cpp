#include "libcam/text/shown_value.hpp"

#include <cstdio>

#include "libcam/text/utf8.hpp"

namespace libcam {

namespace {

// Characters a terminal would not show as themselves: C0 and C1 controls, DEL, and the
// invisible ones that break a line or reorder what follows it.
bool shown_escaped(std::uint32_t code) {
    return code < 0x20 || (code >= 0x7F && code <= 0x9F) || code == 0x200E || code == 0x200F ||
           (code >= 0x2028 && code <= 0x202E) || (code >= 0x2066 && code <= 0x2069) || code == 0xFEFF;
}

std::string escaped(std::uint32_t code) {
    switch (code) {
        case '\t': return "\\t";
        case '\n': return "\\n";
        case '\r': return "\\r";
        default: break;
    }
    char buffer[16];
    std::snprintf(buffer, sizeof buffer, code < 0x80 ? "\\x%02X" : "\\u%04X", static_cast<unsigned>(code));
    return buffer;
}

// The text as printable_text writes it; `cut` says whether it stopped short.
std::string printable(std::string_view bytes, std::size_t max_characters, bool& cut) {
    std::string out;
    std::size_t characters = 0;
    cut = false;
    for (std::size_t at = 0; at < bytes.size(); ++characters) {
        if (characters == max_characters) {
            cut = true;
            return out + "...";
        }
        const Utf8Character character = utf8_character_at(bytes, at);
        if (character.length == 0) {
            char buffer[8];
            const auto byte = static_cast<unsigned char>(bytes[at]);
            std::snprintf(buffer, sizeof buffer, "\\x%02X", static_cast<unsigned>(byte));
            out += buffer;
            ++at;
            continue;
        }
        if (shown_escaped(character.code)) {
            out += escaped(character.code);
        } else {
            out.append(bytes.substr(at, character.length));
        }
        at += character.length;
    }
    return out;
}

}  // namespace

std::string printable_text(std::string_view bytes, std::size_t max_characters) {
    bool cut = false;
    return printable(bytes, max_characters, cut);
}

std::string shown_value(std::string_view bytes, char quote) {
    bool cut = false;
    const std::string shown = quote + printable(bytes, kShownValueLength, cut) + quote;
    return cut ? shown + " (" + std::to_string(bytes.size()) + " bytes)" : shown;
}

}  // namespace libcam
