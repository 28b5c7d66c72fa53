#pragma once
// The table of lens models, one place to add a model (as mrcal's
// MRCAL_LENSMODEL_LIST). A lens model maps a point in the camera frame
// (OpenCV axes: x right, y down, z forward) to a normalised image point m; the
// intrinsic matrix K then maps m to a pixel. Each model lives in its own header
// as a stateless struct templated on the scalar type (see pinhole.hpp).
//
// Columns: enum name, name in files (mrcal's, without "LENSMODEL_"),
// number of distortion coefficients, can it see points with z <= 0 (as mrcal's
// can_project_behind_camera, and FISHEYE, whose angle theta goes on past 90 degrees),
// the struct template implementing it (see lens_models.hpp, which checks the count).

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#define LIBCAM_LENS_MODEL_LIST(_)                                   \
    _(Pinhole, "PINHOLE", 0, false, PinholeLens)                    \
    _(Opencv4, "OPENCV4", 4, false, OpenCv4Lens)                    \
    _(Opencv5, "OPENCV5", 5, false, OpenCv5Lens)                    \
    _(Opencv8, "OPENCV8", 8, false, OpenCv8Lens)                    \
    _(Opencv12, "OPENCV12", 12, false, OpenCv12Lens)                \
    _(Opencv14, "OPENCV14", 14, false, OpenCv14Lens)                \
    _(Fisheye, "FISHEYE", 4, true, FisheyeLens)                     \
    _(Stereographic, "STEREOGRAPHIC", 0, true, StereographicLens)   \
    _(Lonlat, "LONLAT", 0, true, LonlatLens)                        \
    _(Latlon, "LATLON", 0, true, LatlonLens)

namespace libcam {

enum class LensType {
#define LIBCAM_LENS_ENUM(id, name, n, behind, model) id,
    LIBCAM_LENS_MODEL_LIST(LIBCAM_LENS_ENUM)
#undef LIBCAM_LENS_ENUM
};

struct LensInfo {
    LensType type;
    std::string_view name;
    int num_coefficients;
    bool sees_behind_camera;
};

// Every model, in the order of the table.
std::span<const LensInfo> lens_models();
const LensInfo& lens_info(LensType type);
// Accepts "PINHOLE" and mrcal's "LENSMODEL_PINHOLE"; nullopt for an unknown name.
std::optional<LensType> lens_type_from_name(std::string_view name);

// A lens: which model, and its distortion coefficients in the model's order
// (OpenCV's order for OpenCV's models).
struct Lens {
    LensType type = LensType::Pinhole;
    std::vector<double> coefficients;

    // Throws InvalidArgument naming `field` unless the count matches the model and
    // every coefficient is finite.
    void validate(const char* field = "dist") const;
    bool operator==(const Lens&) const = default;
};

}  // namespace libcam
