#pragma once
// A plain table of observations, for a tool libcam has no reader for: each row one pixel
// where a known world point was seen, by a camera of a camera file (read_camera_set:
// its intrinsics and its pose, world to camera).
//
// CSV (any extension but .json), a header line naming the columns in any order:
//
//   view,camera,X,Y,Z,x,y
//   img0,cam0,0.0,0.0,2.0,321.0,240.0
//   img1,cam1,0.2,-0.1,1.0,370.0,190.5
//
//   camera   a camera of the camera file: its name there, else its position counting from
//            0 (as `--camera` takes it)
//   X,Y,Z    the point, in the camera file's world frame
//   x,y      where it was seen, in OpenCV's pixels (the top-left pixel's centre at (0, 0))
//   view     optional: the image the row belongs to, a free name grouping the rows of one
//            image (one camera each); without it, each camera's rows are one view named
//            after the camera
//
// Blank lines and lines starting with '#' are skipped; a field may be "double-quoted"
// ("" for a quote inside it). Every row is its own point (its id: the row's number,
// counting data rows from 1).
//
// JSON (.json): a list of objects with the same keys; camera a name or a position:
//
//   [{"view": "img0", "camera": "cam0", "X": 0, "Y": 0, "Z": 2, "x": 321, "y": 240}, ...]

#include <filesystem>

#include "libcam/io/observations.hpp"

namespace libcam {

// Throws FileError naming the table, the row, the column and the value; the camera file's
// own errors as read_camera_set gives them.
ObservationSet read_observation_table(const std::filesystem::path& table, const std::filesystem::path& camera_file);

}  // namespace libcam
