// libcam derive: the camera of a resized, cropped, padded, binned or turned image.
// A light command (commands.hpp): the camera math is libcam::core's.

#include <cmath>

#include "camera_options.hpp"
#include "commands.hpp"
#include "libcam/error.hpp"
#include "libcam/remap/derived_camera.hpp"
#include "parse.hpp"

namespace libcam::cli {

namespace {

struct DeriveFlags {
    CameraOptions camera;
    std::string resize, crop, pad, bin, rotate90;
    std::string to = "json";
    std::string output;
};

std::vector<long> whole_pixels(const std::string& flag, const std::string& text) {
    std::vector<long> values;
    for (const double v : parse_numbers(flag, text, 4)) {
        if (v != std::floor(v) || std::abs(v) > 1e9) throw UsageError(flag + ": expected whole pixels, got '" + text + "'");
        values.push_back(static_cast<long>(v));
    }
    return values;
}

int bin_factor(const std::string& text) {
    const double factor = parse_number("--bin", text);
    if (factor != std::floor(factor) || factor < 1 || factor > 1e6) {
        throw UsageError("--bin: expected a whole number of pixels, 1 or more, got '" + text + "'");
    }
    return static_cast<int>(factor);
}

int quarter_turns_of(const std::string& turn) {
    if (turn != "cw" && turn != "ccw" && turn != "180") {
        throw UsageError("--rotate90: expected cw, ccw or 180, got '" + turn + "'");
    }
    return turn == "cw" ? 1 : turn == "180" ? 2 : 3;
}

// The camera after the one operation the flags give.
Camera derived_camera(const DeriveFlags& flags, const Camera& camera) {
    const int given = !flags.resize.empty() + !flags.crop.empty() + !flags.pad.empty() + !flags.bin.empty() +
                      !flags.rotate90.empty();
    if (given != 1) throw UsageError("give one of --resize, --crop, --pad, --bin and --rotate90");
    if (!flags.resize.empty()) {
        return flags.resize.find('x') != std::string::npos ? resized(camera, parse_size("--resize", flags.resize))
                                                            : scaled(camera, parse_number("--resize", flags.resize));
    }
    if (!flags.crop.empty()) {
        const std::vector<long> v = whole_pixels("--crop", flags.crop);
        return cropped(camera, v[0], v[1], v[2], v[3]);
    }
    if (!flags.pad.empty()) {
        const std::vector<long> v = whole_pixels("--pad", flags.pad);
        return padded(camera, v[0], v[1], v[2], v[3]);
    }
    if (!flags.bin.empty()) return binned(camera, bin_factor(flags.bin));
    return quarter_turns(camera, quarter_turns_of(flags.rotate90));
}

int run_derive(const DeriveFlags& flags) {
    const Camera derived = derived_camera(flags, flags.camera.camera().camera);
    CameraFormat format;
    try {
        format = camera_format_from_string(flags.to);
    } catch (const InvalidArgument& error) {
        throw UsageError(std::string("--to: ") + error.what());
    }
    if (camera_format_writes_folder(format)) {
        if (flags.output.empty()) throw UsageError("--to " + flags.to + ": give the folder to write into (-o)");
        write_camera_file(flags.output, derived, format);
        return 0;
    }
    emit(format_camera(derived, format), flags.output);
    return 0;
}

}  // namespace

Runner add_derive(CLI::App& app) {
    CLI::App* command = add_command(app, "derive");
    auto flags = std::make_shared<DeriveFlags>();
    flags->camera.add_to(*command);
    command->add_option("--resize", flags->resize, "A scale (0.5) or a new size WIDTHxHEIGHT");
    command->add_option("--crop", flags->crop, "The pixels x0,y0,x1,y1 kept (x1, y1 excluded, as image[y0:y1, x0:x1])");
    command->add_option("--pad", flags->pad, "Pixels added left,top,right,bottom");
    command->add_option("--bin", flags->bin, "Each N x N block of pixels made one");
    command->add_option("--rotate90", flags->rotate90, "Turn the image: cw, ccw or 180");
    command->add_option("--to", flags->to, "Output format: " + written_formats_help())->capture_default_str();
    command->add_option("-o,--output", flags->output, "Output file (written atomically); default stdout");
    return [flags] { return run_derive(*flags); };
}

}  // namespace libcam::cli
