#include "libcam/io/detail/colmap_model.hpp"

#include <algorithm>
#include <limits>
#include <random>
#include <string>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/detail/format_row.hpp"

namespace libcam {

ColmapIdIndex::ColmapIdIndex(const std::vector<std::uint64_t>& ids) {
    std::uint64_t largest = 0;
    for (const std::uint64_t id : ids) largest = std::max(largest, id);
    if (largest < 4 * static_cast<std::uint64_t>(ids.size()) + 1024) {
        table_.assign(static_cast<std::size_t>(largest) + 1, -1);
        for (std::size_t i = 0; i < ids.size(); ++i) {
            int& slot = table_[static_cast<std::size_t>(ids[i])];
            if (slot != -1 && !duplicate_) duplicate_ = ids[i];
            slot = static_cast<int>(i);
        }
        return;
    }
    sorted_.reserve(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) sorted_.emplace_back(ids[i], static_cast<int>(i));
    std::sort(sorted_.begin(), sorted_.end());
    for (std::size_t i = 1; i < sorted_.size(); ++i) {
        if (sorted_[i].first == sorted_[i - 1].first && !duplicate_) duplicate_ = sorted_[i].first;
    }
}

int ColmapIdIndex::find_sorted(std::uint64_t id) const {
    const auto at = std::lower_bound(sorted_.begin(), sorted_.end(), std::pair<std::uint64_t, int>(id, -1));
    return at != sorted_.end() && at->first == id ? at->second : -1;
}

namespace {

namespace fs = std::filesystem;

std::string name_of(const fs::path& file) { return file.filename().string(); }

// COLMAP counts positions in a 32-bit int; a model past it is not one COLMAP wrote.
void check_count(std::size_t count, const fs::path& file, const char* what) {
    if (count > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
        throw FileError(file.string() + ": " + std::to_string(count) + " " + what + ", more than libcam indexes");
    }
}

ColmapIdIndex unique_ids(const std::vector<std::uint64_t>& ids, const fs::path& file, const char* field) {
    check_count(ids.size(), file, "records");
    ColmapIdIndex index(ids);
    if (const auto id = index.duplicate()) {
        throw FileError(file.string() + ": " + field + " " + std::to_string(*id) + " appears more than once");
    }
    return index;
}

template <class Records, class IdOf>
std::vector<std::uint64_t> ids_of(const Records& records, IdOf&& id_of) {
    std::vector<std::uint64_t> ids;
    ids.reserve(records.size());
    for (const auto& record : records) ids.push_back(id_of(record));
    return ids;
}

std::string image_where(const ColmapImage& image) { return image.where + " (" + image.name + ")"; }

// COLMAP refuses an image whose camera is not in the cameras file (Reconstruction::AddImage).
void check_image_cameras(const ColmapModelRecords& model, const ColmapModelPaths& paths) {
    for (const ColmapImage& image : model.images) {
        if (model.camera_index.find(image.camera_id) < 0) {
            throw FileError(image_where(image) + ": CAMERA_ID " + std::to_string(image.camera_id) + " is not in " +
                            name_of(paths.cameras));
        }
    }
}

// COLMAP loads a POINT3D_ID that points3D lacks without a word, but has no point to
// project or to keep; refused here.
void check_points2d_name_points(const ColmapModelRecords& model, const ColmapModelPaths& paths) {
    std::size_t observations = 0;
    for (const ColmapImage& image : model.images) {
        for (std::size_t k = 0; k < image.points.size(); ++k) {
            const std::uint64_t id = image.points[k].point3d_id;
            if (id == kColmapNoPoint3D) continue;
            ++observations;
            if (model.point_index.find(id) < 0) {
                throw FileError(image_where(image) + ": POINTS2D[" + std::to_string(k) + "]: POINT3D_ID " +
                                std::to_string(id) + " is not in " + name_of(paths.points3d));
            }
        }
    }
    check_count(observations, paths.images, "observations");
}

// ---- the tracks against the POINTS2D -------------------------------------------------------
//
// Checked in two steps. First, in file order: the sum of a hash of every (POINT3D_ID,
// IMAGE_ID, POINT2D_IDX) the tracks name against the same sum over every POINTS2D that
// names a point. Equal sums (with equal counts) say that the two are the same set: every
// track element names a 2-D point of its point, once, and every such 2-D point is in its
// point's track. The hash is keyed afresh in each run, so that no file can be made to
// collide. Else the exact check (check_tracks and check_points2d_in_tracks) goes through
// the tracks and names the first element that is wrong, or links a 2-D point of no point
// (the only difference a valid model can have). The exact check reads each track
// element's 2-D point where it lies, a cache miss each: 0.4 s for 4 million observations,
// which the sums take in a tenth of the time.

// SplitMix64's finaliser: every bit of the result depends on every bit of x.
std::uint64_t mix(std::uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

class TripleSum {
public:
    explicit TripleSum(std::uint64_t key) : key_(key) {}
    void add(std::uint64_t point, std::uint64_t image, std::uint64_t index) {
        sum_ += mix(mix(mix(point ^ key_) ^ image) ^ index);
        ++count_;
    }
    bool operator==(const TripleSum& other) const { return sum_ == other.sum_ && count_ == other.count_; }

private:
    std::uint64_t key_;
    std::uint64_t sum_ = 0;
    std::uint64_t count_ = 0;
};

std::uint64_t run_key() {
    static const std::uint64_t key = [] {
        std::random_device device;
        return (std::uint64_t{device()} << 32) ^ device();
    }();
    return key;
}

// Whether the tracks and the POINTS2D that name points hold the same triples (above).
bool tracks_match_points2d(const ColmapModelRecords& model) {
    TripleSum from_tracks(run_key()), from_points2d(run_key());
    const ColmapPoints3D& points = model.points;
    for (std::size_t p = 0; p < points.ids.size(); ++p) {
        for (std::size_t k = points.track_begin[p]; k < points.track_begin[p + 1]; ++k) {
            from_tracks.add(points.ids[p], points.track[k].image_id, points.track[k].point2d_index);
        }
    }
    for (const ColmapImage& image : model.images) {
        for (std::size_t k = 0; k < image.points.size(); ++k) {
            const std::uint64_t id = image.points[k].point3d_id;
            if (id != kColmapNoPoint3D) from_points2d.add(id, image.id, k);
        }
    }
    return from_tracks == from_points2d;
}

// Each image's first place in one list of every image's POINTS2D.
std::vector<std::size_t> first_points2d(const std::vector<ColmapImage>& images) {
    std::vector<std::size_t> first(images.size() + 1, 0);
    for (std::size_t i = 0; i < images.size(); ++i) first[i + 1] = first[i] + images[i].points.size();
    return first;
}

// Every track element against the 2-D point it names; a 2-D point of no point is linked to
// this one, as COLMAP links it. `claimed` marks the 2-D points a track named.
void check_tracks(ColmapModelRecords& model, const ColmapModelPaths& paths, const std::vector<std::size_t>& first,
                  std::vector<bool>& claimed) {
    const ColmapPoints3D& points = model.points;
    for (std::size_t p = 0; p < points.ids.size(); ++p) {
        const std::uint64_t id = points.ids[p];
        for (std::size_t k = points.track_begin[p]; k < points.track_begin[p + 1]; ++k) {
            // Named variables, not a structured binding: the lambdas below use them, which
            // C++20 allows of a binding only from clang 16 on.
            const std::uint32_t image_id = points.track[k].image_id;
            const std::uint32_t index = points.track[k].point2d_index;
            const auto where = [&] {
                return paths.points3d.string() + ": POINT3D_ID " + std::to_string(id) + ": TRACK[" +
                       std::to_string(k - points.track_begin[p]) + "]: ";
            };
            const int position = model.image_index.find(image_id);
            if (position < 0) {
                throw FileError(where() + "IMAGE_ID " + std::to_string(image_id) + " is not in " + name_of(paths.images));
            }
            ColmapImage& image = model.images[static_cast<std::size_t>(position)];
            const auto seen = [&] { return "image " + std::to_string(image_id) + " (" + image.name + ")"; };
            if (index >= image.points.size()) {
                throw FileError(where() + "POINT2D_IDX " + std::to_string(index) + " is not one of " + seen() + "'s " +
                                std::to_string(image.points.size()) + " POINTS2D");
            }
            std::uint64_t& named = image.points[index].point3d_id;
            const std::size_t place = first[static_cast<std::size_t>(position)] + index;
            if (named != id && named != kColmapNoPoint3D) {
                throw FileError(where() + seen() + "'s POINTS2D[" + std::to_string(index) + "] is POINT3D_ID " +
                                std::to_string(named) + "'s");
            }
            if (claimed[place]) {
                throw FileError(where() + seen() + "'s POINTS2D[" + std::to_string(index) + "] is in the track twice");
            }
            named = id;
            claimed[place] = true;
        }
    }
}

// The other way: a 2-D point that names a point is in that point's track.
void check_points2d_in_tracks(const ColmapModelRecords& model, const ColmapModelPaths& paths,
                              const std::vector<std::size_t>& first, const std::vector<bool>& claimed) {
    for (std::size_t i = 0; i < model.images.size(); ++i) {
        const ColmapImage& image = model.images[i];
        for (std::size_t k = 0; k < image.points.size(); ++k) {
            if (image.points[k].point3d_id == kColmapNoPoint3D || claimed[first[i] + k]) continue;
            throw FileError(image_where(image) + ": POINTS2D[" + std::to_string(k) + "]: POINT3D_ID " +
                            std::to_string(image.points[k].point3d_id) + "'s track in " + name_of(paths.points3d) +
                            " does not name it");
        }
    }
}

void check_model(ColmapModelRecords& model, const ColmapModelPaths& paths) {
    model.camera_index = unique_ids(ids_of(model.cameras, [](const ColmapCameraRecord& c) { return c.id; }),
                                    paths.cameras, "CAMERA_ID");
    model.image_index =
        unique_ids(ids_of(model.images, [](const ColmapImage& i) { return i.id; }), paths.images, "IMAGE_ID");
    model.point_index = unique_ids(model.points.ids, paths.points3d, "POINT3D_ID");
    check_image_cameras(model, paths);
    if (paths.points3d.empty()) return;
    check_points2d_name_points(model, paths);
    if (tracks_match_points2d(model)) return;
    const std::vector<std::size_t> first = first_points2d(model.images);
    std::vector<bool> claimed(first.back(), false);
    check_tracks(model, paths, first, claimed);
    check_points2d_in_tracks(model, paths, first, claimed);
}

fs::path regular_file_or_empty(const fs::path& path) { return regular_file_exists(path) ? path : fs::path(); }

}  // namespace

ColmapModelPaths colmap_model_beside(const fs::path& cameras, std::string_view cameras_bytes) {
    ColmapModelPaths paths;
    paths.cameras = cameras;
    paths.binary = cameras_bytes.find('\0') != std::string_view::npos;
    const std::string extension = paths.binary ? ".bin" : ".txt";
    const fs::path folder = cameras.parent_path().empty() ? fs::path(".") : cameras.parent_path();
    paths.images = regular_file_or_empty(folder / ("images" + extension));
    if (!paths.images.empty()) paths.points3d = regular_file_or_empty(folder / ("points3D" + extension));
    return paths;
}

ColmapModelRecords read_colmap_model_records(const ColmapModelPaths& paths, std::string_view cameras_bytes) {
    ColmapModelRecords model;
    model.cameras = read_colmap_cameras(cameras_bytes, paths.cameras.string(), paths.binary);
    const bool with_points = !paths.points3d.empty();
    if (!paths.images.empty()) {
        model.images = read_colmap_images(read_text_file(paths.images, kColmapModelPartLimit), paths.images.string(), paths.binary, with_points);
    }
    if (with_points) model.points = read_colmap_points3d(read_text_file(paths.points3d, kColmapModelPartLimit), paths.points3d.string(), paths.binary);
    check_model(model, paths);
    return model;
}

ColmapModelRecords read_whole_colmap_model(const fs::path& cameras, std::string_view cameras_bytes) {
    const ColmapModelPaths paths = colmap_model_beside(cameras, cameras_bytes);
    const std::string extension = paths.binary ? ".bin" : ".txt";
    for (const auto& [path, name] : {std::pair{&paths.images, "images"}, std::pair{&paths.points3d, "points3D"}}) {
        if (path->empty()) {
            const fs::path folder = cameras.parent_path().empty() ? fs::path(".") : cameras.parent_path();
            throw FileError(folder.string() + ": a COLMAP model is cameras" + extension + ", images" + extension +
                            " and points3D" + extension + "; " + name + extension + " is missing");
        }
    }
    return read_colmap_model_records(paths, cameras_bytes);
}

ColmapModelRecords read_whole_colmap_model(const fs::path& folder_or_file) {
    const detail::LocatedFile located = detail::locate_camera_file(folder_or_file, CameraFormat::Colmap);
    try {
        return read_whole_colmap_model(located.file, located.text);
    } catch (...) {
        detail::rethrow_read_as(located);  // in one printable line, as every reader's message
    }
}

namespace {

std::string id_name(std::uint64_t id) { return "id:" + std::to_string(id); }

// Every image as a camera, named by its name, and every camera no image takes named by
// its id (colmap_model.hpp has checked the ids).
std::vector<NamedCamera> camera_set(const ColmapModelRecords& model, const std::string& source) {
    std::vector<NamedCamera> set;
    std::vector<bool> used(model.cameras.size(), false);
    for (const ColmapImage& image : model.images) {
        const auto position = static_cast<std::size_t>(model.camera_index.find(image.camera_id));
        Camera camera = model.cameras[position].camera;
        camera.pose = image.pose;
        set.push_back({image.name, {std::move(camera), std::nullopt}, id_name(image.camera_id)});
        used[position] = true;
    }
    for (std::size_t c = 0; c < model.cameras.size(); ++c) {
        if (!used[c]) set.push_back({id_name(model.cameras[c].id), {model.cameras[c].camera, std::nullopt}});
    }
    if (set.empty()) throw FileError(source + ": no camera");
    return set;
}

}  // namespace

// The format row's reader (`libcam info`): here, above the record parsers it checks, so the
// parsers never depend on the model.
std::vector<NamedCamera> read_colmap_model(std::string_view text, const ReadContext& context) {
    // Without a folder (text given alone) the cameras are the whole model.
    ColmapModelPaths paths = colmap_model_beside(context.source, text);
    if (context.folder.empty()) paths.images = paths.points3d = std::filesystem::path();
    return camera_set(read_colmap_model_records(paths, text), context.source);
}

}  // namespace libcam
