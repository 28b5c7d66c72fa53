#pragma once
// The simplest lens model that reproduces a calibrated camera over a scene.
//
// The scene's pixels are unprojected through the source camera; each candidate model
// is fitted to those rays by nonlinear least squares in pixels (Ceres,
// Levenberg-Marquardt, with derivatives by automatic differentiation through the
// templated lens models), and measured on a denser set of the scene's pixels. The
// choice is the candidate with the fewest parameters whose largest error over the
// scene is within the tolerance.
//
// Candidates, simplest first:
//   FOV       the look-at (FOV) camera: PINHOLE with square pixels and the principal point
//             at the image centre; one parameter, the focal length f
//   PINHOLE   fx fy cx cy
//   OPENCV4, OPENCV5, OPENCV8, OPENCV12   fx fy cx cy and OpenCV's k1 k2 p1 p2 ...
//   FISHEYE, STEREOGRAPHIC   only for wide scenes (kWideSceneAngleDeg)
// or the models the user names (FitOptions::candidates), among them those the table
// offers on request only: DOUBLE_SPHERE, UCM, EUCM, MEI, EQUISOLID, the thin-prism
// fisheyes and Blender's FISHEYE_LENS_POLYNOMIAL (at a fixed sensor scale, LensInfo).
// Each candidate of the first chain starts from the solution of the one before it
// (whose model it contains), so a richer model never fits worse than a simpler one;
// a candidate that contains the source's own model also starts from the source, and
// keeps the better of the two.
//
// A start that leaves some observations outside its model's domain (a pinhole start of
// a model that can see wider) is fitted to the rest and fitted again from its solution,
// while that brings more of them in.
//
// A candidate's model must be valid at every sample: a distortion that folds over
// inside the scene (two rays on one pixel) is never accepted as a fit, although an
// unconstrained fit (mrcal-convert-lensmodel's) may end up there over wide scenes.
//
// The camera may also move (as in mrcal-convert-lensmodel): with CameraMotion::Rotation
// it may turn, so that a model's error can be traded for a small rotation; with
// RotationAndShift and points at finite depths it may also shift its centre, which
// only points at finite depth can tell apart (a shift does not move points at infinity).

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/fit/scene.hpp"
#include "libcam/stats/error_stats.hpp"

namespace libcam {

// A scene that reaches this far from the optical axis also gets the FISHEYE and
// STEREOGRAPHIC candidates: at 45 degrees a perspective image is already stretched
// 2x (1/cos^2) against its centre, where angle-based models start to pay off.
inline constexpr double kWideSceneAngleDeg = 45.0;

enum class CameraMotion {
    None,              // the fitted camera keeps the source's pose: a fit on rays alone
    Rotation,          // it may rotate about its centre
    RotationAndShift,  // it may also move its centre (needs points at finite depths)
};

// Parameters a fit holds, as OpenCV's calibrateCamera flags hold them: fx = fy
// (CALIB_FIX_ASPECT_RATIO with an aspect ratio of 1) and coefficients held at 0
// (CALIB_ZERO_TANGENT_DIST holds p1 and p2, CALIB_FIX_K3 k3, ...), by name, in any
// candidate that has them.
struct HeldParameters {
    bool square_pixels = false;
    std::vector<std::string> zero_coefficients;

    bool any() const { return square_pixels || !zero_coefficients.empty(); }
    // "fx = fy, p1 = 0, p2 = 0"; empty when nothing is held.
    std::string text() const;
};

struct Candidate {
    std::string_view name;  // "LOOK_AT", or the lens model's name
    LensType lens = LensType::Pinhole;
    bool look_at = false;  // a graphics (look-at) camera: square pixels, centred principal point, one focal length
    // From the table (LensInfo::fit_sensor_width_mm, fit_held_coefficients): for a model
    // measured in millimetres on a sensor, square pixels held at image width / this pixels
    // per millimetre (0: fx and fy fitted); and the leading coefficients held at 0.
    double sensor_width_mm = 0.0;
    int held_coefficients = 0;
    // Held by the user's request (a calibration with OpenCV's flags): the free parameters
    // below stay num_params(), the fit moves them only along free_directions().
    HeldParameters held{};

    // The pixels per millimetre a sensor-scale candidate holds for an image `width` wide.
    double sensor_pixels_per_mm(int width) const { return static_cast<double>(width) / sensor_width_mm; }
    // Free intrinsic parameters, in this order: f for FOV; else fx fy cx cy (cx cy alone at
    // sensor scale) and the lens's coefficients after the held ones.
    int num_params() const;
};

// The candidates for a scene whose rays reach `largest_angle_deg` from the optical axis,
// in order of complexity (FISHEYE and STEREOGRAPHIC last, for wide scenes only).
std::vector<Candidate> candidates_for(double largest_angle_deg);

// The candidate a user names: "LOOK_AT" (the graphics camera; "FOV" is its old name, taken
// for one more release) or a lens model the table lets
// `libcam fit` fit (FitCandidate other than No; OnRequest models only this way). Throws
// InvalidArgument for another name, listing the ones it takes.
Candidate candidate_named(std::string_view name);

// The names candidate_named takes, comma-separated, in the table's order.
std::string candidate_names();

// A pixel and the point that should land on it, in the source camera's frame (a unit
// ray for a fit on rays alone, or a point at a depth along it).
struct FitSample {
    Vec3 point = Vec3::Zero();
    Vec2 pixel = Vec2::Zero();
};

// One observation per pixel and depth: the pixel's unit ray times each depth, or the
// unit ray alone when `depths` is empty.
std::vector<FitSample> observations_of(const ScenePixels& pixels, const std::vector<double>& depths);

struct FittedModel {
    Candidate candidate;
    // The fitted camera in the source camera's frame: its pose is the fitted motion
    // (identity for CameraMotion::None). See camera_in_world().
    Camera camera;
    std::vector<double> params;  // the free intrinsic parameters (candidate.num_params())
    // Observations the candidate cannot project at all, even before fitting (points at
    // or behind the camera plane for a perspective model); left out of its fit.
    std::size_t unrepresentable = 0;
    int iterations = 0;
};

// The fitted camera as a camera of the world: the source's pose followed by the fit's motion.
Camera camera_in_world(const FittedModel& fitted, const Camera& source);

struct FitProgress {
    std::string_view model;
    int candidate_index = 0;  // 0-based
    int candidate_count = 0;
    int iteration = 0;  // the solver's iteration within this candidate
};
using ProgressCallback = std::function<void(const FitProgress&)>;

struct SolveOptions {
    CameraMotion motion = CameraMotion::None;
    // A candidate's fit stops once its RMS error is below this (fit_scene: 1e-3 of the
    // tolerance, where no decision can change any more); 0 runs it to convergence.
    double negligible_rms_px = 0.0;
    ProgressCallback progress;
    // Points every fitted model must still project, though they add no residual.
    // fit_scene passes the denser check samples of the boundary: a fit is often best
    // right at the edge of its model's valid domain, and without these it would fold
    // over between the fitting samples.
    std::vector<FitSample> must_project;
};

// Fits every candidate to the observations, each by Levenberg-Marquardt (Ceres).
// Observations must be non-empty.
std::vector<FittedModel> fit_candidates(const Camera& source, const std::vector<FitSample>& observations,
                                        const std::vector<Candidate>& candidates, const SolveOptions& options = {});

struct ModelError {
    // Over the observations the fitted model projects (stats/error_stats.hpp), except
    // that max_px is +infinity when some observation does not project, and rms_px when
    // none does.
    ErrorStats stats;
    std::size_t unprojected = 0;  // observations outside the fitted model's valid domain
    bool covers() const { return unprojected == 0; }
};

// |pixel - projection| for each observation through a fitted camera (in the source
// camera's frame); +infinity where the observation leaves the model's valid domain.
std::vector<double> reprojection_errors(const Camera& fitted, const std::vector<FitSample>& observations);

// Their statistics.
ModelError measure(const Camera& fitted, const std::vector<FitSample>& observations);

struct FitOptions {
    double tolerance_px = 1.0;
    CameraMotion motion = CameraMotion::None;
    // Distances along each ray at which points are placed (e.g. {near, far}); empty for
    // rays alone. RotationAndShift needs them.
    std::vector<double> depths;
    // The fitting lattice (mrcal's --gridn); default: sized to the scene.
    std::optional<Lattice> lattice;
    // The models to try (candidate_named), simplest first; empty: candidates_for the scene.
    std::vector<Candidate> candidates;
    ProgressCallback progress;
};

struct CandidateReport {
    FittedModel fit;
    double rms_px = 0.0;  // over the fitting samples (what the least squares minimised)
    double max_px = 0.0;  // over the denser check samples
    bool covers_scene = false;  // every check sample projects validly
    bool pass = false;          // covers_scene and max_px <= tolerance
};

struct FitReport {
    SceneSampling sampling;
    std::size_t fit_observations = 0;
    std::size_t check_observations = 0;
    double largest_angle_deg = 0.0;  // of the scene's rays from the optical axis
    std::vector<CandidateReport> candidates;
    std::optional<std::size_t> chosen;  // index into candidates; none when nothing passes
};

// Throws InvalidArgument for a bad scene, tolerance or depths (see FitOptions).
FitReport fit_scene(const Camera& source, const Scene& scene, const FitOptions& options);

}  // namespace libcam
