#pragma once
// The camera-file format that needs libmrcal, plugged into libcam::io's format table
// (io/format_table.hpp): cameramodel (libmrcal's parser, interop/mrcal.hpp).

#include "libcam/io/format_table.hpp"

namespace libcam {

// Fills io's row for cameramodel, so that read_camera_file, parse_camera, format_camera
// and write_camera_file (io/camera_file.hpp) handle it. Call it once at the start of the
// program (calling it again changes nothing). Until it is called that format throws
// FileError naming this function: the call is explicit because a registration made by a
// static initialiser in a static library is dropped by the linker when nothing else in
// its object file is used.
void register_interop_formats();

// The same through `install`: a library loaded at run time that links its own copy of
// libcam::io fills the program's table by calling the program's install_camera_format.
using CameraFormatInstaller = decltype(&install_camera_format);
void register_interop_formats(CameraFormatInstaller install);

}  // namespace libcam
