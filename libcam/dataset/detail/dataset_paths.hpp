#pragma once
// Where `libcam dataset` (colmap_dataset.hpp) reads and writes. An image's name comes from a
// file (COLMAP's NAME, a transforms.json's file_path), and a file can be hostile: every name
// is taken as a plain relative path that stays inside the images folder, and every folder
// the run writes into, followed through its symbolic links, stays inside the output folder.
//
// Followed and not: a source image is read through whatever links the user's own images
// folder holds (that folder is the user's choice); on the output side a link is followed
// only where it leads to another place inside the output folder, and never into the
// folder of a run's unfinished work (dataset_staging.hpp).

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/detail/colmap_format.hpp"

namespace libcam {

// `name` as a plain relative path ("./sub/a.png" is "sub/a.png"), or FileError
// "<where>: <field>: '<name>' <why>" for a name that is empty, holds a control character,
// is absolute, leads out of `folder` through "..", or names a folder ("a/", "."). `folder`
// says in the message what the name is relative to ("the images folder").
std::string plain_image_name(const std::string& name, const std::string& where, const std::string& field,
                             const std::string& folder);

// Throws FileError "<where>: <field>: ..." for two images of one name, or an image whose name
// is a folder of another's ("a" and "a/b.png"): the output keeps one file per name.
void check_distinct_names(const std::vector<ColmapImage>& images, const std::string& field);

// Throws FileError naming the folder unless `relative` (a plain relative folder) under
// `root`, each symbolic link on the way followed, stays inside `root` and outside `avoid`
// (when given: a folder inside root a link must not lead into), and each folder of it that
// exists is a folder on root's filesystem (the run's files are moved into place by renaming).
// Nothing under a root that does not exist yet is checked: the run makes it.
void check_folder_inside(const std::filesystem::path& root, const std::filesystem::path& relative,
                         const std::filesystem::path& avoid = {});

}  // namespace libcam
