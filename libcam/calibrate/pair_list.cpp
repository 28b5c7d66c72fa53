#include "libcam/calibrate/pair_list.hpp"

#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/error.hpp"

namespace libcam {

namespace {

// The names of a list, one token each: a "quoted" name (spaces allowed), or a run of
// characters up to a space, a comma or the list's end.
std::vector<std::string> tokens(std::string_view text, std::string_view stop_at) {
    std::vector<std::string> out;
    std::size_t i = 0;
    const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == ','; };
    while (i < text.size()) {
        while (i < text.size() && space(text[i])) ++i;
        if (i >= text.size() || stop_at.find(text[i]) != std::string_view::npos) break;
        if (text[i] == '"' || text[i] == '\'') {
            const std::size_t end = text.find(text[i], i + 1);
            if (end == std::string_view::npos) break;
            out.emplace_back(text.substr(i + 1, end - i - 1));
            i = end + 1;
        } else {
            const std::size_t start = i;
            while (i < text.size() && !space(text[i]) && stop_at.find(text[i]) == std::string_view::npos) ++i;
            out.emplace_back(text.substr(start, i - start));
        }
    }
    return out;
}

std::string trimmed_line(std::string_view line) {
    const std::size_t start = line.find_first_not_of(" \t\r");
    if (start == std::string_view::npos) return {};
    const std::size_t end = line.find_last_not_of(" \t\r");
    return std::string(line.substr(start, end - start + 1));
}

// The names under `imagelist` in the three forms OpenCV writes a list of strings: XML
// (<imagelist> names </imagelist>), YAML or JSON flow ([ "a", "b" ]) and YAML's block
// (- a, one a line). Read here rather than by cv::FileStorage, whose parser crashes or
// loops forever on some damaged files.
std::optional<std::vector<std::string>> image_names(std::string_view text) {
    const std::size_t key = text.find("imagelist");
    if (key == std::string_view::npos) return std::nullopt;
    if (key > 0 && text[key - 1] == '<') {
        const std::size_t open = text.find('>', key);
        const std::size_t close = text.find("</imagelist>", key);
        if (open == std::string_view::npos || close == std::string_view::npos || close < open) return std::nullopt;
        return tokens(text.substr(open + 1, close - open - 1), "<");
    }
    const std::size_t colon = text.find(':', key);
    if (colon == std::string_view::npos) return std::nullopt;
    const std::size_t first = text.find_first_not_of(" \t\r\n", colon + 1);
    if (first == std::string_view::npos) return std::nullopt;
    if (text[first] == '[') {
        const std::size_t close = text.find(']', first);
        if (close == std::string_view::npos) return std::nullopt;
        return tokens(text.substr(first + 1, close - first - 1), "]");
    }
    std::vector<std::string> names;
    std::size_t line_start = text.find('\n', colon);
    while (line_start != std::string_view::npos && line_start + 1 < text.size()) {
        const std::size_t next = text.find('\n', line_start + 1);
        const std::string line = trimmed_line(text.substr(line_start + 1, next == std::string_view::npos ? std::string_view::npos
                                                                                                           : next - line_start - 1));
        line_start = next;
        if (line.empty()) continue;
        if (line[0] != '-') break;
        const std::vector<std::string> item = tokens(std::string_view(line).substr(1), "");
        if (item.size() != 1) return std::nullopt;
        names.push_back(item[0]);
    }
    if (names.empty()) return std::nullopt;
    return names;
}

}  // namespace

PairList parse_pair_list(std::string_view text, const std::filesystem::path& source) {
    const std::string where = source.string();
    if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
        throw FileError(where + ": byte " + std::to_string(nul) + ": a NUL byte, which no image list holds");
    }
    const std::optional<std::vector<std::string>> listed = image_names(text);
    if (!listed) throw FileError(where + ": imagelist: missing, or not a list of image names");
    const std::vector<std::string>& names = *listed;
    if (names.empty()) throw FileError(where + ": imagelist: no images");
    if (names.size() % 2 != 0) {
        throw FileError(where + ": imagelist: " + std::to_string(names.size()) +
                        " names, an odd count: the list holds left and right images in turn");
    }
    const std::filesystem::path folder = source.parent_path();
    PairList out;
    for (std::size_t i = 0; i < names.size(); ++i) {
        const std::filesystem::path name(names[i]);
        (i % 2 == 0 ? out.left : out.right).push_back(name.is_absolute() ? name : folder / name);
    }
    return out;
}

PairList read_pair_list(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw FileError(path.string() + ": cannot be read");
    std::ostringstream text;
    text << in.rdbuf();
    return parse_pair_list(text.str(), path);
}

}  // namespace libcam
