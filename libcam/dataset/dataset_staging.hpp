#pragma once
// A `libcam dataset` run (colmap_dataset.hpp) shows nothing until it is whole. Everything it
// writes (the model, the images, the masks, the stamp) goes first to its staging folder,
// OUT/.libcam-dataset-partial (kStagingName): inside OUT, so on its filesystem, and each
// file is moved into place by one rename. Only when every image is there is the run
// finished: the images and masks moved into OUT, then the model, then the stamp, then the
// staging folder removed.
//
// A run that fails or is stopped before finishing leaves OUT as it was, its work kept in
// the staging folder. A run started again with the same cameras (the stamp in the staging
// folder says) keeps the images found there; with others, it discards them first.
//
// Stopped while finishing: before the first move the staging folder gets the list of the
// images being moved (kFinishingName); from then on OUT has no model (the old one and the
// old stamp are removed first) until every image is in place, and a run started again
// keeps an image listed there found in OUT as one of this run's, and finishes the moves.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace libcam {

inline constexpr const char* kStagingName = ".libcam-dataset-partial";
inline constexpr const char* kFinishingName = ".finishing";
// The file, in the staging folder and then in OUT, that says which cameras and interpolation
// made the images beside it.
inline constexpr const char* kStampName = ".libcam-dataset";

// What one run writes, all paths relative to both the staging folder and OUT.
struct DatasetStaging {
    std::filesystem::path output;  // OUT
    std::filesystem::path folder;  // OUT/.libcam-dataset-partial
    // The model's files in the order they are moved into place (the one naming the images
    // last), and OUT's files removed before the images move (an earlier model of either kind).
    std::vector<std::filesystem::path> model_files, replaced;
    std::vector<std::string> images;  // output images' names, under images/ (none without images)
    bool masks = false;               // each image's mask, masks/<name>.png
    std::string stamp;                // what made the images (colmap_dataset.cpp); empty without images
};

std::filesystem::path staging_folder(const std::filesystem::path& output);
std::filesystem::path mask_name(const std::string& image_name);  // masks/<name>.png

// Where the files of a run are found from earlier runs: read once (no writes).
class EarlierWork {
public:
    explicit EarlierWork(const DatasetStaging& staging);
    // Whether the staging folder holds images of this run's stamp.
    bool staged_matches() const { return staged_matches_; }
    // Whether `relative` ("images/a.png", "masks/a.png.png") of image `name` is in the
    // staging folder (matching), or in OUT from a finished run of the same stamp or an
    // interrupted finish of this run's images.
    bool staged(const std::filesystem::path& relative) const;
    bool finished(const std::filesystem::path& relative, const std::string& name) const;
    bool has(const std::filesystem::path& relative, const std::string& name) const {
        return staged(relative) || finished(relative, name);
    }

private:
    const DatasetStaging& staging_;
    bool staged_matches_ = false, output_matches_ = false;
    std::vector<std::string> finishing_;  // sorted: the names an interrupted finish was moving
};

// Held by a run from its first write until it has finished or stopped: an exclusive lock on
// OUT itself (flock on the folder: no file is added to OUT), so that a run of another
// process on the same OUT is refused at once instead of mixing its files with this one's.
// The lock goes with the process: a run that is killed leaves none behind. Made by
// lock_output.
class OutputLock {
public:
    explicit OutputLock(const std::filesystem::path& output);
    ~OutputLock();
    OutputLock(const OutputLock&) = delete;
    OutputLock& operator=(const OutputLock&) = delete;

private:
    int descriptor_ = -1;
};

// OUT's lock: the one this process already holds for it (plans made again in one process,
// to resume or after a failure, share it), else a new one. Makes OUT when it is not there;
// FileError when another process holds it, or OUT cannot be made or opened.
std::shared_ptr<const OutputLock> lock_output(const std::filesystem::path& output);

// Throws FileError for a staging folder that is a symbolic link (a run's work stays in a
// folder of its own).
void check_staging_folder(const std::filesystem::path& folder);

// Empties the staging folder unless it holds this run's images (its stamp matches), then
// makes it, removes the temporary files of a stopped run and writes the stamp.
void prepare_staging(const DatasetStaging& staging);

// Moves the staged work into place (above). Throws FileError, changing nothing in OUT, when
// an image or mask is in neither place, or the staging folder holds no model; FileError for
// a move that fails (the work kept: the same run again finishes it).
void finish_staging(const DatasetStaging& staging);

}  // namespace libcam
