#include "libcam/calibrate/pair_list.hpp"

#include <fstream>
#include <sstream>
#include <string>

#include <opencv2/core.hpp>

#include "libcam/error.hpp"

namespace libcam {

namespace {

// The first line of an OpenCV error, whose message spans several lines.
std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

}  // namespace

PairList parse_pair_list(std::string_view text, const std::filesystem::path& source) {
    const std::string where = source.string();
    std::vector<std::string> names;
    try {
        cv::FileStorage file(std::string(text), cv::FileStorage::READ | cv::FileStorage::MEMORY);
        const cv::FileNode list = file["imagelist"];
        if (!list.isSeq()) throw FileError(where + ": imagelist: missing, or not a list of image names");
        for (const cv::FileNode& item : list) {
            if (!item.isString()) throw FileError(where + ": imagelist: an entry that is not a file name");
            names.push_back(item.string());
        }
    } catch (const cv::Exception& error) {
        throw FileError(where + ": not an image list OpenCV reads: " + first_line(error.err));
    }
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
