#pragma once
// The bridge to mrcal (libmrcal, C): its .cameramodel files, and its projection and
// unprojection as a reference for libcam's own.

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/camera/camera.hpp"

namespace libcam {

// mrcal's name for the lens, "LENSMODEL_..."; throws NotRepresentable for a lens that
// mrcal does not model.
std::string mrcal_lensmodel_name(const Lens& lens);

// The .cameramodel text for a camera. libmrcal's own writer prints numbers with "%f"
// (six decimals), which would silently round fx, the pose and every coefficient, so
// libcam prints the same layout with every digit and then parses the text with
// libmrcal's parser and checks it reads back bit for bit. Throws NotRepresentable for
// what .cameramodel cannot hold (skew, a lens mrcal lacks).
std::string format_cameramodel(const Camera& camera);
// The same with the solve the camera came from, as mrcal-calibrate-cameras writes it:
// 'optimization_inputs' (io/observations.hpp's mrcal_optimization_inputs, the bytes
// literal) and 'icam_intrinsics', the camera of the solve this model is.
std::string format_cameramodel(const Camera& camera, const std::string& optimization_inputs, int icam_intrinsics);

// Parses .cameramodel text with libmrcal's parser; the parser's own diagnostic (it
// prints to stderr) is captured into the FileError message.
Camera parse_cameramodel(std::string_view text, const std::string& source);

// mrcal_project and mrcal_unproject on points packed as mrcal stores them (x, y[, z]
// doubles one point after the other), with no conversion: what `libcam bench` times.
// Throw NotRepresentable for a lens mrcal lacks, Error if mrcal fails.
void mrcal_project_packed(const Camera& camera, std::span<const double> points_xyz, std::span<double> pixels_xy);
void mrcal_unproject_packed(const Camera& camera, std::span<const double> pixels_xy, std::span<double> directions_xyz);

// Projects camera-frame points with mrcal_project. mrcal does not flag points behind
// the camera; every result here is marked valid and the caller compares. A point mrcal
// refuses to project (it refuses a whole call for one) gets a NaN pixel.
std::vector<Vec2> mrcal_project_points(const Camera& camera, const std::vector<Vec3>& camera_points);

// Whether mrcal_unproject handles the lens: mrcal has the model and its gradients (mrcal
// 2.2 has none for CAHVORE, and its mrcal_unproject refuses that model).
bool mrcal_unprojects(const Lens& lens);

// Unprojects OpenCV pixels with mrcal_unproject: camera-frame directions, not normalised.
std::vector<Vec3> mrcal_unproject_pixels(const Camera& camera, const std::vector<Vec2>& pixels);

}  // namespace libcam
