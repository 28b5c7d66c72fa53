#pragma once
// The light program's side of the commands module (commands_module.hpp): finds it beside
// the program, loads it on first use and calls its entries.

#include <string_view>

#include "libcam/io/camera_file.hpp"

namespace libcam::cli {

// Runs the command line in the module (a command the light program does not run itself).
// A module that is missing or cannot be loaded: one line naming `command` and the files
// looked for, exit code 1.
int run_in_commands_module(std::string_view command, int argc, char** argv);

// For set_camera_format_loader (io/format_table.hpp): has the module fill the program's
// row of `format`. Throws FileError naming the format and the files looked for when the
// module cannot be loaded.
void load_format_from_commands_module(CameraFormat format);

}  // namespace libcam::cli
