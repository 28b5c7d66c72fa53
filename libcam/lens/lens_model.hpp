#pragma once
// The table of lens models: one row per model, carrying everything the rest of libcam
// asks about a model (as mrcal's MRCAL_LENSMODEL_LIST, with more columns). A lens model
// maps a point in the camera frame (OpenCV axes: x right, y down, z forward) to a
// normalised image point m; the intrinsic matrix K then maps m to a pixel. Each model
// lives in its own header as a stateless struct templated on the scalar type (see
// pinhole.hpp); lens_models.hpp ties each row to its implementation and checks that
// they agree. Adding a model: docs/adding-a-lens-model.md.
//
// This header is plain C++ (no Eigen): file readers, the command line and the tests
// read the table without compiling any model.

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

// Every model: its enum name and the struct template implementing it (lens_models.hpp).
#define LIBCAM_LENS_MODEL_LIST(_)      \
    _(Pinhole, PinholeLens)             \
    _(OpenCv4, OpenCv4Lens)             \
    _(OpenCv5, OpenCv5Lens)             \
    _(OpenCv8, OpenCv8Lens)             \
    _(OpenCv12, OpenCv12Lens)           \
    _(OpenCv14, OpenCv14Lens)           \
    _(Fisheye, FisheyeLens)             \
    _(Stereographic, StereographicLens) \
    _(Lonlat, LonlatLens)               \
    _(Latlon, LatlonLens)               \
    _(DoubleSphere, DoubleSphereLens)   \
    _(Ucm, UcmLens)                     \
    _(Eucm, EucmLens)                   \
    _(Mei, MeiLens)                     \
    _(Fov, FovLens)                     \
    _(ThinPrismFisheye, ThinPrismFisheyeLens) \
    _(RadTanThinPrismFisheye, RadTanThinPrismFisheyeLens) \
    _(Equisolid, EquisolidLens) \
    _(Cahvor, CahvorLens) \
    _(Cahvore, CahvoreLens) \
    _(LensPolynomial, LensPolynomialLens) \
    _(SplinedStereographic, SplinedStereographicLens) \
    _(Cylindrical, CylindricalLens) \
    _(Ptlens, PtlensLens) \
    _(OcamCalib, OcamCalibLens) \
    /* division model (Fitzgibbon; COLMAP's DIVISION) */ \
    _(Division, DivisionLens) \
    /* WoodScape's fisheye */ \
    _(ThetaPolynomial, ThetaPolynomialLens) \
    /* NVIDIA's F-theta */ \
    _(FTheta, FThetaLens) \
    _(FThetaForward, FThetaForwardLens) \
    /* Brown's radial-tangential lens to r^8 (Metashape's, RealityCapture's brown4) */ \
    _(BrownK4, BrownK4Lens) \
    /* fisheye projections with PanoTools' radial polynomial (lensfun's, Hugin's) */ \
    _(EquidistantRadial, EquidistantRadialLens) \
    _(EquisolidRadial, EquisolidRadialLens) \
    _(StereographicRadial, StereographicRadialLens)

namespace libcam {

enum class LensType {
#define LIBCAM_LENS_ENUM(id, model) id,
    LIBCAM_LENS_MODEL_LIST(LIBCAM_LENS_ENUM)
#undef LIBCAM_LENS_ENUM
};

inline constexpr int kMaxLensCoefficients = 14;
// The coefficient count of a model whose count depends on its configuration
// (SPLINED_STEREOGRAPHIC: 4 + 2 Nx Ny); its row names only the configuration values
// that lead its coefficients, and the model checks the count (check_coefficients).
inline constexpr int kVariableCoefficientCount = -1;

// How a pixel's ray is found.
enum class Inverse {
    ClosedForm,  // a formula (Model::unproject)
    Solved,      // the certified iterative solver of lens/undistort.hpp, through Model::distort
};

// Which OpenCV function projects the model (the reference `libcam verify` and the tests
// check against), if any.
enum class OpenCvFunction {
    None,
    ProjectPoints,  // cv::projectPoints, cv::undistortPoints
    Fisheye,        // cv::fisheye::projectPoints, cv::fisheye::undistortPoints
    Omnidir,        // cv::omnidir::projectPoints, cv::omnidir::undistortPoints (xi, then k1 k2 p1 p2)
};

// Models that nest: a model contains every model of its family with a lower or equal
// rank (its coefficient list is theirs followed by more, which can be zero), so a
// camera of the lower model is exactly a camera of the higher one.
enum class LensFamily {
    Perspective,  // PINHOLE < OPENCV4 < OPENCV5 < OPENCV8 < OPENCV12 < OPENCV14
    Fisheye,  // FISHEYE < RAD_TAN_THIN_PRISM_FISHEYE (k1..k4 are its k0..k3)
    Stereographic,
    Lonlat,
    Latlon,
    DoubleSphere,
    Unified,  // UCM < MEI (UCM for xi <= 1 is DOUBLE_SPHERE with alpha = 0; not nested, as xi > 1 is not)
    Eucm,
    Fov,
    ThinPrismFisheye,  // not FISHEYE's: its coefficients interleave (k1 k2 p1 p2 k3 k4)
    Equisolid,
    Cahvor,
    Cahvore,  // not CAHVOR's: CAHVOR is CAHVORE with zero E and a linearity of 1, not 0
    LensPolynomial,
    Splined,
    Cylindrical,
    Ptlens,  // lens databases
    OcamCalib,
    Division,  // Fitzgibbon's one-parameter division model
    ThetaPolynomial,  // WoodScape's: not FISHEYE's, whose powers of theta are odd
    FTheta,  // NVIDIA's: not FISHEYE_LENS_POLYNOMIAL's, whose angle has the other sign and no affine
    FThetaForward,  // NVIDIA's with the forward polynomial the reference: not THETA_POLYNOMIAL's (no affine, degree 4)
    BrownK4,  // not PINHOLE's: its k4 multiplies r^8 where OPENCV8's divides (simplest_equal_lens gives OPENCV5 for k4 = 0)
    EquidistantRadial,  // not FISHEYE's: its polynomial has odd powers of the angle, and another order
};

// Whether `libcam fit` tries the model as a candidate.
enum class FitCandidate {
    No,
    Always,
    WideScenes,  // only for a scene reaching kWideSceneAngleDeg (fit/fit.hpp) off the axis
    OnRequest,   // only when the user names it (libcam fit --model): not in the simplest-first chain
};

// Coefficients mrcal keeps in its name for the model rather than among the intrinsics,
// each as _<coefficient name>=<value>: how many lead the coefficient list and how many end it.
struct InMrcalName {
    int leading = 0;
    int trailing = 0;
};

// The names of a model's coefficients, in the model's order.
struct CoefficientNames {
    std::array<std::string_view, kMaxLensCoefficients> names{};
    int count = 0;

    constexpr CoefficientNames() = default;
    template <class... Names>
    constexpr CoefficientNames(Names... list) : names{list...}, count(static_cast<int>(sizeof...(Names))) {}
    constexpr std::span<const std::string_view> view() const { return {names.data(), static_cast<std::size_t>(count)}; }
};

struct LensInfo {
    LensType type;
    std::string_view name;  // in libcam's files; mrcal's name without "LENSMODEL_" where mrcal has it
    CoefficientNames coefficients;
    int num_coefficients;     // = coefficients.count (checked below), or kVariableCoefficientCount
    bool sees_behind_camera;  // can project points with z <= 0 (mrcal's can_project_behind_camera)
    Inverse inverse;
    // The same model in other libraries; empty where the library lacks it.
    OpenCvFunction opencv;
    std::string_view mrcal;   // "LENSMODEL_..." (mrcal_in_name: its configuration)
    std::string_view colmap;  // COLMAP's camera model name (its pixel centres are at +0.5)
    std::string_view kalibr;  // Kalibr's camera_model-distortion_model
    std::string_view basalt;  // basalt's camera type
    std::string_view also_named{};  // its other names (programs', papers'), in words
    LensFamily family;
    int family_rank;  // see LensFamily
    FitCandidate fit;
    // A model that measures m in millimetres on a sensor (FISHEYE_LENS_POLYNOMIAL) trades the
    // scale of K for its coefficients, which the data cannot tell apart: a fit holds square
    // pixels at (image width / this) pixels per millimetre and fits cx, cy and the
    // coefficients. 0 (every other model): fx and fy are fitted.
    double fit_sensor_width_mm = 0.0;
    // Leading coefficients a fit holds at 0 (FISHEYE_LENS_POLYNOMIAL's k0, which would leave
    // the directions about the axis without a pixel).
    int fit_held_coefficients = 0;
    InMrcalName mrcal_in_name{};
};

// The table. Its order is the order of LensType, and among fit candidates the order from
// the simplest model to the richest.
inline constexpr LensInfo kLensTable[] = {
    {.type = LensType::Pinhole, .name = "PINHOLE", .coefficients = {}, .num_coefficients = 0,
     .sees_behind_camera = false, .inverse = Inverse::ClosedForm, .opencv = OpenCvFunction::ProjectPoints,
     .mrcal = "LENSMODEL_PINHOLE", .colmap = "PINHOLE", .kalibr = "pinhole-none", .basalt = "pinhole",
     .also_named = "Blender's perspective camera", .family = LensFamily::Perspective, .family_rank = 0,
     .fit = FitCandidate::Always},
    {.type = LensType::OpenCv4, .name = "OPENCV4", .coefficients = {"k1", "k2", "p1", "p2"}, .num_coefficients = 4,
     .sees_behind_camera = false, .inverse = Inverse::Solved, .opencv = OpenCvFunction::ProjectPoints,
     .mrcal = "LENSMODEL_OPENCV4", .colmap = "OPENCV", .kalibr = "pinhole-radtan", .basalt = "",
     .family = LensFamily::Perspective, .family_rank = 1, .fit = FitCandidate::Always},
    {.type = LensType::OpenCv5, .name = "OPENCV5", .coefficients = {"k1", "k2", "p1", "p2", "k3"},
     .num_coefficients = 5, .sees_behind_camera = false, .inverse = Inverse::Solved,
     .opencv = OpenCvFunction::ProjectPoints, .mrcal = "LENSMODEL_OPENCV5", .colmap = "", .kalibr = "", .basalt = "",
     .family = LensFamily::Perspective, .family_rank = 2, .fit = FitCandidate::Always},
    {.type = LensType::OpenCv8, .name = "OPENCV8", .coefficients = {"k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6"},
     .num_coefficients = 8, .sees_behind_camera = false, .inverse = Inverse::Solved,
     .opencv = OpenCvFunction::ProjectPoints, .mrcal = "LENSMODEL_OPENCV8", .colmap = "FULL_OPENCV", .kalibr = "",
     .basalt = "pinhole-radtan8", .family = LensFamily::Perspective, .family_rank = 3, .fit = FitCandidate::Always},
    {.type = LensType::OpenCv12, .name = "OPENCV12",
     .coefficients = {"k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6", "s1", "s2", "s3", "s4"}, .num_coefficients = 12,
     .sees_behind_camera = false, .inverse = Inverse::Solved, .opencv = OpenCvFunction::ProjectPoints,
     .mrcal = "LENSMODEL_OPENCV12", .colmap = "", .kalibr = "", .basalt = "", .family = LensFamily::Perspective,
     .family_rank = 4, .fit = FitCandidate::Always},
    {.type = LensType::OpenCv14, .name = "OPENCV14",
     .coefficients = {"k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6", "s1", "s2", "s3", "s4", "tauX", "tauY"},
     .num_coefficients = 14, .sees_behind_camera = false, .inverse = Inverse::Solved,
     .opencv = OpenCvFunction::ProjectPoints, .mrcal = "", .colmap = "", .kalibr = "", .basalt = "",
     .family = LensFamily::Perspective, .family_rank = 5, .fit = FitCandidate::No},
    {.type = LensType::Fisheye, .name = "FISHEYE", .coefficients = {"k1", "k2", "k3", "k4"}, .num_coefficients = 4,
     .sees_behind_camera = true, .inverse = Inverse::Solved, .opencv = OpenCvFunction::Fisheye, .mrcal = "",
     .colmap = "OPENCV_FISHEYE", .kalibr = "pinhole-equi", .basalt = "kb4",
     .also_named = "Kannala-Brandt; Blender's FISHEYE_EQUIDISTANT (with zero coefficients)",
     .family = LensFamily::Fisheye, .family_rank = 0, .fit = FitCandidate::WideScenes},
    {.type = LensType::Stereographic, .name = "STEREOGRAPHIC", .coefficients = {}, .num_coefficients = 0,
     .sees_behind_camera = true, .inverse = Inverse::ClosedForm, .opencv = OpenCvFunction::None,
     .mrcal = "LENSMODEL_STEREOGRAPHIC", .colmap = "", .kalibr = "", .basalt = "", .family = LensFamily::Stereographic,
     .family_rank = 0, .fit = FitCandidate::WideScenes},
    {.type = LensType::Lonlat, .name = "LONLAT", .coefficients = {}, .num_coefficients = 0, .sees_behind_camera = true,
     .inverse = Inverse::ClosedForm, .opencv = OpenCvFunction::None, .mrcal = "LENSMODEL_LONLAT",
     .colmap = "EQUIRECTANGULAR",  // COLMAP's holds only the whole sphere (colmap_models.hpp)
     .kalibr = "", .basalt = "", .also_named = "equirectangular; Blender's EQUIRECTANGULAR",
     .family = LensFamily::Lonlat, .family_rank = 0, .fit = FitCandidate::No},
    {.type = LensType::Latlon, .name = "LATLON", .coefficients = {}, .num_coefficients = 0, .sees_behind_camera = true,
     .inverse = Inverse::ClosedForm, .opencv = OpenCvFunction::None, .mrcal = "LENSMODEL_LATLON", .colmap = "",
     .kalibr = "", .basalt = "", .family = LensFamily::Latlon, .family_rank = 0, .fit = FitCandidate::No},
    {.type = LensType::DoubleSphere, .name = "DOUBLE_SPHERE", .coefficients = {"xi", "alpha"}, .num_coefficients = 2,
     .sees_behind_camera = true, .inverse = Inverse::ClosedForm, .opencv = OpenCvFunction::None, .mrcal = "",
     .colmap = "", .kalibr = "ds-none", .basalt = "ds", .family = LensFamily::DoubleSphere, .family_rank = 0,
     .fit = FitCandidate::OnRequest},
    // basalt's "ucm" is this model with another K (its alpha = xi / (1 + xi), its focal
    // length 1 / (1 + xi) times this one's): not the same numbers, so not named here.
    {.type = LensType::Ucm, .name = "UCM", .coefficients = {"xi"}, .num_coefficients = 1, .sees_behind_camera = true,
     .inverse = Inverse::ClosedForm, .opencv = OpenCvFunction::Omnidir, .mrcal = "", .colmap = "", .kalibr = "omni-none",
     .basalt = "", .family = LensFamily::Unified, .family_rank = 0, .fit = FitCandidate::OnRequest},
    {.type = LensType::Eucm, .name = "EUCM", .coefficients = {"alpha", "beta"}, .num_coefficients = 2,
     .sees_behind_camera = true, .inverse = Inverse::ClosedForm, .opencv = OpenCvFunction::None, .mrcal = "",
     .colmap = "", .kalibr = "eucm-none", .basalt = "eucm", .family = LensFamily::Eucm, .family_rank = 0,
     .fit = FitCandidate::OnRequest},
    {.type = LensType::Mei, .name = "MEI", .coefficients = {"xi", "k1", "k2", "p1", "p2"}, .num_coefficients = 5,
     .sees_behind_camera = true, .inverse = Inverse::Solved, .opencv = OpenCvFunction::Omnidir, .mrcal = "",
     .colmap = "", .kalibr = "omni-radtan", .basalt = "", .also_named = "camodocal's and VINS-Fusion's MEI",
     .family = LensFamily::Unified, .family_rank = 1, .fit = FitCandidate::OnRequest},
    // COLMAP's and Kalibr's take points in front of the camera only; basalt's and this
    // one go on behind it (the same map where both are defined).
    {.type = LensType::Fov, .name = "FOV", .coefficients = {"omega"}, .num_coefficients = 1, .sees_behind_camera = true,
     .inverse = Inverse::ClosedForm, .opencv = OpenCvFunction::None, .mrcal = "", .colmap = "FOV",
     .kalibr = "pinhole-fov", .basalt = "fov", .family = LensFamily::Fov, .family_rank = 0, .fit = FitCandidate::No},
    {.type = LensType::ThinPrismFisheye, .name = "THIN_PRISM_FISHEYE",
     .coefficients = {"k1", "k2", "p1", "p2", "k3", "k4", "sx1", "sy1"}, .num_coefficients = 8,
     .sees_behind_camera = true, .inverse = Inverse::Solved, .opencv = OpenCvFunction::None, .mrcal = "",
     .colmap = "THIN_PRISM_FISHEYE", .kalibr = "", .basalt = "", .family = LensFamily::ThinPrismFisheye,
     .family_rank = 0, .fit = FitCandidate::OnRequest},
    {.type = LensType::RadTanThinPrismFisheye, .name = "RAD_TAN_THIN_PRISM_FISHEYE",
     .coefficients = {"k0", "k1", "k2", "k3", "k4", "k5", "p0", "p1", "s0", "s1", "s2", "s3"},
     .num_coefficients = 12, .sees_behind_camera = true, .inverse = Inverse::Solved,
     .opencv = OpenCvFunction::None, .mrcal = "", .colmap = "RAD_TAN_THIN_PRISM_FISHEYE", .kalibr = "",
     .basalt = "", .also_named = "Project Aria's Fisheye624", .family = LensFamily::Fisheye, .family_rank = 1,
     .fit = FitCandidate::OnRequest},
    // Blender's FISHEYE_EQUISOLID panoramic camera (convert/blender_camera.hpp).
    {.type = LensType::Equisolid, .name = "EQUISOLID", .coefficients = {}, .num_coefficients = 0,
     .sees_behind_camera = true, .inverse = Inverse::ClosedForm, .opencv = OpenCvFunction::None, .mrcal = "",
     .colmap = "", .kalibr = "", .basalt = "", .also_named = "equal-area fisheye; Blender's FISHEYE_EQUISOLID",
     .family = LensFamily::Equisolid, .family_rank = 0, .fit = FitCandidate::OnRequest},
    // JPL's CAHVOR (the C, A, H, V of its files are the pinhole and pose; O the optical
    // axis; R the radial terms).
    {.type = LensType::Cahvor, .name = "CAHVOR", .coefficients = {"alpha", "beta", "r0", "r1", "r2"},
     .num_coefficients = 5, .sees_behind_camera = false, .inverse = Inverse::Solved, .opencv = OpenCvFunction::None,
     .mrcal = "LENSMODEL_CAHVOR", .colmap = "", .kalibr = "", .basalt = "", .family = LensFamily::Cahvor,
     .family_rank = 0, .fit = FitCandidate::No},
    // JPL's CAHVORE as libmrcal 2.2 has it (central: see cahvore.hpp); mrcal keeps the
    // linearity in the model's name, LENSMODEL_CAHVORE_linearity=L.
    {.type = LensType::Cahvore, .name = "CAHVORE",
     .coefficients = {"alpha", "beta", "r0", "r1", "r2", "e0", "e1", "e2", "linearity"}, .num_coefficients = 9,
     .sees_behind_camera = false, .inverse = Inverse::Solved, .opencv = OpenCvFunction::None,
     .mrcal = "LENSMODEL_CAHVORE", .colmap = "", .kalibr = "", .basalt = "", .family = LensFamily::Cahvore,
     .family_rank = 0, .fit = FitCandidate::No, .mrcal_in_name = {.trailing = 1}},
    // Blender's FISHEYE_LENS_POLYNOMIAL panoramic camera: the angle as a polynomial of the
    // radius on the sensor, in millimetres (convert/blender_camera.hpp).
    {.type = LensType::LensPolynomial, .name = "FISHEYE_LENS_POLYNOMIAL", .coefficients = {"k0", "k1", "k2", "k3", "k4"},
     .num_coefficients = 5, .sees_behind_camera = true, .inverse = Inverse::ClosedForm,
     .opencv = OpenCvFunction::None, .mrcal = "", .colmap = "", .kalibr = "", .basalt = "",
     .also_named = "Blender's FISHEYE_LENS_POLYNOMIAL", .family = LensFamily::LensPolynomial, .family_rank = 0,
     .fit = FitCandidate::OnRequest, .fit_sensor_width_mm = 36.0, .fit_held_coefficients = 1},
    // mrcal's splined model of a real lens; mrcal keeps the configuration (the first four
    // coefficients) in the model's name, LENSMODEL_SPLINED_STEREOGRAPHIC_order=3_Nx=..., and
    // the control points in the intrinsics.
    {.type = LensType::SplinedStereographic, .name = "SPLINED_STEREOGRAPHIC",
     .coefficients = {"order", "Nx", "Ny", "fov_x_deg"}, .num_coefficients = kVariableCoefficientCount,
     .sees_behind_camera = true, .inverse = Inverse::Solved, .opencv = OpenCvFunction::None,
     .mrcal = "LENSMODEL_SPLINED_STEREOGRAPHIC", .colmap = "", .kalibr = "", .basalt = "",
     .family = LensFamily::Splined, .family_rank = 0, .fit = FitCandidate::No, .mrcal_in_name = {.leading = 4}},
    // The panorama with straight verticals: LONLAT across, a pinhole down.
    {.type = LensType::Cylindrical, .name = "CYLINDRICAL", .coefficients = {}, .num_coefficients = 0,
     .sees_behind_camera = true, .inverse = Inverse::ClosedForm, .opencv = OpenCvFunction::None, .mrcal = "",
     .colmap = "", .kalibr = "", .basalt = "",
     .also_named = "OpenCV's stitching cv::detail::CylindricalWarper; Hugin's and PTGui's cylindrical",
     .family = LensFamily::Cylindrical, .family_rank = 0, .fit = FitCandidate::No},
    // PanoTools' a b c in units of the focal length: lensfun's ptlens
    // and Hugin's a b c, rescaled (lens/ptlens.hpp).
    {.type = LensType::Ptlens, .name = "PTLENS", .coefficients = {"a", "b", "c"}, .num_coefficients = 3,
     .sees_behind_camera = false, .inverse = Inverse::Solved, .opencv = OpenCvFunction::None, .mrcal = "",
     .colmap = "", .kalibr = "", .basalt = "",
     .also_named = "PanoTools' and Hugin's a b c, lensfun's ptlens (rescaled to the focal length, d = 1)",
     .family = LensFamily::Ptlens, .family_rank = 0, .fit = FitCandidate::No},
    // Scaramuzza's OCamCalib (ocamcalib.hpp): the ray's forward part a polynomial of the
    // radius in the sensor plane, behind an affine [1 e; d c]; the toolbox's files
    // (calib_results.txt), py-OCamCalib's JSON and camodocal's SCARAMUZZA hold it.
    {.type = LensType::OcamCalib, .name = "OCAMCALIB",
     .coefficients = {"c", "d", "e", "k1", "k2", "k3", "k4", "k5"}, .num_coefficients = 8,
     .sees_behind_camera = true, .inverse = Inverse::ClosedForm, .opencv = OpenCvFunction::None, .mrcal = "",
     .colmap = "", .kalibr = "", .basalt = "",
     .also_named = "Scaramuzza's omnidirectional model; camodocal's SCARAMUZZA; py-OCamCalib's",
     .family = LensFamily::OcamCalib, .family_rank = 0, .fit = FitCandidate::No},
    // Fitzgibbon's one-parameter division model: u = m / (1 + k |m|^2). COLMAP's
    // SIMPLE_DIVISION is it with fx = fy (convert/colmap_models.cpp).
    {.type = LensType::Division, .name = "DIVISION", .coefficients = {"k"}, .num_coefficients = 1,
     .sees_behind_camera = true, .inverse = Inverse::ClosedForm, .opencv = OpenCvFunction::None, .mrcal = "",
     .colmap = "DIVISION", .kalibr = "", .basalt = "",
     .also_named = "Fitzgibbon's division model; COLMAP's SIMPLE_DIVISION; OpenImuCameraCalibrator's and Theia's "
                   "DIVISION_UNDISTORTION",
     .family = LensFamily::Division, .family_rank = 0, .fit = FitCandidate::No},
    // ---- WoodScape's fisheye: the radius as a polynomial of every power of the angle
    // (its calibrations give the coefficients in pixels, with fx = 1: theta_polynomial.hpp).
    {.type = LensType::ThetaPolynomial, .name = "THETA_POLYNOMIAL", .coefficients = {"k1", "k2", "k3", "k4"},
     .num_coefficients = 4, .sees_behind_camera = true, .inverse = Inverse::Solved,
     .opencv = OpenCvFunction::None, .mrcal = "", .colmap = "", .kalibr = "", .basalt = "",
     .also_named = "Valeo's WoodScape radial_poly (rho = k1 theta + k2 theta^2 + k3 theta^3 + k4 theta^4)",
     .family = LensFamily::ThetaPolynomial, .family_rank = 0, .fit = FitCandidate::No},
    // NVIDIA's F-theta (ftheta.hpp): the angle a polynomial of the sensor radius, behind an
    // affine [c d; e 1], bounded by max_angle; DriveWorks' rig files, NCore, 3DGUT and
    // gsplat hold it (their backward polynomial the reference).
    {.type = LensType::FTheta, .name = "FTHETA",
     .coefficients = {"c", "d", "e", "k1", "k2", "k3", "k4", "k5", "max_angle"}, .num_coefficients = 9,
     .sees_behind_camera = true, .inverse = Inverse::ClosedForm, .opencv = OpenCvFunction::None, .mrcal = "",
     .colmap = "", .kalibr = "", .basalt = "",
     .also_named = "NVIDIA's F-theta (DriveWorks' ftheta, NCore's, 3DGUT's and gsplat's FThetaCameraModel, "
                   "pixeldistance-to-angle)",
     .family = LensFamily::FTheta, .family_rank = 0, .fit = FitCandidate::No},
    // The same with its forward polynomial the reference (ftheta_forward.hpp): the sensor
    // radius a polynomial of the angle, the ray solved.
    {.type = LensType::FThetaForward, .name = "FTHETA_FORWARD",
     .coefficients = {"c", "d", "e", "k1", "k2", "k3", "k4", "k5", "max_angle"}, .num_coefficients = 9,
     .sees_behind_camera = true, .inverse = Inverse::Solved, .opencv = OpenCvFunction::None, .mrcal = "",
     .colmap = "", .kalibr = "", .basalt = "",
     .also_named = "NVIDIA's F-theta with its forward polynomial the reference (angle-to-pixeldistance, "
                   "NCore's ANGLE_TO_PIXELDIST)",
     .family = LensFamily::FThetaForward, .family_rank = 0, .fit = FitCandidate::No},
    // Brown's radial-tangential lens with a fourth radial coefficient (brown_k4.hpp): OPENCV5
    // with k4 r^8 added to the radial factor, as Metashape's frame camera and RealityCapture's
    // brown4 and brown4t2 have it.
    {.type = LensType::BrownK4, .name = "BROWN_K4", .coefficients = {"k1", "k2", "p1", "p2", "k3", "k4"},
     .num_coefficients = 6, .sees_behind_camera = false, .inverse = Inverse::Solved,
     .opencv = OpenCvFunction::None, .mrcal = "", .colmap = "", .kalibr = "", .basalt = "",
     .also_named = "Metashape's frame camera with k4; RealityCapture's brown4 and brown4t2; nerfstudio's perspective "
                   "camera with k4 (1 + k1 r^2 + k2 r^4 + k3 r^6 + k4 r^8)",
     .family = LensFamily::BrownK4, .family_rank = 0, .fit = FitCandidate::No},
    // Fisheye projections followed by PanoTools' radial polynomial of the projected radius,
    // r (1 + c r + b r^2 + a r^3 + k2 r^4) (fisheye_radial.hpp): lensfun's fisheye lenses
    // with their ptlens, poly3 or poly5 distortion, and Hugin's fisheye projections with a b c.
    {.type = LensType::EquidistantRadial, .name = "EQUIDISTANT_RADIAL", .coefficients = {"a", "b", "c", "k2"},
     .num_coefficients = 4, .sees_behind_camera = true, .inverse = Inverse::Solved,
     .opencv = OpenCvFunction::None, .mrcal = "", .colmap = "", .kalibr = "", .basalt = "",
     .also_named = "lensfun's fisheye lenses with distortion; Hugin's fisheye (f2, f3) with a b c",
     .family = LensFamily::EquidistantRadial, .family_rank = 0, .fit = FitCandidate::No},
    {.type = LensType::EquisolidRadial, .name = "EQUISOLID_RADIAL", .coefficients = {"a", "b", "c", "k2"},
     .num_coefficients = 4, .sees_behind_camera = true, .inverse = Inverse::Solved,
     .opencv = OpenCvFunction::None, .mrcal = "", .colmap = "", .kalibr = "", .basalt = "",
     .also_named = "lensfun's equisolid lenses with distortion; Hugin's equisolid (f21) with a b c",
     .family = LensFamily::Equisolid, .family_rank = 1, .fit = FitCandidate::No},
    {.type = LensType::StereographicRadial, .name = "STEREOGRAPHIC_RADIAL", .coefficients = {"a", "b", "c", "k2"},
     .num_coefficients = 4, .sees_behind_camera = true, .inverse = Inverse::Solved,
     .opencv = OpenCvFunction::None, .mrcal = "", .colmap = "", .kalibr = "", .basalt = "",
     .also_named = "lensfun's stereographic lenses with distortion; Hugin's stereographic (f10) with a b c",
     .family = LensFamily::Stereographic, .family_rank = 1, .fit = FitCandidate::No},
};

namespace detail {
constexpr bool lens_table_is_consistent() {
    std::size_t index = 0;
    for (const LensInfo& info : kLensTable) {
        if (static_cast<std::size_t>(info.type) != index++) return false;  // rows in LensType's order
        const bool variable = info.num_coefficients == kVariableCoefficientCount;
        if (!variable && info.coefficients.count != info.num_coefficients) return false;
        for (int i = 0; i < info.coefficients.count; ++i) {
            if (info.coefficients.names[static_cast<std::size_t>(i)].empty()) return false;
        }
        // Every family has its simplest model, of rank 0, which names it (lens_family_base).
        bool has_base = false;
        for (const LensInfo& base : kLensTable) {
            has_base = has_base || (base.family == info.family && base.family_rank == 0);
        }
        if (!has_base) return false;
        // The names in mrcal's name are the table's: the trailing ones only where the count is fixed.
        const InMrcalName in_name = info.mrcal_in_name;
        if (in_name.leading < 0 || in_name.trailing < 0 || (variable && in_name.trailing > 0) ||
            in_name.leading + in_name.trailing > info.coefficients.count ||
            (info.mrcal.empty() && in_name.leading + in_name.trailing > 0)) {
            return false;
        }
    }
    return true;
}
}  // namespace detail
static_assert(detail::lens_table_is_consistent(),
              "kLensTable: a row out of LensType's order, a coefficient count that disagrees with its names, "
              "a family without a model of rank 0, or coefficients in mrcal's name that the row does not name");

// Every model, in the order of the table.
constexpr std::span<const LensInfo> lens_models() { return kLensTable; }
constexpr const LensInfo& lens_info(LensType type) { return kLensTable[static_cast<std::size_t>(type)]; }

// mrcal's name for a lens of the model, its configuration included
// (LENSMODEL_CAHVORE_linearity=0.37); "..." for each value when `coefficients` holds too
// few (mrcal's unconfigured name, LENSMODEL_CAHVORE_linearity=...). Empty when mrcal lacks
// the model.
std::string mrcal_model_name(LensType type, std::span<const double> coefficients = {});

// The table's values as words (libcam models): "closed-form", "solved"; "always",
// "wide-scenes", "on-request", "no"; OpenCV's projection function
// ("cv::fisheye::projectPoints"; empty for None).
std::string_view to_string(Inverse inverse);
std::string_view to_string(FitCandidate fit);
std::string_view to_string(OpenCvFunction function);

// Accepts "PINHOLE" and mrcal's "LENSMODEL_PINHOLE"; nullopt for an unknown name.
std::optional<LensType> lens_type_from_name(std::string_view name);

// OpenCV's radial-tangential model (cv::projectPoints) with `count` coefficients (4, 5,
// 8, 12 or 14): how a distortion vector tells its model; nothing for another count.
std::optional<LensType> opencv_model_with(std::size_t count);

// The simplest model of `type`'s family (its rank 0), which names the family: PINHOLE
// for OPENCV8, UCM for MEI, FISHEYE for RAD_TAN_THIN_PRISM_FISHEYE.
constexpr const LensInfo& lens_family_base(LensType type) {
    for (const LensInfo& info : kLensTable) {
        if (info.family == lens_info(type).family && info.family_rank == 0) return info;
    }
    return lens_info(type);  // not reached: every family has one (lens_table_is_consistent)
}

// Does `container` express every camera of `model` exactly (same family, higher or equal rank)?
constexpr bool lens_contains(LensType container, LensType model) {
    const LensInfo &a = lens_info(container), &b = lens_info(model);
    return a.family == b.family && a.family_rank >= b.family_rank;
}

struct Lens;
// The simplest model of the lens's family that is this very lens: a model below it whose
// coefficients are its leading ones, the rest exactly 0 (OPENCV8 with k3..k6 = 0 is
// OPENCV4; PINHOLE when every coefficient is 0; BROWN_K4 with k4 = 0, whose k4 is not
// OPENCV8's, is OPENCV5 or simpler). The lens itself when there is none.
// Writers use it to hold a lens in a format that lacks its model, dropping nothing.
Lens simplest_equal_lens(const Lens& lens);

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
