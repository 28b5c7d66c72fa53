#include "libcam/dataset/detail/dataset_sources.hpp"

#include <algorithm>
#include <sstream>

#include "libcam/error.hpp"
#include "libcam/dataset/detail/dataset_paths.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/lens/lens_model.hpp"

namespace libcam {

namespace {

namespace fs = std::filesystem;

constexpr const char* kImagesFolder = "images";

bool same_intrinsics(const Camera& a, const Camera& b) {
    const Intrinsics& p = a.intrinsics;
    const Intrinsics& q = b.intrinsics;
    return a.size == b.size && p.fx == q.fx && p.fy == q.fy && p.cx == q.cx && p.cy == q.cy && p.skew == q.skew &&
           a.lens.type == b.lens.type && a.lens.coefficients == b.lens.coefficients;
}

// A frame's file_path made plain, relative to the json's folder; refused outside it.
fs::path plain_image_path(const std::string& file_path, const std::string& where) {
    return plain_image_name(file_path, where, "\"file_path\"", "the json's folder");
}

// Whether every image is under images/ (then the names are relative to it).
bool all_under_images(const std::vector<fs::path>& paths) {
    return std::all_of(paths.begin(), paths.end(), [](const fs::path& path) {
        auto part = path.begin();
        return part != path.end() && *part == kImagesFolder && std::next(part) != path.end();
    });
}

// The frames of a transforms.json; refused without frames (one camera, not a dataset).
NerfScene read_scene(const fs::path& json) {
    const std::string text = read_text_file(json, {kCameraFileLimit.max_bytes, "NeRF transforms.json"});
    NerfScene scene = read_nerf_scene(text, {json.string(), json.parent_path(), {}});
    if (scene.cameras.size() == 1 && scene.cameras[0].name.empty() && !scene.posed[0]) {
        throw FileError(json.string() + ": \"frames\": missing: a dataset needs frames, each with its image and pose");
    }
    return scene;
}

// Each frame's image, plain; refused for a frame without a pose. (An image two frames
// name is refused with the names of every source: dataset_paths.hpp.)
std::vector<fs::path> image_paths(const NerfScene& scene, const fs::path& json) {
    std::vector<fs::path> paths;
    for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
        const std::string where = json.string() + ": frames[" + std::to_string(i) + "]";
        if (!scene.posed[i]) throw FileError(where + ": \"transform_matrix\": missing: a dataset needs each frame's pose");
        paths.push_back(plain_image_path(scene.cameras[i].name, where));
    }
    return paths;
}

// The points' positions in the frames' world, as nerfstudio's ply holds them.
std::string ply_text(const ColmapPoints3D& points, const NerfWorld& world) {
    std::ostringstream out;
    out.precision(17);
    out << "ply\nformat ascii 1.0\nelement vertex " << points.ids.size()
        << "\nproperty double x\nproperty double y\nproperty double z\n"
           "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
    const Mat3 a = world.transform.leftCols<3>();
    const Vec3 b = world.transform.col(3);
    for (std::size_t i = 0; i < points.ids.size(); ++i) {
        const Vec3 moved = world.scale * (a * points.xyz[i] + b);
        const auto& rgb = points.colours[i];
        out << moved.x() << " " << moved.y() << " " << moved.z() << " " << int(rgb[0]) << " " << int(rgb[1]) << " "
            << int(rgb[2]) << "\n";
    }
    return out.str();
}

}  // namespace

bool is_nerf_dataset_source(const fs::path& source) {
    std::error_code error;
    return source.extension() == ".json" && fs::is_regular_file(source, error);
}

fs::path nerf_dataset_images_folder(const fs::path& json) {
    const NerfScene scene = read_scene(json);
    return all_under_images(image_paths(scene, json)) ? json.parent_path() / kImagesFolder : json.parent_path();
}

DatasetModel read_nerf_dataset(const fs::path& json) {
    const NerfScene scene = read_scene(json);
    const std::vector<fs::path> paths = image_paths(scene, json);
    const bool under_images = all_under_images(paths);
    DatasetModel model;
    model.world = scene.world;
    model.images_folder = under_images ? json.parent_path() / kImagesFolder : json.parent_path();
    for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
        const Camera& camera = scene.cameras[i].file.camera;
        Camera intrinsics = camera;
        intrinsics.pose = Pose{};
        const auto same = std::find_if(model.cameras.begin(), model.cameras.end(), [&](const ColmapCameraRecord& record) {
            return same_intrinsics(record.camera, intrinsics);
        });
        std::uint64_t camera_id = model.cameras.size() + 1;
        if (same == model.cameras.end()) {
            model.cameras.push_back({camera_id, intrinsics, lens_info(camera.lens.type).name});
        } else {
            camera_id = same->id;
        }
        const fs::path name = under_images ? paths[i].lexically_relative(kImagesFolder) : paths[i];
        model.images.push_back({i + 1, camera_id, name.generic_string(), camera.pose, {},
                                json.string() + ": frames[" + std::to_string(i) + "]"});
    }
    return model;
}

std::vector<fs::path> write_nerf_dataset(const fs::path& output, const std::vector<ColmapCameraRecord>& cameras,
                        const std::vector<ColmapImage>& images, const ColmapPoints3D& points, const NerfWorld& world,
                        bool masks) {
    std::vector<NamedCamera> frames;
    std::vector<std::string> mask_paths;
    for (const ColmapImage& image : images) {
        const auto record = std::find_if(cameras.begin(), cameras.end(),
                                         [&](const ColmapCameraRecord& c) { return c.id == image.camera_id; });
        if (record == cameras.end()) {
            throw FileError(image.where + ": CAMERA_ID " + std::to_string(image.camera_id) + " has no camera");
        }
        Camera camera = record->camera;
        camera.pose = image.pose;
        frames.push_back({(fs::path(kImagesFolder) / image.name).generic_string(), {camera, std::nullopt}});
        if (masks) mask_paths.push_back((fs::path("masks") / (image.name + ".png")).generic_string());
    }
    fs::create_directories(output);
    const std::string ply_file_path = points.ids.empty() ? std::string() : kNerfPointsName;
    const std::vector<CameraFileText> files = write_nerf_scene(frames, world, ply_file_path, mask_paths);
    std::vector<fs::path> written;
    if (!ply_file_path.empty()) {
        write_file_atomically(output / ply_file_path, ply_text(points, world));
        written.push_back(ply_file_path);
    }
    // transforms.json (the first) last.
    for (auto file = files.rbegin(); file != files.rend(); ++file) {
        write_file_atomically(output / file->name, file->text);
        written.push_back(file->name);
    }
    return written;
}

}  // namespace libcam
