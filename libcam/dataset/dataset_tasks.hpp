#pragma once
// The image part of `libcam dataset` (colmap_dataset.hpp) as tasks that can run anywhere:
// each task is one output image, self-contained (both cameras, the view's turn, the
// interpolation, the paths), and travels as one line of JSON to another process or
// machine, where run_image_task makes the same file the local run makes.
//
//   const DatasetPlan plan = plan_dataset(options);       // the model and stamp staged
//   for (const ImageTask& task : plan.tasks) send(image_task_json(task));
//   ...
//   MapCache maps;                                         // one per worker process
//   run_image_task(image_task_from_json(received), maps);
//   ...
//   finish_dataset(plan);                                  // once every task is done
//
// A worker builds each camera's map once and keeps the few it used last (MapCache): tasks
// come in camera order, so a worker given a run of one camera's images builds its map once.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/interop/image_remap.hpp"

namespace libcam {

struct ImageTask {
    Camera source;                 // the source image's camera (its pose is not used)
    Camera camera;                 // the new pinhole
    Mat3 turn = Mat3::Identity();  // the new camera's axes relative to the source's (a view's turn)
    bool copy = false;             // the source camera kept as it was: the file copied byte for byte
    Interpolation interpolation = Interpolation::Cubic;
    int jpeg_quality = kDefaultJpegQuality;
    std::filesystem::path source_path;  // the image read
    std::filesystem::path target_path;  // the image written (to a temporary name, then renamed)
    std::filesystem::path mask_path;    // its mask (dataset --masks); empty: none
};

// One line of JSON holding the whole task, the cameras in libcam's JSON camera layout
// (io/detail/json_format.hpp), every number to the last bit; paths as UTF-8 text.
// Throws InvalidArgument for a path that is not UTF-8.
std::string image_task_json(const ImageTask& task);
// The task back; FileError naming `source` and the field for text that is not one.
ImageTask image_task_from_json(std::string_view text, const std::string& source = "image task");

// The maps of the cameras a process has used last, at most `capacity` of them (each 6
// bytes per output pixel in OpenCV's fixed point: 72 MB for a 12-megapixel image), keyed
// by what makes the map (both cameras, the turn, the interpolation), so tasks of different
// plans with the same cameras share one. Safe to use from several threads: a map is built once however many
// ask for it at the same time; a map still in use when it is dropped stays alive for its
// users.
class MapCache {
public:
    static constexpr std::size_t kDefaultCapacity = 4;
    // `threads`: threads each map is built with (0: one per core).
    explicit MapCache(std::size_t capacity = kDefaultCapacity, int threads = 1);

    // The task's map; nullptr for a task that copies its image.
    std::shared_ptr<const PreparedRemap> map_for(const ImageTask& task);

    std::size_t size() const;    // maps held now
    std::size_t builds() const;  // maps built so far
    std::size_t capacity() const { return capacity_; }
    int threads() const { return threads_; }

private:
    struct Entry {
        std::string key;
        std::mutex build_lock;
        std::shared_ptr<const PreparedRemap> map;
    };
    std::shared_ptr<Entry> entry_for(const std::string& key);

    mutable std::mutex lock_;
    std::list<std::shared_ptr<Entry>> entries_;  // the last used first
    std::size_t capacity_;
    int threads_;
    std::size_t builds_ = 0;
};

// Reads the task's image, remaps it through its camera's map (or copies it), writes it and
// its mask, each to a temporary name renamed into place, creating their folders. Throws
// FileError naming the image for one that cannot be read or written (or is of another
// size than its camera), InvalidArgument when the map cannot be built.
//
// A task line is checked before anything is written: it writes only what a plan's task
// writes, <output>/.libcam-dataset-partial/images/<name> and its mask masks/<name>.png
// there (dataset_staging.hpp), in a staging folder a plan made (holding its stamp), with a
// plain relative name and no symbolic link leading out of that folder; anything else is
// refused (FileError naming target_path or mask_path). Its source may be any image file.
void run_image_task(const ImageTask& task, MapCache& maps);

// Runs the tasks on `threads` workers sharing one MapCache, each worker holding one image
// at a time; returns how many failed, each reported through `report` (one line, one call at
// a time). A map that cannot be built stops every worker and is thrown.
// `progress`, when given, is called after each task with how many are done, one call at
// a time (from the worker that finished it).
std::size_t run_image_tasks(const std::vector<ImageTask>& tasks, int threads,
                            const std::function<void(const std::string&)>& report,
                            const std::function<void(std::size_t done, std::size_t total)>& progress = {});

}  // namespace libcam
