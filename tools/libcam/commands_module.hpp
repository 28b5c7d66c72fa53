#pragma once
// What the `libcam` program and its commands module (libcam-commands.so) agree on.
//
// The program links libcam::core and libcam::io alone and runs the light commands
// (the light ones of commands.hpp's table: convert, info, rays, project, derive) itself: it starts without
// loading OpenCV, libmrcal or Ceres, which take most of a run that does little. The module
// holds the whole program (every command, OpenCV, mrcal, Ceres, image files); the program
// loads it with dlopen only for a command that needs it, or to read or write a format
// that libcam::interop provides (mrcal's .cameramodel).
//
// The module exports three C functions, by these names:

#include "libcam/io/format_table.hpp"

namespace libcam::cli {

// The module's file name, in the program's folder in a build tree and in
// <libdir>/libcam/ once installed.
inline constexpr const char* kCommandsModuleFile = "libcam-commands.so";

// "libcam_commands_version": the LIBCAM_VERSION it was built from; the program refuses a
// module of another version (the two share C++ types, so they must come from one build).
inline constexpr const char* kVersionEntry = "libcam_commands_version";
using VersionEntry = const char* (*)();

// "libcam_run_commands": runs a whole command line, any command, as the program did
// before it was split; returns the exit code.
inline constexpr const char* kRunEntry = "libcam_run_commands";
using RunEntry = int (*)(int argc, char** argv);

// "libcam_install_formats": fills the program's format table through `install` (the
// program's own install_camera_format: the module's copy of libcam::io has a table of its
// own) with the readers and writers of libcam::interop.
inline constexpr const char* kInstallFormatsEntry = "libcam_install_formats";
using InstallFormatsEntry = void (*)(decltype(&install_camera_format) install);

}  // namespace libcam::cli
