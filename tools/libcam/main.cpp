// libcam: graphics cameras <-> calibrated cameras, proven against OpenCV and mrcal.
//
// Exit codes: 0 success, 1 a failure (bad value, unreadable file, failed check),
// 2 a usage error (unknown flag, malformed number). Errors are one line on stderr.
//
// This program links libcam::core and libcam::io alone and runs the light commands
// itself; the others, and mrcal's .cameramodel format, are in the commands module, loaded
// only when asked for (commands_module.hpp): `libcam --version` or `libcam info cam.json`
// start without OpenCV, libmrcal and Ceres.

#include "commands.hpp"
#include "libcam/io/format_table.hpp"
#include "module_loader.hpp"

using namespace libcam::cli;

int main(int argc, char** argv) {
    const std::string_view name = subcommand_of(argc, argv);
    const CommandInfo* command = find_command(name);
    if (command != nullptr && runs_in_module(*command, argc, argv)) return run_in_commands_module(name, argc, argv);
    libcam::set_camera_format_loader(load_format_from_commands_module);
    return run_commands(light_commands(), argc, argv);
}
