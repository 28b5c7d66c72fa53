// libcam remap: images from one camera to another (undistort a photo into a pinhole,
// LONLAT or cylindrical camera chosen for it, or distort a render to the real lens).

#include <cmath>
#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "camera_options.hpp"
#include "commands.hpp"
#include "image_flags.hpp"
#include "libcam/camera/parallel.hpp"
#include "libcam/error.hpp"
#include "libcam/interop/image_remap.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/remap/derived_camera.hpp"
#include "libcam/remap/new_camera.hpp"
#include "libcam/text/number_format.hpp"
#include "parse.hpp"

namespace libcam::cli {

namespace {

namespace fs = std::filesystem;

struct RemapFlags {
    FileSelection source;
    std::string from;
    std::string to;
    std::string to_pinhole;
    std::string to_fov;
    std::string to_fov_axis = "horizontal";
    std::string to_fov_model;  // default: pinhole
    std::string to_lonlat;
    std::string to_cylindrical;
    std::string size;
    std::string rotate;
    bool inverse = false;
    std::string method = "exact";
    std::string interpolation = "linear";
    int threads = worker_count(0);
    std::string map_out;
    std::string stmap_out;
    std::string overscan;
    std::string camera_out;
    std::string camera_format = "json";
    std::string output;
    std::vector<std::string> images;
};

Keep keep_from(const std::string& flag, const std::string& value) {
    if (value == "valid") return Keep::Valid;
    if (value == "all") return Keep::All;
    throw UsageError(flag + ": expected valid (no pixel without a source) or all (every source pixel kept), got '" +
                     value + "'");
}

LensType fov_model_from(const std::string& text) {
    if (text.empty() || text == "pinhole") return LensType::Pinhole;
    if (text == "lonlat") return LensType::Lonlat;
    if (text == "cylindrical") return LensType::Cylindrical;
    throw UsageError("--to-fov-model: expected pinhole, lonlat or cylindrical, got '" + text + "'");
}

// The camera the images go into (or, with --inverse, come from): a file, or one chosen.
NewCamera target_camera(const RemapFlags& flags, const PreparedCamera& source, const Mat3& rotation) {
    const int given = !flags.to.empty() + !flags.to_pinhole.empty() + !flags.to_fov.empty() + !flags.to_lonlat.empty() +
                      !flags.to_cylindrical.empty();
    if (given > 1) throw UsageError("give one of --to, --to-pinhole, --to-fov, --to-lonlat and --to-cylindrical");
    if (!flags.to.empty()) {
        if (!flags.size.empty()) throw UsageError("--size: the camera --to names has its own size");
        const CameraFile file = read_camera_file(flags.to);
        return {file.camera, "the camera in " + flags.to};
    }
    if (!flags.to_fov_model.empty() && flags.to_fov.empty()) throw UsageError("--to-fov-model: give it with --to-fov");
    NewCameraRequest request;
    request.rotation = rotation;
    request.threads = flags.threads;
    if (!flags.size.empty()) request.size = parse_size("--size", flags.size);
    if (!flags.to_fov.empty()) {
        request.keep.reset();
        request.fov_deg = parse_number("--to-fov", flags.to_fov);
        request.model = fov_model_from(flags.to_fov_model);
        try {
            request.fov_axis = fov_axis_from_string(flags.to_fov_axis);
        } catch (const InvalidArgument& error) {
            throw UsageError(std::string("--to-fov-axis: ") + error.what());
        }
    } else if (!flags.to_lonlat.empty()) {
        request.model = LensType::Lonlat;
        request.keep = keep_from("--to-lonlat", flags.to_lonlat);
    } else if (!flags.to_cylindrical.empty()) {
        request.model = LensType::Cylindrical;
        request.keep = keep_from("--to-cylindrical", flags.to_cylindrical);
    } else {
        request.keep = keep_from("--to-pinhole", flags.to_pinhole.empty() ? "valid" : flags.to_pinhole);
    }
    return choose_new_camera(source, request);
}

// --overscan: none, a number of pixels on every side, or auto (the least that gives every
// lens pixel with a ray a source in the render).
Overscan render_margins(const RemapFlags& flags, const PreparedCamera& lens, const Camera& render, const Mat3& rotation) {
    if (flags.overscan.empty()) return {};
    if (flags.overscan == "auto") {
        try {
            return overscan_for(lens, render, rotation, flags.threads);
        } catch (const InvalidArgument& error) {
            throw UsageError(std::string("--") + error.what());
        }
    }
    const double pixels = parse_number("--overscan", flags.overscan);
    if (pixels < 0 || pixels > 100000 || pixels != std::floor(pixels)) {
        throw UsageError("--overscan: expected auto or whole pixels from 0 to 100000, got '" + flags.overscan + "'");
    }
    const long each = static_cast<long>(pixels);
    return {each, each, each, each};
}

UnprojectMethod method_from(const std::string& text) {
    if (text == "exact") return UnprojectMethod::Exact;
    if (text == "fast") return UnprojectMethod::Fast;
    throw UsageError("--method: expected exact or fast, got '" + text + "'");
}



std::string percent(std::size_t part, std::size_t whole) {
    return format_short(100.0 * static_cast<double>(part) / static_cast<double>(std::max<std::size_t>(whole, 1)), 4) + "%";
}

int run_remap(const RemapFlags& flags) {
    if (flags.images.empty() && flags.map_out.empty() && flags.stmap_out.empty() && flags.camera_out.empty()) {
        throw UsageError("nothing to write: give images (with -o), --map-out, --stmap-out or --camera-out");
    }
    if (!flags.overscan.empty() && !flags.inverse) {
        throw UsageError("--overscan: the margins of a render, for --inverse (distorting renders to the lens)");
    }
    if (!flags.images.empty() && flags.output.empty()) throw UsageError("-o: give the folder to write the images into");
    // Output names checked before any work, so that a bad one leaves nothing half written.
    if (!flags.map_out.empty()) check_map_file_name(flags.map_out);
    if (!flags.stmap_out.empty()) check_stmap_file_name(flags.stmap_out);
    if (flags.threads < 1) throw UsageError("--threads: expected 1 or more");
    const Interpolation interpolation = interpolation_flag(flags.interpolation);
    const Mat3 rotation = flags.rotate.empty() ? Mat3::Identity() : rotation_from_rvec(parse_vec3("--rotate", flags.rotate));
    const PreparedCamera lens(flags.source.read(flags.from).camera);
    NewCamera chosen = target_camera(flags, lens, rotation);
    std::cout << "camera: " << chosen.why << "\n";
    // The render's margins: its image grows by them, its format (the STMap's) stays.
    const Camera format_camera = chosen.camera;
    const Overscan margins = render_margins(flags, lens, chosen.camera, rotation);
    if (!flags.overscan.empty()) {
        chosen.camera = padded(chosen.camera, margins.left, margins.top, margins.right, margins.bottom);
        std::cout << "overscan: left " << margins.left << ", top " << margins.top << ", right " << margins.right
                  << ", bottom " << margins.bottom << " px: render " << chosen.camera.size.width << "x"
                  << chosen.camera.size.height << " for a " << format_camera.size.width << "x"
                  << format_camera.size.height << " format\n";
    }
    const PreparedCamera other(chosen.camera);

    // Undistorting: each pixel of the chosen camera from the lens. --inverse: each pixel
    // of the lens from the chosen camera (a render made with it).
    RemapOptions options;
    options.method = method_from(flags.method);
    options.threads = flags.threads;
    // The new camera's axes are the lens's turned by --rotate (a camera from --to too:
    // files from different tools seldom share a world).
    options.rotation = flags.inverse ? Mat3(rotation.transpose()) : rotation;
    const RemapMap map = flags.inverse ? build_remap_map(lens, other, options) : build_remap_map(other, lens, options);
    const std::size_t pixels = map.x.size();
    std::cout << "map: " << map.size.width << "x" << map.size.height << " from " << map.source_size.width << "x"
              << map.source_size.height << ", " << percent(map.with_source, pixels) << " of its pixels have a source ("
              << pixels - map.with_source << " without)\n";

    if (!flags.camera_out.empty()) {
        CameraFormat format;
        try {
            format = camera_format_from_string(flags.camera_format);
        } catch (const InvalidArgument& error) {
            throw UsageError(std::string("--camera-format: ") + error.what());
        }
        write_camera_file(flags.camera_out, chosen.camera, format);
    }
    if (!flags.map_out.empty()) write_map_file(flags.map_out, map);
    if (!flags.stmap_out.empty()) {
        // The format: the photo when undistorting, the render without its margins when not.
        const StmapFormat format = flags.inverse ? StmapFormat{format_camera.size, margins.left, margins.top}
                                                 : StmapFormat{map.source_size, 0, 0};
        write_stmap_file(flags.stmap_out, map, format);
    }
    if (flags.images.empty()) return 0;

    fs::create_directories(flags.output);
    for (std::size_t i = 0; i < flags.images.size(); ++i) {
        const std::string& path = flags.images[i];
        const fs::path out = fs::path(flags.output) / fs::path(path).filename();
        if (fs::exists(out) && fs::equivalent(out, path)) {
            throw FileError(out.string() + ": is the input image itself: give another output folder");
        }
        const cv::Mat image = read_image(path);
        cv::Mat result;
        try {
            result = remap_image(image, map, interpolation);
        } catch (const InvalidArgument& error) {
            throw FileError(path + ": " + error.what());
        }
        write_image(out, result);
        if (flags.images.size() > 1) std::cerr << "[" << i + 1 << "/" << flags.images.size() << "] " << out.string() << "\n";
    }
    return 0;
}

}  // namespace

Runner add_remap(CLI::App& app) {
    CLI::App* command = add_command(app, "remap");
    auto flags = std::make_shared<RemapFlags>();
    command->add_option("--from", flags->from, "The lens's camera file (the camera the images were taken with)")
        ->required();
    flags->source.add_to(*command);
    command->add_option("--to", flags->to,
                        "A camera file to turn the images into (its axes are the lens's, turned by --rotate)");
    command->add_option("--to-pinhole", flags->to_pinhole,
                        "A pinhole chosen for the lens (the default, valid): valid = the widest view with a source "
                        "for every pixel (no black borders); all = the narrowest that keeps every pixel of the lens "
                        "(LONLAT instead when the lens sees past 75 degrees off its axis)");
    command->add_option("--to-fov", flags->to_fov,
                        "A camera with this field of view in degrees, edge to edge (--to-fov-model, --to-fov-axis)");
    command->add_option("--to-fov-axis", flags->to_fov_axis,
                        "--to-fov's axis: horizontal, vertical or (pinhole) diagonal")
        ->capture_default_str();
    command->add_option("--to-fov-model", flags->to_fov_model,
                        "--to-fov's camera: pinhole (the default), lonlat or cylindrical (centred, square pixels)");
    command->add_option("--to-lonlat", flags->to_lonlat,
                        "An equirectangular (LONLAT) camera chosen for the lens: valid or all, as for --to-pinhole");
    command->add_option("--to-cylindrical", flags->to_cylindrical,
                        "A cylindrical panorama (straight verticals: longitude across, a pinhole's height down) "
                        "chosen for the lens: valid or all, as for --to-pinhole (LONLAT instead when all of the lens "
                        "reaches past 75 degrees above or below its horizon)");
    command->add_option("--size", flags->size, "The new camera's image size WIDTHxHEIGHT (default: the lens's)");
    command->add_option("--rotate", flags->rotate,
                        "Turn the new camera by this rotation vector (radians, x,y,z in the lens's camera frame)");
    command->add_flag("--inverse", flags->inverse,
                      "The images are of the new camera (renders made with it, see --camera-out): turn them into "
                      "images of the lens");
    command->add_option("--method", flags->method,
                        "Unprojection: exact (to 1e-9 px) or fast (within about 0.01 px)")
        ->capture_default_str();
    command->add_option("--interpolation", flags->interpolation, "nearest, linear, cubic or lanczos (cv::remap)")
        ->capture_default_str();
    command->add_option("--threads", flags->threads, "Threads that build the map")->capture_default_str();
    command->add_option("--map-out", flags->map_out,
                        "Write the map: source x, y per pixel, NaN where none (.exr: channels R, G; .npy: H x W x 2)");
    command->add_option("--stmap-out", flags->stmap_out,
                        "Write the map as a compositor's STMap (.exr: R, G = u, v of the source's format with Nuke's "
                        "y up, A = 1 where there is a source)");
    command->add_option("--overscan", flags->overscan,
                        "With --inverse: render this many pixels more on every side, or auto: the least that gives "
                        "every lens pixel a source (the new camera written is the render's; the STMap's format stays)");
    command->add_option("--camera-out", flags->camera_out, "Write the new camera (--camera-format)");
    command->add_option("--camera-format", flags->camera_format,
                        "--camera-out's format: " + written_formats_help())
        ->capture_default_str();
    command->add_option("-o,--output", flags->output, "Folder for the images (each keeps its file name)");
    command->add_option("images", flags->images, "Images to turn");
    return [flags] { return run_remap(*flags); };
}

}  // namespace libcam::cli
