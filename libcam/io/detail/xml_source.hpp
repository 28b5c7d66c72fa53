#pragma once
// An XML file being read, for messages that name the line of an element:
// "<source>: line L: <what>". The readers of XML formats (Metashape, lensfun) derive their
// own field readers from it.

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>

#include <pugixml.hpp>

#include "libcam/error.hpp"

namespace libcam {

// The line of byte `offset` of `text`, counted from 1.
inline int line_at_offset(std::string_view text, std::ptrdiff_t offset) {
    const auto end = std::min<std::size_t>(static_cast<std::size_t>(std::max<std::ptrdiff_t>(offset, 0)), text.size());
    return static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(end), '\n')) + 1;
}

// Parses `text` into `document`; throws FileError "<source>: line L: not valid XML: <why>".
inline void load_xml(pugi::xml_document& document, std::string_view text, const std::string& source) {
    const pugi::xml_parse_result result = document.load_buffer(text.data(), text.size(), pugi::parse_default);
    if (!result) {
        throw FileError(source + ": line " + std::to_string(line_at_offset(text, result.offset)) +
                        ": not valid XML: " + result.description());
    }
}

class XmlSource {
public:
    XmlSource(std::string_view text, const std::string& name) : text_(text), name_(name) {}

    [[noreturn]] void fail(const pugi::xml_node& node, const std::string& what) const {
        throw FileError(name_ + ": line " + std::to_string(line_of(node)) + ": " + what);
    }

    const std::string& name() const { return name_; }

private:
    // pugixml keeps each element's byte offset (parse_default); 0 where it has none.
    int line_of(const pugi::xml_node& node) const {
        const std::ptrdiff_t offset = node.offset_debug();
        return offset < 0 ? 0 : line_at_offset(text_, offset);
    }

    std::string_view text_;
    const std::string& name_;
};

}  // namespace libcam
