#include "libcam/dataset/dataset_staging.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "libcam/error.hpp"
#include "libcam/dataset/detail/dataset_paths.hpp"
#include "libcam/io/atomic_write.hpp"

namespace libcam {

namespace {

namespace fs = std::filesystem;

constexpr const char* kFinishingHeader = "libcam dataset: moving these images into place\n";

// The file's contents when it is a regular file of at most `limit` bytes (a stamp or list
// libcam wrote); nothing otherwise, without reading more than `limit` + 1 bytes of it.
std::optional<std::string> small_file(const fs::path& path, std::size_t limit) {
    try {
        if (!regular_file_exists(path)) return std::nullopt;
        return read_text_file(path, ReadLimit{limit, "libcam dataset's own"});
    } catch (const FileError&) {
        return std::nullopt;  // another file than the one libcam wrote: not a match
    }
}

bool holds(const fs::path& file, const std::string& text) {
    const std::optional<std::string> found = small_file(file, text.size());
    return found && *found == text;
}

std::string finishing_list(const std::vector<std::string>& names) {
    std::string list = kFinishingHeader;
    for (const std::string& name : names) list += name + "\n";
    return list;
}

std::string kept_note(const DatasetStaging& staging) {
    return "the run's work is kept in " + staging.folder.string() + ", and the same run started again finishes it";
}

// Every image file of the run, relative to OUT and to the staging folder.
std::vector<fs::path> image_files(const DatasetStaging& staging) {
    std::vector<fs::path> files;
    for (const std::string& name : staging.images) {
        files.push_back(fs::path("images") / name);
        if (staging.masks) files.push_back(mask_name(name));
    }
    return files;
}

void remove_file(const fs::path& file, const DatasetStaging& staging) {
    std::error_code error;
    fs::remove(file, error);
    if (error) throw FileError(file.string() + ": cannot remove it: " + error.message() + "; " + kept_note(staging));
}

void move_into_place(const fs::path& relative, const DatasetStaging& staging) {
    const fs::path from = staging.folder / relative, to = staging.output / relative;
    std::error_code error;
    fs::create_directories(to.parent_path(), error);
    if (!error) fs::rename(from, to, error);
    if (error) {
        throw FileError(to.string() + ": cannot move it into place from " + from.string() + ": " + error.message() + "; " +
                        kept_note(staging));
    }
}

// Each folder the run's files go to, relative to OUT: the images' and the model's.
std::set<fs::path> destination_folders(const std::vector<fs::path>& files, const DatasetStaging& staging) {
    std::set<fs::path> folders;
    for (const fs::path& file : files) folders.insert(file.parent_path());
    for (const fs::path& file : staging.model_files) folders.insert(file.parent_path());
    return folders;
}

void discard(const fs::path& folder) {
    std::error_code error;
    // The stamp first: a run stopped meanwhile leaves images no stamp vouches for.
    fs::remove(folder / kStampName, error);
    if (!error) fs::remove_all(folder, error);
    if (error) throw FileError(folder.string() + ": cannot remove an earlier run's unfinished work: " + error.message());
}

}  // namespace

fs::path staging_folder(const fs::path& output) { return output / kStagingName; }

fs::path mask_name(const std::string& image_name) { return fs::path("masks") / (image_name + ".png"); }

EarlierWork::EarlierWork(const DatasetStaging& staging) : staging_(staging) {
    if (staging.stamp.empty()) return;
    staged_matches_ = holds(staging.folder / kStampName, staging.stamp);
    output_matches_ = holds(staging.output / kStampName, staging.stamp);
    if (!staged_matches_) return;
    const std::string expected = finishing_list(staging.images);
    const std::optional<std::string> list = small_file(staging.folder / kFinishingName, expected.size());
    if (!list || !list->starts_with(kFinishingHeader)) return;
    std::size_t at = std::string_view(kFinishingHeader).size();
    for (std::size_t end = list->find('\n', at); end != std::string::npos; at = end + 1, end = list->find('\n', at)) {
        finishing_.push_back(list->substr(at, end - at));
    }
    std::sort(finishing_.begin(), finishing_.end());
}

bool EarlierWork::staged(const fs::path& relative) const {
    std::error_code error;
    return staged_matches_ && fs::is_regular_file(staging_.folder / relative, error);
}

bool EarlierWork::finished(const fs::path& relative, const std::string& name) const {
    std::error_code error;
    const bool vouched = output_matches_ || std::binary_search(finishing_.begin(), finishing_.end(), name);
    return vouched && fs::is_regular_file(staging_.output / relative, error);
}

OutputLock::OutputLock(const std::filesystem::path& output) {
    descriptor_ = ::open(output.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (descriptor_ < 0) throw FileError(output.string() + ": cannot open the output folder: " + std::strerror(errno));
    if (::flock(descriptor_, LOCK_EX | LOCK_NB) != 0) {
        const int cause = errno;
        ::close(descriptor_);
        if (cause == EWOULDBLOCK) {
            throw FileError(output.string() + ": another libcam dataset run is writing this folder; wait for it to "
                                              "finish, or give another output folder");
        }
        throw FileError(output.string() + ": cannot lock the output folder: " + std::strerror(cause));
    }
}

OutputLock::~OutputLock() { ::close(descriptor_); }

std::shared_ptr<const OutputLock> lock_output(const std::filesystem::path& output) {
    std::error_code error;
    std::filesystem::create_directories(output, error);
    if (error) throw FileError(output.string() + ": cannot make the output folder: " + error.message());
    // A folder's one name in this process, whichever path led to it.
    const std::string key = std::filesystem::weakly_canonical(output, error).string();
    static std::mutex mutex;
    static std::map<std::string, std::weak_ptr<const OutputLock>> held;
    const std::lock_guard<std::mutex> guard(mutex);
    std::weak_ptr<const OutputLock>& entry = held[error ? output.string() : key];
    if (std::shared_ptr<const OutputLock> lock = entry.lock()) return lock;
    auto lock = std::make_shared<const OutputLock>(output);
    entry = lock;
    return lock;
}

void check_staging_folder(const fs::path& folder) {
    std::error_code error;
    if (fs::is_symlink(fs::symlink_status(folder, error))) {
        throw FileError(folder.string() + ": a symbolic link, where libcam dataset keeps a run's unfinished work: remove it");
    }
}

void prepare_staging(const DatasetStaging& staging) {
    check_staging_folder(staging.folder);
    std::error_code error;
    if (!EarlierWork(staging).staged_matches() && fs::exists(staging.folder, error)) discard(staging.folder);
    fs::create_directories(staging.folder, error);
    if (error) throw FileError(staging.folder.string() + ": cannot make the folder: " + error.message());
    // A run killed midway leaves the temporary file of each file it was writing.
    remove_stopped_writes(staging.folder);
    if (!staging.stamp.empty()) write_file_atomically(staging.folder / kStampName, staging.stamp);
}

void finish_staging(const DatasetStaging& staging) {
    std::error_code error;
    if (!fs::is_directory(fs::symlink_status(staging.folder, error))) {
        throw FileError(staging.folder.string() + ": no unfinished dataset here (finished already, or never planned)");
    }
    for (const fs::path& file : staging.model_files) {
        if (!fs::is_regular_file(staging.folder / file, error)) {
            throw FileError((staging.folder / file).string() + ": missing: the run's model is not there to move; plan again");
        }
    }
    const EarlierWork earlier(staging);
    const std::vector<fs::path> files = image_files(staging);
    std::size_t missing = 0;
    const fs::path* first = nullptr;
    for (std::size_t i = 0; i < files.size(); ++i) {
        if (earlier.has(files[i], staging.images[staging.masks ? i / 2 : i])) continue;
        if (missing++ == 0) first = &files[i];
    }
    if (missing > 0) {
        throw FileError(staging.folder.string() + ": " + std::to_string(missing) + " of the run's " +
                        std::to_string(files.size()) + " image files are not written yet (the first: " +
                        (staging.folder / *first).string() + "): nothing was moved into " + staging.output.string() +
                        "; run the rest of the tasks, or the same run again");
    }
    // Each folder checked as the plan checked it (it may have changed since).
    const std::set<fs::path> folders = destination_folders(files, staging);
    for (const fs::path& folder : folders) check_folder_inside(staging.output, folder, staging.folder);
    if (!staging.images.empty()) {
        write_file_atomically(staging.folder / kFinishingName, finishing_list(staging.images));
        remove_file(staging.output / kStampName, staging);
    }
    for (const fs::path& file : staging.replaced) remove_file(staging.output / file, staging);
    for (const fs::path& file : files) {
        if (earlier.staged(file)) move_into_place(file, staging);
    }
    for (const fs::path& file : staging.model_files) move_into_place(file, staging);
    // The moves flushed before the stamp says the run is finished, and the stamp after: a
    // power cut then leaves either every file or no stamp vouching for them.
    for (const fs::path& folder : folders) sync_folder(staging.output / folder);
    if (!staging.images.empty()) {
        move_into_place(kStampName, staging);
        sync_folder(staging.output);
    }
    fs::remove_all(staging.folder, error);
    if (error) {
        throw FileError(staging.folder.string() + ": the dataset is finished, but this folder of its unfinished work "
                        "cannot be removed: " + error.message());
    }
}

}  // namespace libcam
