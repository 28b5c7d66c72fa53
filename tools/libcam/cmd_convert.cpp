// libcam convert: a look-at camera (flags) or a camera file, written in any format.

#include "camera_options.hpp"
#include "commands.hpp"
#include "libcam/error.hpp"
#include "parse.hpp"

namespace libcam::cli {


Runner add_convert(CLI::App& app) {
    CLI::App* command = add_command(app, "convert");
    struct Flags {
        CameraOptions camera;
        std::string to = "json";
        std::string output;
        std::string near = "0.1";
        std::string far = "1000";
        std::string depth_range = "minus-one-to-one";
        std::string image_name = "image.png";
        bool no_pose = false;
    };
    auto flags = std::make_shared<Flags>();
    flags->camera.add_to(*command);
    command->add_option("--to", flags->to, "Output format: " + written_formats_help())->capture_default_str();
    command->add_option("-o,--output", flags->output,
                        "Output file (written atomically; for colmap, a folder); default stdout");
    command->add_option("--image-name", flags->image_name,
                        "colmap, nerf: the name of the image the pose belongs to (images.txt's NAME, "
                        "transforms.json's file_path)")
        ->capture_default_str();
    command->add_option("--near", flags->near, "gl: near plane distance; blender: clip_start")->capture_default_str();
    command->add_option("--far", flags->far, "gl: far plane distance; blender: clip_end")->capture_default_str();
    command->add_option("--depth-range", flags->depth_range,
                        "gl: NDC depth range, minus-one-to-one (OpenGL) or zero-to-one (Direct3D/Vulkan)")
        ->capture_default_str();
    command->add_flag("--no-pose", flags->no_pose,
                      "ros: write the camera's intrinsics alone (camera_info holds no pose; without this flag a "
                      "camera whose pose is not the identity is refused)");

    return [flags] {
        const CameraFormat format = [&] {
            try {
                return camera_format_from_string(flags->to);
            } catch (const InvalidArgument& error) {
                throw UsageError(std::string("--to: ") + error.what());
            }
        }();
        if (flags->depth_range != "minus-one-to-one" && flags->depth_range != "zero-to-one") {
            throw UsageError("--depth-range: expected minus-one-to-one or zero-to-one, got '" + flags->depth_range + "'");
        }
        WriteOptions options;
        options.gl_near = parse_number("--near", flags->near);
        options.gl_far = parse_number("--far", flags->far);
        options.gl_depth_range =
            flags->depth_range == "zero-to-one" ? DepthRange::ZeroToOne : DepthRange::MinusOneToOne;
        options.image_name = flags->image_name;
        options.drop_pose = flags->no_pose;
        const CameraFile file = flags->camera.camera();
        options.look_at_camera = file.look_at_camera;
        if (camera_format_writes_folder(format)) {
            if (flags->output.empty()) {
                throw UsageError("--to " + flags->to + ": writes several files: give the folder to write them into (-o)");
            }
            write_camera_file(flags->output, file.camera, format, options);
            return 0;
        }
        emit(format_camera(file.camera, format, options), flags->output);
        return 0;
    };
}

}  // namespace libcam::cli
