// libcam rectify: a calibrated pair's rectified cameras (PINHOLE as OpenCV's stereoRectify,
// LATLON as mrcal's rectified_system), and with --images the rectified images.

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgcodecs.hpp>

#include "camera_options.hpp"
#include "commands.hpp"
#include "image_flags.hpp"
#include "json_output.hpp"
#include "libcam/camera/parallel.hpp"
#include "libcam/error.hpp"
#include "libcam/interop/image_remap.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/remap/remap_map.hpp"
#include "libcam/stereo/rectify.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"
#include "parse.hpp"

namespace libcam::cli {

namespace {

namespace fs = std::filesystem;

struct RectifyFlags {
    std::vector<std::string> sources;
    std::string cameras;
    std::string to = "auto";
    std::string keep = "valid";
    bool json = false;
    std::string output;
    std::vector<std::string> images;
    std::string size;
    std::string interpolation = "linear";
    std::string maps;  // with -o: also write each camera's map, as .exr or .npy
    int threads = worker_count(0);
};

std::optional<LensType> model_from(const std::string& text) {
    if (text == "auto") return std::nullopt;
    if (text == "pinhole") return LensType::Pinhole;
    if (text == "latlon") return LensType::Latlon;
    throw UsageError("--to: expected pinhole, latlon or auto, got '" + text + "'");
}

Keep keep_from(const std::string& text) {
    if (text == "valid") return Keep::Valid;
    if (text == "all") return Keep::All;
    throw UsageError("--keep: expected valid (no black border) or all (every pixel either camera sees), got '" + text +
                     "'");
}

// Every camera the sources hold, in order: one file with two or more posed cameras, OpenCV's
// two stereo files, or two files of one camera each (mrcal's .cameramodel with extrinsics).
std::vector<NamedCamera> cameras_of(const RectifyFlags& flags, const ReadOptions& options) {
    const std::string& first = flags.sources[0];
    if (flags.sources.size() == 2) {
        const std::string& second = flags.sources[1];
        const std::string second_text = read_text_file(second, kCameraFileLimit);
        if (is_opencv_stereo_extrinsics(second_text)) {
            return parse_opencv_stereo_files(read_text_file(first, kCameraFileLimit), first, second_text, second, options)
                .cameras;
        }
    }
    std::vector<NamedCamera> cameras;
    for (const std::string& path : flags.sources) {
        for (NamedCamera& camera : read_camera_set(path, std::nullopt, options).cameras) {
            if (camera.name.empty() || flags.sources.size() == 2) camera.name = fs::path(path).filename().string() +
                                                                                (camera.name.empty() ? "" : ":" + camera.name);
            cameras.push_back(std::move(camera));
        }
    }
    return cameras;
}

// The two cameras --cameras names (by name or position), or the first two.
std::array<NamedCamera, 2> chosen_pair(const RectifyFlags& flags, std::vector<NamedCamera> cameras) {
    const std::string where = flags.sources.size() == 2 ? flags.sources[0] + " and " + flags.sources[1] : flags.sources[0];
    if (cameras.size() < 2) {
        throw FileError(where + ": holds one camera; rectifying needs two with their relative pose (a file of a pair "
                                "or a rig, or a second file)");
    }
    if (flags.cameras.empty()) return {cameras[0], cameras[1]};
    const std::size_t comma = flags.cameras.find(',');
    if (comma == std::string::npos) throw UsageError("--cameras: expected two names or positions A,B, got '" + flags.cameras + "'");
    CameraSet set;
    set.cameras = std::move(cameras);
    try {
        return {select_camera(set, flags.cameras.substr(0, comma), where),
                select_camera(set, flags.cameras.substr(comma + 1), where)};
    } catch (const InvalidArgument& error) {
        throw UsageError(std::string("--cameras: ") + error.what());
    }
}

// The pair with the first camera's frame as the world.
void rebase_on_first(std::array<NamedCamera, 2>& pair) {
    const Pose to_world = pair[0].file.camera.pose.inverse();
    for (NamedCamera& camera : pair) camera.file.camera.pose = camera.file.camera.pose.after(to_world);
}

Json matrix_json(const auto& m) {
    Json rows = Json::array();
    for (Eigen::Index r = 0; r < m.rows(); ++r) {
        Json row = Json::array();
        for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(finite_or_null(m(r, c) + 0.0));
        rows.push_back(row);
    }
    return rows;
}

Json pair_json(const RectifiedPair& pair, const std::array<NamedCamera, 2>& sources) {
    Json out;
    out["model"] = std::string(lens_info(pair.model).name);
    out["baseline"] = pair.baseline;
    out["cameras"] = Json::array();
    for (std::size_t k = 0; k < 2; ++k) {
        const RectifiedCamera& camera = pair.cameras[k];
        Json one;
        one["name"] = sources[k].name;
        one["image_size"] = Json::array({camera.camera.size.width, camera.camera.size.height});
        one["K"] = matrix_json(camera.camera.intrinsics.K());
        one["R"] = matrix_json(camera.rotation);
        one["kept"] = camera.kept;
        out["cameras"].push_back(one);
    }
    out["Q"] = pair.model == LensType::Pinhole ? matrix_json(pair.Q) : Json(nullptr);
    out["why"] = pair.why;
    return out;
}

// R T R1 R2 P1 P2 Q as OpenCV's stereo_calib sample writes its extrinsics.yml.
std::string opencv_extrinsics(const RectifiedPair& pair, const std::array<NamedCamera, 2>& sources) {
    const Pose& second = sources[1].file.camera.pose;  // the first's is the identity
    const auto mat = [](const auto& m) {
        cv::Mat out;
        cv::eigen2cv(Eigen::MatrixXd(m), out);
        return out;
    };
    Mat34 P1 = Mat34::Zero(), P2 = Mat34::Zero();
    P1.leftCols<3>() = pair.cameras[0].camera.intrinsics.K();
    P2.leftCols<3>() = pair.cameras[1].camera.intrinsics.K();
    P2(0, 3) = -pair.baseline * pair.cameras[1].camera.intrinsics.fx;
    cv::FileStorage storage(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
    storage << "R" << mat(second.R) << "T" << mat(second.t) << "R1" << mat(pair.cameras[0].rotation) << "R2"
            << mat(pair.cameras[1].rotation) << "P1" << mat(P1) << "P2" << mat(P2) << "Q" << mat(pair.Q);
    return storage.releaseAndGetString();
}

struct OutputFile {
    std::string name;
    std::string bytes;
};

std::string encoded_png(const cv::Mat& image, const std::string& name) {
    std::vector<unsigned char> bytes;
    if (!cv::imencode(".png", image, bytes)) throw FileError(name + ": OpenCV cannot write this image as PNG");
    return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

int run_rectify(const RectifyFlags& flags) {
    if (flags.sources.empty() || flags.sources.size() > 2) throw UsageError("give one file holding the pair, or two");
    if (!flags.images.empty() && flags.images.size() != 2) throw UsageError("--images: give two images, LEFT RIGHT");
    if (!flags.images.empty() && flags.output.empty()) throw UsageError("-o: give the folder for the rectified images");
    if (flags.threads < 1) throw UsageError("--threads: expected 1 or more");
    if (!flags.maps.empty() && flags.maps != "exr" && flags.maps != "npy")
        throw UsageError("--maps: expected exr or npy, got '" + flags.maps + "'");
    if (!flags.maps.empty() && flags.output.empty()) throw UsageError("-o: give the folder for the maps");
    const Interpolation interpolation = interpolation_flag(flags.interpolation);
    RectifyRequest request;
    request.model = model_from(flags.to);
    request.keep = keep_from(flags.keep);
    request.threads = flags.threads;

    std::vector<cv::Mat> images;
    for (const std::string& path : flags.images) images.push_back(read_image(path));
    ReadOptions options;
    if (!flags.size.empty()) {
        options.size = parse_size("--size", flags.size);
    } else if (!images.empty()) {
        options.size = ImageSize{images[0].cols, images[0].rows};
    }
    std::vector<NamedCamera> cameras;
    try {
        cameras = cameras_of(flags, options);
    } catch (const Error& error) {
        const std::string text = error.what();
        if (!options.size && (text.find("image_width") != std::string::npos || text.find("width") != std::string::npos)) {
            throw FileError(text + " (the file holds no image size: give --size WIDTHxHEIGHT or --images LEFT RIGHT)");
        }
        throw;
    }
    std::array<NamedCamera, 2> pair_sources = chosen_pair(flags, std::move(cameras));
    rebase_on_first(pair_sources);
    for (std::size_t k = 0; k < images.size(); ++k) {
        const ImageSize& size = pair_sources[k].file.camera.size;
        if (images[k].cols != size.width || images[k].rows != size.height) {
            throw FileError(flags.images[k] + ": the image is " + std::to_string(images[k].cols) + "x" +
                            std::to_string(images[k].rows) + ", the camera " + pair_sources[k].name + " " +
                            std::to_string(size.width) + "x" + std::to_string(size.height));
        }
    }
    const RectifiedPair pair = rectify_pair(pair_sources[0].file.camera, pair_sources[1].file.camera, request);

    if (flags.json) {
        emit(pair_json(pair, pair_sources).dump(2) + "\n", "");
    } else {
        std::cout << "rectified: " << pair.why << "\n";
        std::cout << "baseline: " << format_number(pair.baseline) << "\n";
        for (std::size_t k = 0; k < 2; ++k) {
            const RectifiedCamera& c = pair.cameras[k];
            std::cout << pair_sources[k].name << ": " << c.camera.size.width << "x" << c.camera.size.height << ", keeps "
                      << format_short(100.0 * c.kept, 5) << "% of the pixels looking in front of the camera\n";
        }
    }
    if (flags.output.empty()) return 0;

    // Everything made before anything is written: a failure leaves the folder as it was.
    std::vector<OutputFile> files;
    const char* side[2] = {"left", "right"};
    for (std::size_t k = 0; k < 2 && (!images.empty() || !flags.maps.empty()); ++k) {
        RemapOptions remap_options;
        remap_options.rotation = pair.cameras[k].rotation;
        remap_options.threads = flags.threads;
        const RemapMap map = build_remap_map(PreparedCamera(pair.cameras[k].camera),
                                             PreparedCamera(pair_sources[k].file.camera), remap_options);
        if (!images.empty()) {
            files.push_back({std::string(side[k]) + ".png",
                             encoded_png(remap_image(images[k], map, interpolation), flags.images[k])});
        }
        if (!flags.maps.empty()) {
            const std::string name = std::string(side[k]) + "-map." + flags.maps;
            files.push_back({name, encoded_map(fs::path(flags.output) / name, map)});
        }
    }
    for (std::size_t k = 0; k < 2; ++k) {
        files.push_back({std::string(side[k]) + ".json", format_camera(pair.cameras[k].camera, CameraFormat::Json)});
        files.push_back({std::string(side[k]) + ".cameramodel",
                         format_camera(pair.cameras[k].camera, CameraFormat::Cameramodel)});
    }
    if (pair.model == LensType::Pinhole) files.push_back({"extrinsics.yml", opencv_extrinsics(pair, pair_sources)});
    fs::create_directories(flags.output);
    for (const OutputFile& file : files) write_file_atomically(fs::path(flags.output) / file.name, file.bytes);
    std::cerr << "wrote " << files.size() << " files into " << flags.output << "\n";
    return 0;
}

}  // namespace

Runner add_rectify(CLI::App& app) {
    CLI::App* command = add_command(app, "rectify");
    auto flags = std::make_shared<RectifyFlags>();
    command
        ->add_option("sources", flags->sources,
                     "The pair: one file holding two posed cameras (Kalibr camchain, libcam JSON, a rig), or two "
                     "files (two mrcal .cameramodel with extrinsics; OpenCV's intrinsics.yml and extrinsics.yml)")
        ->required();
    command->add_option("--cameras", flags->cameras, "The two cameras, by name or position A,B (default: the first two)");
    command->add_option("--to", flags->to,
                        "pinhole (OpenCV's rectification), latlon (mrcal's: azimuth across, elevation down) or auto "
                        "(pinhole while both cameras see under 100 degrees across)")
        ->capture_default_str();
    command->add_option("--keep", flags->keep,
                        "pinhole's view: valid (no black border, OpenCV's alpha 0) or all (every pixel either camera "
                        "sees, alpha 1)")
        ->capture_default_str();
    command->add_flag("--json", flags->json, "Print the rectified pair as JSON");
    command->add_option("-o,--output", flags->output,
                        "Folder for the rectified cameras (left.json and right.json, and left.cameramodel and "
                        "right.cameramodel for mrcal), extrinsics.yml (OpenCV's R1 R2 P1 P2 Q; PINHOLE), and with "
                        "--images left.png and right.png");
    command->add_option("--images", flags->images, "The two images to rectify, LEFT RIGHT")->expected(2);
    command->add_option("--maps", flags->maps,
                        "With -o: also write each rectified camera's map, left-map and right-map: for each rectified "
                        "pixel the source pixel x, y (OpenCV's convention, NaN where none), as exr (channels R, G) or "
                        "npy (height x width x 2)");
    command->add_option("--size", flags->size,
                        "The cameras' image size WIDTHxHEIGHT, for files that hold none (OpenCV's stereo files); "
                        "default: the images'");
    command->add_option("--interpolation", flags->interpolation, "nearest, linear, cubic or lanczos (cv::remap)")
        ->capture_default_str();
    command->add_option("--threads", flags->threads, "Threads")->capture_default_str();
    return [flags] { return run_rectify(*flags); };
}

}  // namespace libcam::cli
