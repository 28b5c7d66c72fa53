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
        if (offset < 0) return 0;
        const std::string_view before = text_.substr(0, std::min<std::size_t>(static_cast<std::size_t>(offset), text_.size()));
        return static_cast<int>(std::count(before.begin(), before.end(), '\n')) + 1;
    }

    std::string_view text_;
    const std::string& name_;
};

}  // namespace libcam
