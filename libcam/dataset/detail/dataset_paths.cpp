#include "libcam/dataset/detail/dataset_paths.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <unordered_map>

#include "libcam/error.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

namespace fs = std::filesystem;

std::string hex_byte(unsigned char byte) {
    char text[5];
    std::snprintf(text, sizeof text, "\\x%02x", byte);
    return text;
}

bool is_control(unsigned char byte) { return byte < 0x20 || byte == 0x7f; }

// Whether `path` is `root` or inside it (both canonical: component by component).
bool is_within(const fs::path& path, const fs::path& root) {
    auto part = path.begin();
    for (const fs::path& root_part : root) {
        if (part == path.end() || *part != root_part) return false;
        ++part;
    }
    return true;
}

bool same_filesystem(const fs::path& a, const fs::path& b) {
    struct stat first {}, second {};
    return ::stat(a.c_str(), &first) != 0 || ::stat(b.c_str(), &second) != 0 || first.st_dev == second.st_dev;
}

}  // namespace


std::string plain_image_name(const std::string& name, const std::string& where, const std::string& field,
                             const std::string& folder) {
    const std::string prefix = where + ": " + field + ": ";
    if (name.empty()) throw FileError(prefix + "missing or empty");
    const std::string shown = shown_value(name);
    for (const char c : name) {
        if (is_control(static_cast<unsigned char>(c))) {
            throw FileError(prefix + shown + " holds a control character (" + hex_byte(static_cast<unsigned char>(c)) +
                            "): not a file name libcam dataset writes");
        }
    }
    const std::string rule = "; libcam dataset reads and writes each image under its name, relative to " + folder;
    const fs::path path(name);
    if (path.has_root_name() || path.has_root_directory()) throw FileError(prefix + shown + " is an absolute path" + rule);
    const fs::path plain = path.lexically_normal();
    if (!plain.empty() && *plain.begin() == "..") {
        throw FileError(prefix + shown + " leads out of " + folder + " through '..'" + rule);
    }
    if (plain.empty() || plain == "." || !plain.has_filename()) {
        throw FileError(prefix + shown + " names a folder, not an image file");
    }
    return plain.generic_string();
}

void check_distinct_names(const std::vector<ColmapImage>& images, const std::string& field) {
    std::unordered_map<std::string, std::size_t> files, folders;  // each name and folder, by the image giving it
    for (std::size_t i = 0; i < images.size(); ++i) {
        const std::string& name = images[i].name;
        const std::string prefix = images[i].where + ": " + field + ": " + shown_value(name);
        if (const auto found = files.find(name); found != files.end()) {
            throw FileError(prefix + " is also the name of " + images[found->second].where +
                            "; the output keeps one image per name");
        }
        if (const auto found = folders.find(name); found != folders.end()) {
            throw FileError(prefix + " is a folder of " + images[found->second].where + "'s name " +
                            shown_value(images[found->second].name) + "; an image cannot be a folder too");
        }
        files.emplace(name, i);
        for (fs::path folder = fs::path(name).parent_path(); !folder.empty(); folder = folder.parent_path()) {
            if (const auto found = files.find(folder.generic_string()); found != files.end()) {
                throw FileError(prefix + " makes a folder of " + images[found->second].where + "'s name " +
                                shown_value(images[found->second].name) + "; an image cannot be a folder too");
            }
            folders.emplace(folder.generic_string(), i);
        }
    }
}

void check_folder_inside(const fs::path& root, const fs::path& relative, const fs::path& avoid) {
    std::error_code error;
    if (!fs::exists(root, error)) return;
    const fs::path top = fs::canonical(root, error);
    if (error) throw FileError(root.string() + ": cannot resolve it: " + error.message());
    const fs::path avoided = avoid.empty() ? fs::path() : fs::weakly_canonical(avoid, error);
    const std::string rule = ": libcam dataset writes only inside its output folder " + root.string();
    fs::path at = top, shown = root;
    for (const fs::path& part : relative) {
        shown /= part;
        const fs::path next = at / part;
        const fs::file_status status = fs::symlink_status(next, error);
        if (status.type() == fs::file_type::not_found) return;  // made by the run: a plain folder
        at = next;
        if (fs::is_symlink(status)) {
            at = fs::canonical(next, error);
            if (error) throw FileError(shown.string() + ": a symbolic link to nothing" + rule);
            if (!is_within(at, top)) {
                throw FileError(shown.string() + ": a symbolic link leading out of the output folder (to " + at.string() + ")" + rule);
            }
        }
        if (!avoided.empty() && is_within(at, avoided)) {
            throw FileError(shown.string() + ": leads into " + avoid.string() + ", the folder of a run's unfinished work");
        }
        if (!fs::is_directory(at, error)) throw FileError(shown.string() + ": not a folder, where the output needs one");
        if (!same_filesystem(at, top)) {
            throw FileError(shown.string() + ": on another filesystem than " + root.string() +
                            ": a run's files are moved into place by renaming, within one filesystem");
        }
    }
}

}  // namespace libcam
