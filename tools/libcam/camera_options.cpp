#include "camera_options.hpp"

#include <iostream>

#include "libcam/convert/look_at_convert.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_formats.hpp"
#include "libcam/text/shown_value.hpp"
#include "parse.hpp"

namespace libcam::cli {

void FileSelection::add_to(CLI::App& command) {
    command.add_option("--camera", camera,
                       "Which camera of a file holding several: its name in the file (cam1), its image's file "
                       "name where that name is a path (IMG_1.jpg for D:/photos/IMG_1.jpg) and no other camera's "
                       "image shares it, or its position counting from 0 (default: the first); `libcam formats` "
                       "says which names each format has");
    command.add_option("--from-format", format,
                       "The file's format, when its extension and contents do not say: " + camera_format_names());
    command.add_option("--image-size", image_size,
                       "The image size WIDTHxHEIGHT, for a file that does not record it (NeRF's synthetic scenes, RealityCapture's XMP and CSV)");
    command.add_option("--nerf-principal-point", nerf_principal_point,
                       "transforms.json without cx, cy, and LLFF's poses_bounds.npy: centre (the image's centre, "
                       "where Blender rendered NeRF's synthetic scenes and COLMAP put LLFF's) or half-size (W/2, "
                       "H/2 with pixel centres at integers, where NeRF's own ray code puts it, half a pixel off)")
        ->capture_default_str();
    command.add_option("--lens", lens,
                       "A lens database's lens (lensfun's XML): one of its model names, or a part of one that names "
                       "no other lens");
    command.add_option("--focal", focal, "A lens database's focal length in millimetres (default: a prime lens's own)");
    command.add_option("--crop-factor", crop_factor,
                       "A lens database's sensor crop factor (default: the one the lens was calibrated on)");
    command.add_flag("--projection-only", projection_only,
                     "A lens database's lens without its distortion: its projection alone (lensfun's projection "
                     "transform without distortion correction)");
}

ReadOptions FileSelection::read_options() const {
    ReadOptions options;
    if (!image_size.empty()) options.size = parse_size("--image-size", image_size);
    options.lens = lens;
    if (!focal.empty()) options.focal_mm = parse_number("--focal", focal);
    if (!crop_factor.empty()) options.crop_factor = parse_number("--crop-factor", crop_factor);
    options.lens_projection_only = projection_only;
    if (nerf_principal_point == "half-size") {
        options.nerf_principal_point = NerfPrincipalPoint::HalfSize;
    } else if (nerf_principal_point != "centre") {
        throw UsageError("--nerf-principal-point: expected centre or half-size, got '" + nerf_principal_point + "'");
    }
    return options;
}

CameraSet FileSelection::read_set(const std::string& path) const {
    return read_camera_set(path, chosen_format(), read_options());
}

std::optional<CameraFormat> FileSelection::chosen_format() const {
    if (format.empty()) return std::nullopt;
    try {
        return camera_format_from_string(format);
    } catch (const InvalidArgument& error) {
        throw UsageError(std::string("--from-format: ") + error.what());
    }
}

CameraFile FileSelection::read(const std::string& path) const { return read_named(path).file; }

NamedCamera FileSelection::read_named(const std::string& path) const {
    return select_camera(read_set(path), camera, path);
}

void CameraOptions::add_to(CLI::App& command) {
    auto* from_option = command.add_option(
        "--from", from, "Camera file (libcam JSON, OpenCV YAML/XML, .cameramodel, .cahvor, Kalibr, basalt, camodocal, COLMAP, "
        "transforms.json, ROS camera_info, Open3D, EuRoC sensor.yaml, ORB-SLAM settings)");
    selection.add_to(command);
    std::vector<CLI::Option*> fov_flags = {
        command.add_option("--fov", fov, "Field of view in degrees, in (0, 180)"),
        command.add_option("--fov-axis", fov_axis,
                           "Axis the fov spans: horizontal, vertical, diagonal, or both (the look-at formula's: "
                           "the same angle on each axis, each normalised by its own side)")
            ->capture_default_str(),
        command.add_option("--size", size, "Image size WIDTHxHEIGHT in pixels"),
        command.add_option("--eye", eye, "Eye position x,y,z")->capture_default_str(),
        command.add_option("--target", target, "Point looked at x,y,z"),
        command.add_option("--gaze", gaze, "Gaze direction x,y,z (instead of --target; default 0,0,-1)"),
        command.add_option("--up", up, "Up vector x,y,z")->capture_default_str(),
    };
    for (CLI::Option* flag : fov_flags) from_option->excludes(flag);
    fov_flags[4]->excludes(fov_flags[5]);
    command.add_option("--pixel-origin", pixel_origin,
                       "How pixel rows are counted: bottom-left (as the look-at formula counts them) or "
                       "top-left (OpenCV's)")
        ->capture_default_str();
}

PixelOrigin CameraOptions::origin() const {
    if (pixel_origin != "bottom-left" && pixel_origin != "top-left") {
        throw UsageError("--pixel-origin: expected bottom-left or top-left, got '" + pixel_origin + "'");
    }
    return pixel_origin_from_string(pixel_origin);
}

CameraFile CameraOptions::camera() const {
    if (!from.empty()) {
        // The commands that take a camera this way use its pose (rays from its centre, world
        // points projected, extrinsics written). A view the file lists without one has the
        // identity there: said once, so that no one takes it for where the view was.
        NamedCamera named = selection.read_named(from);
        if (named.unposed) {
            std::cerr << "libcam: warning: " << printable_text(from) << ": "
                      << (named.name.empty() ? std::string("this camera") : "camera '" + printable_text(named.name) + "'")
                      << " has no pose in the file; the identity pose is used (the camera at the origin, looking "
                         "down +z)\n";
        }
        return std::move(named.file);
    }
    if (fov.empty()) throw UsageError("--fov: required (or give a camera file with --from)");
    if (size.empty()) throw UsageError("--size: required (or give a camera file with --from)");
    if (fov_axis != "horizontal" && fov_axis != "vertical" && fov_axis != "diagonal" && fov_axis != "both") {
        throw UsageError("--fov-axis: expected horizontal, vertical, diagonal or both, got '" + fov_axis + "'");
    }
    LookAtCamera look_at_camera;
    look_at_camera.fov_deg = parse_number("--fov", fov);
    look_at_camera.fov_axis = fov_axis_from_string(fov_axis);
    look_at_camera.size = parse_size("--size", size);
    look_at_camera.eye = parse_vec3("--eye", eye);
    look_at_camera.up = parse_vec3("--up", up);
    if (!target.empty()) {
        look_at_camera = LookAtCamera::look_at(look_at_camera.eye, parse_vec3("--target", target), look_at_camera.up,
                                        look_at_camera.fov_deg, look_at_camera.fov_axis, look_at_camera.size);
    } else if (!gaze.empty()) {
        look_at_camera.gaze = parse_vec3("--gaze", gaze);
    }
    return {to_camera(look_at_camera), look_at_camera};
}

std::string written_formats_help() {
    std::string help;
    for (const CameraFormatInfo& format : camera_formats()) {
        if (!format.writes) continue;
        help += (help.empty() ? "" : ", ") + std::string(format.name) + " (" + std::string(format.title) +
                (format.writes_folder ? ", into a folder" : "") + ")";
    }
    return help + "; `libcam formats` says what each holds";
}

}  // namespace libcam::cli
