#pragma once
// COLMAP's camera models as libcam cameras, and back.
//
// Every COLMAP model is a libcam lens model with some parameters fixed: one focal
// length (SIMPLE_*: fx = fy = f), or coefficients held at zero (SIMPLE_RADIAL is OPENCV4
// with k2 = p1 = p2 = 0; RADIAL_FISHEYE is FISHEYE with k3 = k4 = 0). The table below
// says, for each COLMAP model, which libcam model it is and where its parameters go;
// the conversion is then exact both ways.
//
// Pixel centres: COLMAP puts the top-left pixel's centre at (0.5, 0.5), libcam (as
// OpenCV) at (0, 0). So libcam's cx, cy are COLMAP's minus 0.5, and a COLMAP pixel is
// libcam's plus 0.5. Skew: COLMAP has none.
//
// COLMAP's equirectangular camera (EQUIRECTANGULAR, id 17) takes the image size, w and h,
// as its parameters: it is libcam's LONLAT lens over the whole sphere, with
//   fx = w / (2 pi), fy = h / pi, cx = w / 2 - 0.5, cy = h / 2 - 0.5
// (COLMAP: x = (lon / (2 pi) + 0.5) w, y = (0.5 - elevation / pi) h, its elevation
// measured up, against OpenCV's y; libcam's latitude is measured down, so y = h / 2 +
// lat h / pi; the -0.5 is the pixel-centre shift). A LONLAT camera with any other K
// has no COLMAP model.
//
// COLMAP's models that libcam cannot express exactly (the division models
// SIMPLE_DIVISION and DIVISION) are not in the table: converting one is an error that
// says so.

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/lens/lens_model.hpp"

namespace libcam {

// The shift from a libcam (OpenCV) pixel to a COLMAP pixel, in both coordinates.
inline constexpr double kColmapPixelShift = 0.5;

struct ColmapModel {
    std::string_view name;        // COLMAP's
    int id;                       // COLMAP's model id (cameras.bin)
    std::string_view parameters;  // COLMAP's parameter list, in order
    LensType lens;                // the libcam model it is
    bool one_focal;               // f cx cy (fx = fy = f), else fx fy cx cy
    // Which of the lens's coefficients COLMAP's parameters after the principal point set,
    // in COLMAP's order; the lens's other coefficients are zero.
    std::array<int, kMaxLensCoefficients> coefficient{};
    int coefficient_count = 0;
    // EQUIRECTANGULAR: the parameters are the image's width and height, K follows from them.
    bool size_parameters = false;

    int num_params() const { return size_parameters ? 2 : (one_focal ? 1 : 2) + 2 + coefficient_count; }
};

// COLMAP's models (3.8's, and those COLMAP added later that libcam expresses exactly),
// in COLMAP's id order.
std::span<const ColmapModel> colmap_models();

// The model named `name` (COLMAP's spelling, e.g. "SIMPLE_RADIAL"); nullptr if none.
const ColmapModel* colmap_model(std::string_view name);

// The model of COLMAP's id `id` (cameras.bin's model_id); nullptr if none.
const ColmapModel* colmap_model_by_id(int id);

// Every model's name, comma-separated, and every id ("0 to 11, 14 to 16"), for messages.
std::string colmap_model_names();
std::string colmap_model_ids();

// The model a camera file written for COLMAP uses for `lens`: the one the lens table
// names for it (OPENCV for OPENCV4, OPENCV_FISHEYE for FISHEYE), else the first
// two-focal model whose lens contains it (FULL_OPENCV for OPENCV5); OPENCV12 and OPENCV14
// as FULL_OPENCV when their coefficients past the eighth are 0. Throws NotRepresentable,
// naming COLMAP's models, when none holds the lens.
const ColmapModel& colmap_model_for(const Lens& lens);

// The camera COLMAP's model and parameters describe, at the origin (identity pose).
// Throws InvalidArgument for an unknown model, a wrong parameter count, or a parameter
// that is not a number, naming it.
Camera camera_from_colmap(std::string_view model, std::span<const double> params, const ImageSize& size);

struct ColmapCamera {
    std::string_view model;
    std::vector<double> params;
};

// The camera's intrinsics as COLMAP's model and parameters: the model `model` names, or
// by default the one COLMAP users know for the camera's lens model (OPENCV for OPENCV4,
// OPENCV_FISHEYE for FISHEYE, ...; FULL_OPENCV for OPENCV5, which it contains). Throws
// InvalidArgument for an unknown model name, NotRepresentable when that model cannot express the camera exactly (a skew, fx != fy
// for a one-focal model, a coefficient the model holds at zero, a lens COLMAP lacks),
// saying which.
ColmapCamera colmap_from_camera(const Camera& camera, std::optional<std::string_view> model = std::nullopt);

}  // namespace libcam
