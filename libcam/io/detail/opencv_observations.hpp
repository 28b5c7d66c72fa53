#pragma once
// The observations in the files OpenCV's calibration sample writes (out_camera_data.yml
// or .xml, samples/cpp/tutorial_code/calib3d/camera_calibration): the board's corners
// it found in each image, the board's pose in each, and the errors it computed.
//
//   board_width: 9                       corners per row (2011's spelling: board_Width)
//   board_height: 6                      rows of corners
//   square_size: 50.                     between corners, in the user's unit
//   camera_matrix, distortion_coefficients, fisheye_model   the camera (opencv_storage.hpp)
//   avg_reprojection_error: 0.38         sqrt(sum |d|^2 / N) over every corner of every view
//   per_view_reprojection_errors         N x 1 floats: sqrt(sum |d|^2 / n) over one view's corners
//   extrinsic_parameters                 N x 6: rvec | tvec per view (board to camera)
//   image_points                         N x (board_width * board_height), dt "2f": the corners
//   grid_points                          the board's corners as the sample solved them
//                                        (calibrateCameraRO), 3 floats each; optional
//
// The 2011 sample spelled them image_Width, board_Width, square_Size, Camera_Matrix,
// Avg_Reprojection_Error, Per_View_Reprojection_Errors, Extrinsic_Parameters, Image_points
// (both are read). Some copies of the sample write extrinsic_parameters as 3N x 4, a
// stacked [R | t] per view; that is read too.
//
// The board without grid_points is the sample's calcBoardCornerPositions for a
// chessboard or a circles grid, corner i * board_width + j at (j, i, 0) * square_size,
// computed in float as the sample does. The sample does not write which pattern it used:
// an asymmetric circles grid's file reads right only with its grid_points.

#include <filesystem>

#include "libcam/io/observations.hpp"

namespace libcam {

// Throws FileError naming the file, the key and the value; for a file with OpenCV's
// camera but no image_points, saying that it holds none.
ObservationSet read_opencv_observations(const std::filesystem::path& file, std::string_view text,
                                        const ObservationReadOptions& options);

}  // namespace libcam
