#include "libcam/dataset/dataset_tasks.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>
#include <nlohmann/json.hpp>
#include <opencv2/core/utility.hpp>
#include <thread>

#include "libcam/camera/parallel.hpp"
#include "libcam/error.hpp"
#include "libcam/dataset/detail/dataset_paths.hpp"
#include "libcam/dataset/dataset_staging.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/detail/document.hpp"
#include "libcam/io/detail/json_format.hpp"
#include "libcam/remap/remap_map.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

namespace fs = std::filesystem;

// A camera as the task carries it: what makes its map, without the pose the map ignores.
std::string camera_object(const Camera& camera) {
    Camera bare = camera;
    bare.pose = Pose{};
    return format_json_camera_object(bare);
}

// Each entry to the last bit, -0 as -0.0: JSON readers take "-0" for the integer 0.
std::string turn_array(const Mat3& turn) {
    std::string out = "[";
    for (const double entry : turn.reshaped<Eigen::RowMajor>()) {
        out += (out.size() > 1 ? ", " : "") + (entry == 0.0 && std::signbit(entry) ? "-0.0" : format_number(entry));
    }
    return out + "]";
}

// What makes a task's map, as text: its key in MapCache, and most of the task's JSON.
std::string map_fields(const ImageTask& task) {
    return "\"source\": " + camera_object(task.source) + ", \"camera\": " + camera_object(task.camera) +
           ", \"turn\": " + turn_array(task.turn) + ", \"interpolation\": \"" + std::string(to_string(task.interpolation)) +
           "\"";
}

std::string quoted_path(const fs::path& path, const char* field) {
    try {
        return nlohmann::json(path.string()).dump();
    } catch (const nlohmann::json::exception&) {
        throw InvalidArgument(std::string(field) + ": '" + path.string() + "' is not UTF-8 text, which a task's JSON holds");
    }
}

// 255 where the map gives the target pixel a source pixel, 0 where remap_image leaves it
// black: the fixed-point map's whole pixel is kNoSourceCoordinate there (exactly, and no
// source pixel is that far off the image).
cv::Mat source_mask(const PreparedRemap& map) {
    constexpr short kNoSource = static_cast<short>(kNoSourceCoordinate);
    cv::Mat mask(map.xy.rows, map.xy.cols, CV_8U);
    for (int y = 0; y < mask.rows; ++y) {
        const cv::Vec2s* coordinates = map.xy.ptr<cv::Vec2s>(y);
        std::uint8_t* row = mask.ptr<std::uint8_t>(y);
        for (int x = 0; x < mask.cols; ++x) row[x] = coordinates[x][0] == kNoSource ? 0 : 255;
    }
    return mask;
}

void write_mask(const fs::path& path, const cv::Mat& mask) {
    fs::create_directories(path.parent_path());
    write_image(path, mask);
}

// The staging folder a task's target is in: its path up to the first folder of that name.
fs::path staging_of(const fs::path& target) {
    fs::path folder;
    for (const fs::path& part : target) {
        folder /= part;
        if (part == kStagingName) return folder;
    }
    return {};
}

// A task writes only files of the plan's form (dataset_staging.hpp): its image at
// <staging folder>/images/<plain name>, its mask at masks/<name>.png there, in a staging
// folder a plan made (a folder, not a link, holding the plan's stamp), and through no
// symbolic link leading out of it. So a task line made by hand cannot write anywhere else.
void check_task_paths(const ImageTask& task) {
    const std::string rule = ": a task writes only <output>/" + std::string(kStagingName) +
                             "/images/<name> (and its mask) in a folder a plan made";
    const fs::path staging = staging_of(task.target_path);
    std::error_code error;
    if (staging.empty() || !fs::is_directory(fs::symlink_status(staging, error)) ||
        !fs::is_regular_file(staging / kStampName, error)) {
        throw FileError(task.target_path.string() + ": target_path: not in a staging folder a plan made" + rule);
    }
    const fs::path relative = task.target_path.lexically_relative(staging);
    const std::string name = relative.lexically_relative("images").generic_string();
    if (relative.empty() || *relative.begin() != "images" ||
        plain_image_name(name, task.target_path.string(), "target_path", "the staging folder's images/") != name) {
        throw FileError(task.target_path.string() + ": target_path: not a plain name under images/" + rule);
    }
    check_folder_inside(staging, relative.parent_path());
    if (task.mask_path.empty()) return;
    if (task.mask_path != staging / mask_name(name)) {
        throw FileError(task.mask_path.string() + ": mask_path: not " + (staging / mask_name(name)).string() + rule);
    }
    check_folder_inside(staging, mask_name(name).parent_path());
}

// The task's image (and mask) written through `map`; nullptr: copied.
void write_task_image(const ImageTask& task, const PreparedRemap* map) {
    check_task_paths(task);
    std::error_code error;
    if (!fs::is_regular_file(task.source_path, error)) throw FileError(task.source_path.string() + ": no such image file");
    fs::create_directories(task.target_path.parent_path());
    if (map == nullptr) {
        write_file_atomically(task.target_path, read_text_file(task.source_path));
        if (!task.mask_path.empty()) {
            const cv::Mat image = read_image(task.source_path);
            write_mask(task.mask_path, cv::Mat(image.rows, image.cols, CV_8U, cv::Scalar(255)));
        }
        return;
    }
    const cv::Mat image = read_image(task.source_path);
    cv::Mat result;
    try {
        result = remap_image(image, *map);
    } catch (const InvalidArgument& wrong_size) {
        throw FileError(task.source_path.string() + ": " + wrong_size.what());
    }
    write_image(task.target_path, result, task.jpeg_quality);
    if (!task.mask_path.empty()) write_mask(task.mask_path, source_mask(*map));
}

// OpenCV's own threads off while the workers run: each image is one worker's.
class OpenCvThreads {
public:
    explicit OpenCvThreads(int threads) : before_(cv::getNumThreads()) {
        if (threads > 1) cv::setNumThreads(1);
    }
    ~OpenCvThreads() { cv::setNumThreads(before_); }
    OpenCvThreads(const OpenCvThreads&) = delete;
    OpenCvThreads& operator=(const OpenCvThreads&) = delete;

private:
    int before_;
};

fs::path path_field(const Field& task, const char* key) {
    const std::optional<Field> value = task.find({key});
    return value ? fs::path(value->text()) : fs::path();
}

}  // namespace

std::string image_task_json(const ImageTask& task) {
    return "{" + map_fields(task) + ", \"copy\": " + (task.copy ? "true" : "false") +
           ", \"jpeg_quality\": " + std::to_string(task.jpeg_quality) +
           ", \"source_path\": " + quoted_path(task.source_path, "source_path") +
           ", \"target_path\": " + quoted_path(task.target_path, "target_path") +
           (task.mask_path.empty() ? "" : ", \"mask_path\": " + quoted_path(task.mask_path, "mask_path")) + "}";
}

ImageTask image_task_from_json(std::string_view text, const std::string& source) {
    const DocumentNode root = parse_json_tree(text, source);
    const Field in(root, "", source);
    if (root.kind != DocumentNode::Kind::Map) in.fail("expected an image task (a JSON object), got " + in.shown());
    ImageTask task;
    task.source = read_json_camera_object(in.at({"source"}));
    task.camera = read_json_camera_object(in.at({"camera"}));
    const Field turn = in.at({"turn"});
    const std::vector<double> entries = turn.numbers(9);
    if (entries.size() != 9) turn.fail("expected 9 numbers (a 3x3 rotation, row by row), got " + std::to_string(entries.size()));
    task.turn = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(entries.data());
    const Field interpolation = in.at({"interpolation"});
    try {
        task.interpolation = interpolation_from_string(interpolation.text());
    } catch (const InvalidArgument& error) {
        interpolation.fail(error.what());
    }
    const Field copy = in.at({"copy"});
    const std::optional<bool> copied = copy.boolean();
    if (!copied) copy.fail("expected true or false, got " + copy.shown());
    task.copy = *copied;
    task.jpeg_quality = static_cast<int>(in.at({"jpeg_quality"}).integer(1, 100));
    task.source_path = path_field(in, "source_path");
    task.target_path = path_field(in, "target_path");
    task.mask_path = path_field(in, "mask_path");
    if (task.source_path.empty()) in.fail_at("source_path", "missing");
    if (task.target_path.empty()) in.fail_at("target_path", "missing");
    return task;
}

MapCache::MapCache(std::size_t capacity, int threads) : capacity_(std::max<std::size_t>(capacity, 1)), threads_(worker_count(threads)) {}

std::shared_ptr<MapCache::Entry> MapCache::entry_for(const std::string& key) {
    const std::lock_guard<std::mutex> lock(lock_);
    const auto found = std::find_if(entries_.begin(), entries_.end(), [&](const auto& entry) { return entry->key == key; });
    if (found != entries_.end()) {
        entries_.splice(entries_.begin(), entries_, found);
        return entries_.front();
    }
    auto entry = std::make_shared<Entry>();
    entry->key = key;
    entries_.push_front(entry);
    if (entries_.size() > capacity_) entries_.pop_back();
    return entry;
}

std::shared_ptr<const PreparedRemap> MapCache::map_for(const ImageTask& task) {
    if (task.copy) return nullptr;
    const std::shared_ptr<Entry> entry = entry_for(map_fields(task));
    // Others asking for the same map wait here for the one building it.
    const std::lock_guard<std::mutex> build(entry->build_lock);
    if (!entry->map) {
        RemapOptions options;
        options.threads = threads_;
        options.rotation = task.turn;
        entry->map = std::make_shared<const PreparedRemap>(
            prepare_remap(build_remap_map(PreparedCamera(task.camera), PreparedCamera(task.source), options), task.interpolation));
        const std::lock_guard<std::mutex> lock(lock_);
        ++builds_;
    }
    return entry->map;
}

std::size_t MapCache::size() const {
    const std::lock_guard<std::mutex> lock(lock_);
    return entries_.size();
}

std::size_t MapCache::builds() const {
    const std::lock_guard<std::mutex> lock(lock_);
    return builds_;
}

void run_image_task(const ImageTask& task, MapCache& maps) {
    const std::shared_ptr<const PreparedRemap> map = maps.map_for(task);
    write_task_image(task, map.get());
}

std::size_t run_image_tasks(const std::vector<ImageTask>& tasks, int threads,
                            const std::function<void(const std::string&)>& report,
                            const std::function<void(std::size_t done, std::size_t total)>& progress) {
    const std::size_t workers =
        std::clamp<std::size_t>(static_cast<std::size_t>(worker_count(threads)), 1, std::max<std::size_t>(tasks.size(), 1));
    const OpenCvThreads opencv_threads(static_cast<int>(workers));
    // Tasks come in camera order, so the workers share at most one camera each at a time;
    // each map is built with a share of the threads (the other workers are busy with images).
    MapCache maps(workers, std::max(1, static_cast<int>(workers) / 2));
    std::atomic<std::size_t> next{0}, failed{0}, done{0};
    std::mutex report_lock;
    std::exception_ptr fatal;  // a map that cannot be built stops every worker
    const auto work = [&] {
        for (std::size_t i = next++; i < tasks.size(); i = next++) {
            std::shared_ptr<const PreparedRemap> map;
            try {
                map = maps.map_for(tasks[i]);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(report_lock);
                if (!fatal) fatal = std::current_exception();
                next = tasks.size();
                return;
            }
            try {
                write_task_image(tasks[i], map.get());
            } catch (const std::exception& error) {
                ++failed;
                const std::lock_guard<std::mutex> lock(report_lock);
                if (report) report(error.what());
            }
            const std::size_t finished = ++done;
            if (progress) {
                const std::lock_guard<std::mutex> lock(report_lock);
                progress(finished, tasks.size());
            }
        }
    };
    std::vector<std::thread> pool;
    for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work);
    work();
    for (std::thread& thread : pool) thread.join();
    if (fatal) std::rethrow_exception(fatal);
    return failed;
}

}  // namespace libcam
