#include "commands.hpp"

#include <array>
#include <iostream>
#include <map>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/text/shown_value.hpp"
#include "libcam/version.hpp"
#include "parse.hpp"

namespace libcam::cli {

namespace {

// In the order `libcam --help` lists them.
constexpr std::array<CommandInfo, 18> kCommands = {{
    {"convert", "Convert a look-at camera or a camera file to K, R|t, P, rvec, an OpenGL projection, or a file", true},
    {"info", "Every camera a file holds: model, size, K, field of view, pose", true},
    {"rays", "World rays through pixels, by K^-1 and by the look-at formula", true},
    {"project", "The pixel of each world point (through R|t, K and the lens)", true},
    {"remap",
     "Turn images from one camera into another: undistort into a pinhole, LONLAT or cylindrical camera chosen for "
     "the lens, or (--inverse) distort renders to the real lens",
     false},
    {"rectify",
     "A calibrated pair's rectified cameras and images (a point on the same row of both): pinhole as OpenCV's, "
     "LATLON as mrcal's for wide lenses; depth from disparity",
     false},
    {"dataset",
     "A whole COLMAP reconstruction (or NeRF's transforms.json) into pinhole cameras: images undistorted, "
     "observations moved to the new pixels; written as COLMAP or NeRF",
     false},
    {"derive", "The camera of a resized, cropped, padded, binned or quarter-turned image (one operation a call)", true},
    {"render-plan",
     "How to render with Blender through a lens it cannot draw: the camera to render with and the map that turns "
     "its render into the lens's image",
     false},
    {"verify", "Check a camera file against OpenCV and mrcal over a grid of pixels", false},
    {"reproject",
     "Reproject the observations of a calibration or reconstruction (OpenCV, mrcal, COLMAP, OpenSfM, OpenMVG) and "
     "reproduce each tool's own reprojection error",
     true, "--heatmap"},
    {"fit", "The simplest lens model that reproduces a camera over a scene within a pixel tolerance", false},
    {"calibrate",
     "A folder of board images (chessboard or ChArUco) to a calibration: the corners found, the lens model the "
     "views held out of the fit support",
     false},
    {"uncertainty",
     "How far a calibration can be trusted at each pixel: mrcal's projection uncertainty, from the observations a "
     "calibration file holds",
     false},
    {"bench", "Time and accuracy of every projection and unprojection method of libcam, OpenCV and mrcal", false},
    {"demo",
     "The built-in example: convert the two worked example cameras and check them against OpenCV and mrcal",
     false},
    {"formats", "List every camera-file format: what libcam reads and writes, and the lens models each holds", true},
    {"models", "Every lens model: its coefficients, abilities and other names", true},
}};

// The command's runner, or for a command that runs elsewhere (the commands module) a bare
// entry that lists it in --help and takes any flags.
Runner add_or_list(CLI::App& app, const CommandInfo& info, std::span<const CommandAdder> here) {
    for (const CommandAdder& adder : here) {
        if (adder.name == info.name) return adder.add(app);
    }
    add_command(app, info.name)->allow_extras()->prefix_command();
    return [name = std::string(info.name)]() -> int {
        throw Error(name + ": runs in the commands module, which this program did not load");
    };
}

// The exit code of a runner: 2 for a usage error, 1 for any other error, each one
// printable line whatever bytes a file put in it.
int run_reporting_errors(const Runner& run) {
    try {
        return run();
    } catch (const UsageError& error) {
        std::cerr << "libcam: usage error: " << printable_text(error.what()) << " (see --help)\n";
        return 2;
    } catch (const std::exception& error) {
        std::cerr << "libcam: error: " << printable_text(error.what()) << "\n";
        return 1;
    }
}

}  // namespace

std::span<const CommandAdder> light_commands() {
    static constexpr CommandAdder kLight[] = {
        {"convert", add_convert}, {"info", add_info},       {"rays", add_rays},     {"project", add_project},
        {"derive", add_derive},   {"formats", add_formats}, {"models", add_models}, {"reproject", add_reproject},
    };
    return kLight;
}

const CommandInfo* find_command(std::string_view name) {
    for (const CommandInfo& info : kCommands) {
        if (info.name == name) return &info;
    }
    return nullptr;
}

CLI::App* add_command(CLI::App& app, std::string_view name) {
    const CommandInfo* info = find_command(name);
    return app.add_subcommand(std::string(name), info == nullptr ? std::string() : std::string(info->description));
}

bool runs_in_module(const CommandInfo& command, int argc, char** argv) {
    if (!command.light) return true;
    if (command.module_flag.empty()) return false;
    for (int i = 1; i < argc; ++i) {
        const std::string_view word = argv[i];
        if (word == command.module_flag ||
            (word.starts_with(command.module_flag) && word.size() > command.module_flag.size() &&
             word[command.module_flag.size()] == '=')) {
            return true;
        }
    }
    return false;
}

std::string_view subcommand_of(int argc, char** argv) {
    // The program's own flags (--help, --version) take no value, so the first word that is
    // not a flag names the subcommand.
    for (int i = 1; i < argc; ++i) {
        if (argv[i][0] != '-') return argv[i];
    }
    return {};
}

int run_commands(std::span<const CommandAdder> here, int argc, char** argv) {
    CLI::App app{"libcam: graphics cameras <-> calibrated cameras, checked against OpenCV and mrcal"};
    app.set_version_flag("--version", std::string("libcam ") + LIBCAM_VERSION);
    app.require_subcommand(1);
    std::map<CLI::App*, Runner> runners;
    for (const CommandInfo& info : kCommands) {
        Runner run = add_or_list(app, info, here);
        runners[app.get_subcommands({}).back()] = std::move(run);
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& help) {
        return app.exit(help);
    } catch (const CLI::CallForAllHelp& help) {
        return app.exit(help);
    } catch (const CLI::CallForVersion& version) {
        return app.exit(version);
    } catch (const CLI::ParseError& error) {
        std::cerr << "libcam: usage error: " << error.what() << " (see --help)\n";
        return 2;
    }
    for (const auto& [command, run] : runners) {
        if (command->parsed()) return run_reporting_errors(run);
    }
    return 2;
}

void emit(const std::string& text, const std::string& path) {
    if (path.empty()) {
        std::cout << text << std::flush;
    } else {
        write_file_atomically(path, text);
    }
}

}  // namespace libcam::cli
