#include "libcam/io/detail/nvm_bundler_formats.hpp"

#include <Eigen/Geometry>

#include <cstdint>
#include <optional>
#include <sstream>
#include <string>

#include "libcam/error.hpp"
#include "libcam/geometry/image_size.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/detail/format_row.hpp"
#include "libcam/io/detail/word_reader.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

using detail::WordReader;

ImageSize given_size(const std::optional<ImageSize>& size, const std::string& source, std::string_view format) {
    if (!size) {
        throw FileError(source + ": " + std::string(format) +
                        " stores no image size: give it (--image-size WIDTHxHEIGHT; every image of the file has it)");
    }
    return *size;
}

// A pinhole at the image's centre (the header says which centre).
Camera centred_camera(const ImageSize& size, double focal, const WordReader& words) {
    Camera camera;
    camera.size = size;
    camera.intrinsics = {focal, focal, 0.5 * static_cast<double>(size.width - 1),
                         0.5 * static_cast<double>(size.height - 1), 0.0};
    if (!(focal > 0.0)) words.fail("focal length: must be positive, got " + format_number(focal));
    return camera;
}

// ---- VisualSfM's .nvm ------------------------------------------------------------------

struct NvmFile {
    ObservationSet set;
    std::vector<double> distortion;  // each camera's r
};

NvmFile parse_nvm(std::string_view text, const std::string& source, const ImageSize& size) {
    WordReader words(text, source);
    const std::string_view magic = words.word("the header");
    if (magic != "NVM_V3") words.fail("expected the header NVM_V3, got " + shown_value(magic));
    NvmFile out;
    out.set.tool = ObservationTool::VisualSfm;
    out.set.source = source;
    if (words.peek() == "FixedK") words.fail("NVM_V3 FixedK (a calibration shared by every camera) is not read");
    // Each camera takes at least 22 bytes ("a 1 1 0 0 0 0 0 0 0 0").
    const std::size_t cameras = words.count("camera count", 22);
    for (std::size_t i = 0; i < cameras; ++i) {
        const std::string where = "camera " + std::to_string(i);
        const std::string name(words.word(where + " file name"));
        const double focal = words.number(where + " focal length");
        double q[4];
        for (double& value : q) value = words.number(where + " quaternion");
        double centre[3];
        for (double& value : centre) value = words.number(where + " centre");
        const double r = words.number(where + " radial distortion");
        words.integer(where + " (the 0 that ends a camera)", 0, 0);
        const Eigen::Quaterniond rotation(q[0], q[1], q[2], q[3]);
        if (!(rotation.norm() > 0.5 && rotation.norm() < 2.0)) {
            words.fail(where + " quaternion: expected a unit quaternion, got norm " + format_number(rotation.norm()));
        }
        const Mat3 R = rotation.normalized().toRotationMatrix();
        out.set.cameras.push_back({name, centred_camera(size, focal, words)});
        out.set.views.push_back({name, static_cast<int>(i), Pose::from_centre(R, Vec3(centre[0], centre[1], centre[2]))});
        out.distortion.push_back(r);
    }
    if (words.at_end()) return out;  // cameras alone
    // Each point takes at least 14 bytes ("0 0 0 0 0 0 0\n"), each measurement 8.
    const std::size_t points = words.count("point count", 14);
    for (std::size_t i = 0; i < points; ++i) {
        const std::string where = "point " + std::to_string(i);
        Vec3 X;
        for (int k = 0; k < 3; ++k) X(k) = words.number(where + " position");
        for (int k = 0; k < 3; ++k) words.number(where + " colour");
        const int point = static_cast<int>(out.set.points.size());
        out.set.points.push_back(X);
        out.set.point_ids.push_back(static_cast<std::int64_t>(i));
        const std::size_t measurements = words.count(where + " measurement count", 8);
        for (std::size_t j = 0; j < measurements; ++j) {
            const auto image = words.integer(where + " image index", 0, static_cast<long long>(cameras) - 1);
            words.integer(where + " feature index", -1, 1LL << 40);
            const double x = words.number(where + " x");
            const Vec2 m(x, words.number(where + " y"));
            const ObservedCamera& camera = out.set.cameras[static_cast<std::size_t>(image)];
            const double f = camera.camera.intrinsics.fx;
            // VisualSfM's measurement distortion, undone: (1 + r |m / f|^2) m.
            const Vec2 ideal = (1.0 + out.distortion[static_cast<std::size_t>(image)] * m.squaredNorm() / (f * f)) * m;
            const Vec2 centre(camera.camera.intrinsics.cx, camera.camera.intrinsics.cy);
            out.set.observations.push_back({static_cast<int>(image), point, ideal + centre});
        }
    }
    return out;
}

// ---- Bundler's bundle.out --------------------------------------------------------------

// The names of list.txt beside the file, where it is there.
std::vector<std::string> list_names(const std::filesystem::path& folder) {
    std::vector<std::string> names;
    if (folder.empty() || !regular_file_exists(folder / "list.txt")) return names;
    std::istringstream list(read_text_file(folder / "list.txt", kCameraFileLimit));
    std::string line;
    while (std::getline(list, line)) {
        std::istringstream words(line);
        std::string name;
        if (words >> name) names.push_back(name);
    }
    return names;
}

ObservationSet parse_bundler(std::string_view text, const std::string& source, const ImageSize& size,
                             const std::filesystem::path& folder) {
    WordReader words(text, source);
    words.skip_comment_lines();
    // Each camera takes at least 30 bytes (15 numbers), each point 14.
    const std::size_t cameras = words.count("camera count", 30);
    const std::size_t points = words.count("point count", 14);
    const std::vector<std::string> names = list_names(folder);
    ObservationSet set;
    set.tool = ObservationTool::Bundler;
    set.source = source;
    std::vector<int> view_of(cameras, -1);  // Bundler's camera index -> index into set.views
    const Mat3 flip = Vec3(1, -1, -1).asDiagonal();
    for (std::size_t i = 0; i < cameras; ++i) {
        const std::string where = "camera " + std::to_string(i);
        const double f = words.number(where + " f");
        const double k1 = words.number(where + " k1");
        const double k2 = words.number(where + " k2");
        Mat3 R;
        for (int row = 0; row < 3; ++row) {
            for (int column = 0; column < 3; ++column) R(row, column) = words.number(where + " R");
        }
        Vec3 t;
        for (int k = 0; k < 3; ++k) t(k) = words.number(where + " t");
        if (f == 0.0) continue;  // not registered: Bundler writes zeros
        Camera camera = centred_camera(size, f, words);
        camera.lens = simplest_equal_lens({LensType::OpenCv4, {k1, k2, 0.0, 0.0}});
        Pose pose{nearest_rotation_if_rounded(flip * R), flip * t};
        try {
            pose.validate("R");
        } catch (const InvalidArgument& error) {
            words.fail(where + ": " + error.what());
        }
        const std::string name = i < names.size() ? names[i] : "camera " + std::to_string(i);
        view_of[i] = static_cast<int>(set.views.size());
        set.views.push_back({name, static_cast<int>(set.cameras.size()), pose});
        set.cameras.push_back({name, camera});
    }
    for (std::size_t i = 0; i < points; ++i) {
        const std::string where = "point " + std::to_string(i);
        Vec3 X;
        for (int k = 0; k < 3; ++k) X(k) = words.number(where + " position");
        for (int k = 0; k < 3; ++k) words.number(where + " colour");
        const int point = static_cast<int>(set.points.size());
        set.points.push_back(X);
        set.point_ids.push_back(static_cast<std::int64_t>(i));
        const std::size_t views = words.count(where + " view count", 8);
        for (std::size_t j = 0; j < views; ++j) {
            const auto camera = words.integer(where + " camera", 0, static_cast<long long>(cameras) - 1);
            words.integer(where + " key", -1, 1LL << 40);
            const double x = words.number(where + " x");
            const double y = words.number(where + " y");
            const int view = view_of[static_cast<std::size_t>(camera)];
            if (view < 0) words.fail(where + ": camera " + std::to_string(camera) + " is not registered (its f is 0)");
            const Intrinsics& K = set.cameras[static_cast<std::size_t>(set.views[static_cast<std::size_t>(view)].camera)].camera.intrinsics;
            set.observations.push_back({view, point, Vec2(K.cx + x, K.cy - y)});
        }
    }
    return set;
}

ObservationSet with_observations(ObservationSet set, std::string_view format) {
    if (set.observations.empty()) throw FileError(set.source + ": " + std::string(format) + " holds no observation");
    return set;
}

}  // namespace

std::vector<NamedCamera> read_nvm(std::string_view text, const ReadContext& context) {
    const NvmFile file = parse_nvm(text, context.source, given_size(context.options.size, context.source, "an NVM file"));
    for (std::size_t i = 0; i < file.distortion.size(); ++i) {
        if (file.distortion[i] != 0.0) {
            throw NotRepresentable(context.source + ": camera " + std::to_string(i) + " (" +
                                   shown_value(file.set.cameras[i].name) + "): VisualSfM's measurement distortion r = " + format_number(file.distortion[i]) +
                                   " undistorts the measured pixel, which no libcam lens does (its observations read)");
        }
    }
    return detail::cameras_of_views(file.set, context.source, "");
}

ObservationSet read_nvm_observations(const std::filesystem::path& file, std::string_view text,
                                     const ObservationReadOptions& options) {
    const std::string source = file.string();
    return with_observations(parse_nvm(text, source, given_size(options.size, source, "an NVM file")).set, "the file");
}

std::vector<NamedCamera> read_bundler(std::string_view text, const ReadContext& context) {
    const ImageSize size = given_size(context.options.size, context.source, "a bundle file");
    return detail::cameras_of_views(parse_bundler(text, context.source, size, context.folder), context.source, "");
}

ObservationSet read_bundler_observations(const std::filesystem::path& file, std::string_view text,
                                         const ObservationReadOptions& options) {
    const std::string source = file.string();
    const ImageSize size = given_size(options.size, source, "a bundle file");
    return with_observations(parse_bundler(text, source, size, file.parent_path()), "the file");
}

}  // namespace libcam
