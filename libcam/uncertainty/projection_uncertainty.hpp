#pragma once
// How far a calibration can be trusted at each pixel: mrcal's projection uncertainty
// (mrcal 2.2's projection_uncertainty, what = 'worstdirection-stdev').
//
// The noise of the observed corners moves the solution (the intrinsics and every board
// pose); the uncertainty is how far that moves the projection of a point seen at a pixel.
// As mrcal computes it:
//   - the noise sigma: the standard deviation of the fit's residuals (x and y of every
//     observation used, each weighted by its observation's weight), not a stored value;
//   - the covariance of the solution: sigma^2 (J^T J)^-1, J the derivatives of every
//     residual by the intrinsics and by every board pose at the solution (the fit's own
//     residuals, differentiated automatically);
//   - the point: the pixel's ray, at `distance` along it (infinity: the direction alone),
//     carried into each board's frame by that board's solved pose. The boards are what
//     the data fix, the camera's frame is not: a principal-point shift and a common turn
//     of every board look alike to the corners. The point comes back into the camera as
//     the mean over the boards of each one carried back by its (perturbed) pose, then is
//     projected by the (perturbed) intrinsics;
//   - sigma_px: the square root of the larger eigenvalue of the 2x2 covariance of that
//     projection, the standard deviation in the worst direction.
// J^T J is inverted once, through the Schur complement over the poses (each board's pose
// touches only its own residuals), and every pixel reuses it.
//
// The board's bow (mrcal's calobject_warp) is free beside the intrinsics where the solve
// freed it (SolvedCalibration::bow). The difference from mrcal: it adds its small
// regularization terms to J, libcam has none (on mrcal's real OPENCV8 solve of a bowed
// board, sigma within 1e-4 of mrcal's; on a flat board without regularization, 1e-9).

#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "libcam/camera/unprojector.hpp"
#include "libcam/fit/observation_fit.hpp"

namespace libcam {

using Mat2 = Eigen::Matrix2d;

// A solved calibration: the camera (intrinsics and lens; its pose is not used) and each
// view's solved board pose (board to camera) with the observations it was solved from
// (board points, observed pixels).
struct SolvedCalibration {
    Camera camera;
    std::vector<FitView> views;
    // Each observation's weight (the tool's, mrcal's), as views' observations; empty:
    // every observation weighs 1.
    std::vector<std::vector<double>> weights;
    // What the fit held (fx = fy, coefficients at 0): the solution moves only along the
    // rest, and so does its uncertainty.
    HeldParameters held;
    // The board's bow, where the solve freed it (mrcal's calobject_warp): two parabolas
    // lifting the board out of its plane, z += w_x 4 x_r (1 - x_r) + w_y 4 y_r (1 - y_r),
    // x_r = x / width and y_r = y / height over the corners' extent (mrcal's
    // ref_calibration_object). Free beside the intrinsics: the data fix it as they do them.
    struct BoardBow {
        double width = 0.0;   // the corners' extent along x, in the board's unit
        double height = 0.0;  // and along y
    };
    std::optional<BoardBow> bow;
    // A camera solved together with others (mrcal's solves of several cameras), the boards'
    // poses shared between them. Empty for a camera solved alone, each of its views then a
    // board pose of its own. Otherwise: every board pose in the reference camera's frame
    // (mrcal's frames), the frame of each of `views`, camera.pose the camera's pose from
    // the reference (solved unless the camera is the reference), and the other cameras,
    // each as this struct (its camera.pose, views, frame_of_view, weights, held, pose_solved
    // used; its `frames` and `others` empty). The uncertainty is then the camera's in the
    // whole solve, as mrcal's: every camera's intrinsics, poses and observations count.
    std::vector<Pose> frames;
    std::vector<int> frame_of_view;
    bool pose_solved = false;
    std::vector<SolvedCalibration> others;
};

// One intrinsic parameter: its value and its standard deviation.
struct ParameterSpread {
    std::string name;
    double value = 0.0;
    double stdev = 0.0;
};

inline constexpr double kAtInfinity = std::numeric_limits<double>::infinity();

// The square root of the larger eigenvalue of a 2x2 covariance (mrcal's worst_direction_stdev).
double worst_direction_stdev(const Mat2& covariance);

class ProjectionUncertainty {
public:
    // Throws InvalidArgument when the camera's model cannot be differentiated
    // (parameters_of), an observation does not project, or the observations do not
    // determine the intrinsics (J^T J singular: too few views or corners).
    explicit ProjectionUncertainty(const SolvedCalibration& solved);

    // sigma: the noise the fit's residuals imply, per coordinate, in pixels.
    double observed_pixel_uncertainty_px() const { return noise_px_; }
    const Camera& camera() const { return camera_; }
    std::size_t observations() const { return observations_; }
    // The intrinsics with their standard deviations (0 for a held coefficient; fx and fy
    // the same when held equal).
    std::vector<ParameterSpread> parameters() const;

    // The covariance (pixels^2) of the projection of the point at `distance` (in the
    // board's unit) along the ray through each pixel; NaN where the pixel has no ray or
    // the point does not project.
    std::vector<Mat2> covariances(const std::vector<Vec2>& pixels, double distance = kAtInfinity) const;
    // Their worst-direction standard deviations (sigma_px).
    std::vector<double> sigma_px(const std::vector<Vec2>& pixels, double distance = kAtInfinity) const;

private:
    Camera camera_;
    // The exact unprojection with the smallest start table: a table over the whole image
    // would cost more than every pixel a report asks about.
    std::shared_ptr<const Unprojector<double>> unprojector_;
    CameraParameters parameters_;
    // The directions the intrinsics may move in (free_directions): J's intrinsics columns
    // are taken along them, and the covariance below is over them.
    Eigen::MatrixXd directions_;
    // The camera's pose from the rig's reference (the identity for a camera alone) and,
    // where it was solved, where its 6 columns start among the free parameters (else -1).
    Pose from_reference_;
    Eigen::Index pose_at_ = -1;
    double noise_px_ = 0.0;
    std::size_t observations_ = 0;
    std::size_t frames_ = 0;
    // The free parameters: the camera's intrinsics along their free directions first, then
    // the other cameras' intrinsics, the solved camera poses and the bow. The Schur
    // complement's inverse over them (their covariance / sigma^2); summed over the board
    // poses: V^-1 (each pose block's inverse) and V^-1 W^T (W: the free parameters by the
    // pose). Each board pose moves by a turn and a shift in the reference frame, which
    // moves the point every board carries back by the same amount: the sums are all the
    // projection needs.
    Eigen::MatrixXd intrinsics_inverse_;
    Eigen::Matrix<double, 6, 6> frame_inverse_sum_ = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::MatrixXd frame_coupling_sum_;
};

}  // namespace libcam
