#include "libcam/uncertainty/projection_uncertainty.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "libcam/error.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

// The inverse of a symmetric positive-definite matrix, scaled to a unit diagonal first
// (the intrinsics mix focal lengths of thousands of pixels with coefficients of 0.01:
// unscaled, their conditioning would be the units'). Throws InvalidArgument saying `what`
// is not determined when the matrix is singular or near it.
Eigen::MatrixXd inverse_of_information(const Eigen::MatrixXd& information, const std::string& what) {
    const Eigen::Index n = information.rows();
    const Eigen::VectorXd diagonal = information.diagonal();
    if ((diagonal.array() <= 0.0).any() || !diagonal.allFinite()) {
        throw InvalidArgument(what + ": the observations do not determine it");
    }
    const Eigen::VectorXd scale = diagonal.cwiseSqrt().cwiseInverse();
    const Eigen::MatrixXd scaled = scale.asDiagonal() * information * scale.asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scaled);
    // A unit-diagonal matrix's eigenvalues sum to n; one below n 1e-12 is rounding.
    if (eigen.info() != Eigen::Success || eigen.eigenvalues()(0) <= 1e-12 * static_cast<double>(n)) {
        throw InvalidArgument(what + ": the observations do not determine it (too few views or corners, or all "
                                     "alike)");
    }
    const Eigen::MatrixXd inverse = eigen.eigenvectors() * eigen.eigenvalues().cwiseInverse().asDiagonal() *
                                    eigen.eigenvectors().transpose();
    return scale.asDiagonal() * inverse * scale.asDiagonal();
}

// d(residuals)/d(the bow's two parameters), from d(residuals)/d(the pose's shift), which is
// d/d(the board point in the camera's frame): the bow lifts a corner along the board's z,
// R's third column in the camera's frame.
Eigen::MatrixXd by_bow(const ResidualDerivatives& d, const Pose& pose, const std::vector<FitSample>& observations,
                       const SolvedCalibration::BoardBow& bow) {
    Eigen::MatrixXd out(d.by_pose.rows(), 2);
    const Vec3 lift = pose.R.col(2);
    for (std::size_t i = 0; i < observations.size(); ++i) {
        const auto row = static_cast<Eigen::Index>(2 * i);
        const Eigen::Vector2d by_lift = d.by_pose.block(row, 3, 2, 3) * lift;
        const double xr = observations[i].point.x() / bow.width, yr = observations[i].point.y() / bow.height;
        out.block(row, 0, 2, 1) = by_lift * (4.0 * xr * (1.0 - xr));
        out.block(row, 1, 2, 1) = by_lift * (4.0 * yr * (1.0 - yr));
    }
    return out;
}

// Each observation's weight on both of its rows.
void weigh_rows(ResidualDerivatives& d, const std::vector<double>& weights) {
    for (std::size_t i = 0; i < weights.size(); ++i) {
        const auto row = static_cast<Eigen::Index>(2 * i);
        d.residuals.segment(row, 2) *= weights[i];
        d.by_intrinsics.middleRows(row, 2) *= weights[i];
        d.by_pose.middleRows(row, 2) *= weights[i];
    }
}

}  // namespace

double worst_direction_stdev(const Mat2& c) {
    const double a = c(0, 0), b = c(1, 0), d = c(1, 1);
    return std::sqrt(0.5 * (a + d) + std::sqrt(0.25 * (a - d) * (a - d) + b * b));
}

ProjectionUncertainty::ProjectionUncertainty(const SolvedCalibration& solved)
    : camera_(solved.camera), parameters_(parameters_of(solved.camera)) {
    camera_.pose = Pose{};
    parameters_.candidate.held = solved.held;
    directions_ = free_directions(parameters_.candidate);
    unprojector_ = std::make_shared<const Unprojector<double>>(camera_, UnprojectorOptions{.table_nodes = 4, .threads = 1});
    if (!solved.weights.empty() && solved.weights.size() != solved.views.size()) {
        throw InvalidArgument("uncertainty: weights for " + std::to_string(solved.weights.size()) + " views of " +
                              std::to_string(solved.views.size()));
    }
    if (solved.bow && !(solved.bow->width > 0.0 && solved.bow->height > 0.0)) {
        throw InvalidArgument("uncertainty: the board's bow over an extent of " + format_short(solved.bow->width) +
                              " x " + format_short(solved.bow->height) + ": both must be above 0");
    }
    const Eigen::Index count = directions_.cols() + (solved.bow ? 2 : 0);
    Eigen::MatrixXd schur = Eigen::MatrixXd::Zero(count, count);
    std::vector<double> residuals;
    for (std::size_t v = 0; v < solved.views.size(); ++v) {
        const FitView& view = solved.views[v];
        if (view.observations.empty()) continue;
        ResidualDerivatives d = residual_derivatives(parameters_.candidate, camera_.size, parameters_.params, view.pose,
                                                     view.observations);
        if (!solved.weights.empty()) {
            if (solved.weights[v].size() != view.observations.size()) {
                throw InvalidArgument("uncertainty: view " + view.name + ": " + std::to_string(solved.weights[v].size()) +
                                      " weights for " + std::to_string(view.observations.size()) + " observations");
            }
            weigh_rows(d, solved.weights[v]);
        }
        // The columns of the free parameters: the intrinsics' free directions, then the bow's.
        if (solved.bow) {
            const Eigen::MatrixXd bow = by_bow(d, view.pose, view.observations, *solved.bow);
            Eigen::MatrixXd free(d.by_intrinsics.rows(), count);
            free << d.by_intrinsics * directions_, bow;
            d.by_intrinsics = std::move(free);
        } else {
            d.by_intrinsics = d.by_intrinsics * directions_;
        }
        residuals.insert(residuals.end(), d.residuals.data(), d.residuals.data() + d.residuals.size());
        observations_ += view.observations.size();
        // J^T J's blocks: U (intrinsics), W (intrinsics by this pose), V (this pose). The
        // Schur complement U - sum W V^-1 W^T is the information of the intrinsics alone.
        const Eigen::MatrixXd pose_information = d.by_pose.transpose() * d.by_pose;
        const Eigen::MatrixXd coupling = d.by_intrinsics.transpose() * d.by_pose;
        const Eigen::Matrix<double, 6, 6> pose_inverse =
            inverse_of_information(pose_information, "the pose of view " + view.name);
        schur += d.by_intrinsics.transpose() * d.by_intrinsics;
        schur -= coupling * pose_inverse * coupling.transpose();
        poses_.push_back(view.pose);
        pose_inverse_.push_back(pose_inverse);
        pose_coupling_.push_back(pose_inverse * coupling.transpose());
    }
    if (residuals.empty()) throw InvalidArgument("uncertainty: no observations");
    // As mrcal: the standard deviation (about their mean) of every residual coordinate.
    double mean = 0.0;
    for (const double r : residuals) mean += r;
    mean /= static_cast<double>(residuals.size());
    double spread = 0.0;
    for (const double r : residuals) spread += (r - mean) * (r - mean);
    noise_px_ = std::sqrt(spread / static_cast<double>(residuals.size()));
    intrinsics_inverse_ = inverse_of_information(
        0.5 * (schur + schur.transpose()), "the " + std::string(parameters_.candidate.name) + " intrinsics");
}

std::vector<ParameterSpread> ProjectionUncertainty::parameters() const {
    const std::vector<std::string> names = parameter_names(parameters_.candidate);
    const Eigen::Index free = directions_.cols();
    const Eigen::MatrixXd covariance =
        directions_ * intrinsics_inverse_.topLeftCorner(free, free) * directions_.transpose();
    std::vector<ParameterSpread> out;
    for (std::size_t i = 0; i < parameters_.params.size(); ++i) {
        const auto k = static_cast<Eigen::Index>(i);
        out.push_back({names[i], parameters_.params[i], noise_px_ * std::sqrt(std::max(0.0, covariance(k, k)))});
    }
    return out;
}

std::vector<Mat2> ProjectionUncertainty::covariances(const std::vector<Vec2>& pixels, double distance) const {
    if (!(distance > 0.0)) throw InvalidArgument("distance: " + format_short(distance) + ": must be above 0");
    const bool at_infinity = std::isinf(distance);
    const PreparedCamera prepared(camera_);
    // The camera-frame points of the pixels with a ray that projects back.
    std::vector<std::size_t> index;
    std::vector<FitSample> points;
    for (std::size_t k = 0; k < pixels.size(); ++k) {
        Vec3 ray;
        if (!unprojector_->unproject(pixels[k], UnprojectMethod::Exact, ray)) continue;
        const Vec3 direction = ray.normalized();
        const Vec3 point = at_infinity ? direction : Vec3(distance * direction);
        if (!prepared.project_camera_point(point).valid) continue;
        index.push_back(k);
        points.push_back({point, pixels[k]});
    }
    const auto n = static_cast<Eigen::Index>(points.size());
    // dq/d(intrinsics), then each view's share of dq/d(its pose): the point is the mean over
    // the views of each one's board point carried back by its pose.
    const ResidualDerivatives at_camera =
        residual_derivatives(parameters_.candidate, camera_.size, parameters_.params, Pose{}, points);
    // 2n x count: dq/d(free) - sum_v dq/dpose_v V^-1 W^T; the bow does not move the point (it
    // is carried by the boards' poses, not lifted with their corners): its columns start at 0.
    Eigen::MatrixXd reduced = Eigen::MatrixXd::Zero(2 * n, intrinsics_inverse_.cols());
    reduced.leftCols(directions_.cols()) = at_camera.by_intrinsics * directions_;
    std::vector<Mat2> from_poses(points.size(), Mat2::Zero());  // sum_v dq/dpose_v V^-1 dq/dpose_v^T
    const double share = 1.0 / static_cast<double>(poses_.size());
    std::vector<FitSample> on_board(points.size());
    for (std::size_t v = 0; v < poses_.size(); ++v) {
        // At infinity only the boards' rotations carry a direction: the pose without its
        // translation carries the board's direction back to the camera's.
        const Pose pose = at_infinity ? Pose{poses_[v].R, Vec3::Zero()} : poses_[v];
        for (std::size_t k = 0; k < points.size(); ++k) {
            on_board[k] = {pose.R.transpose() * (points[k].point - pose.t), points[k].pixel};
        }
        ResidualDerivatives d = residual_derivatives(parameters_.candidate, camera_.size, parameters_.params, pose, on_board);
        d.by_pose *= share;
        if (at_infinity) d.by_pose.rightCols(3).setZero();
        reduced.noalias() -= d.by_pose * pose_coupling_[v];
        for (Eigen::Index k = 0; k < n; ++k) {
            const Eigen::Matrix<double, 2, 6> g = d.by_pose.middleRows(2 * k, 2);
            from_poses[static_cast<std::size_t>(k)] += g * pose_inverse_[v] * g.transpose();
        }
    }
    const double noise2 = noise_px_ * noise_px_;
    const Mat2 unknown = Mat2::Constant(std::numeric_limits<double>::quiet_NaN());
    std::vector<Mat2> out(pixels.size(), unknown);
    for (Eigen::Index k = 0; k < n; ++k) {
        const Eigen::MatrixXd a = reduced.middleRows(2 * k, 2);
        const Mat2 intrinsic = a * intrinsics_inverse_ * a.transpose();
        out[index[static_cast<std::size_t>(k)]] = noise2 * (intrinsic + from_poses[static_cast<std::size_t>(k)]);
    }
    return out;
}

std::vector<double> ProjectionUncertainty::sigma_px(const std::vector<Vec2>& pixels, double distance) const {
    std::vector<double> out;
    for (const Mat2& c : covariances(pixels, distance)) out.push_back(worst_direction_stdev(c));
    return out;
}

}  // namespace libcam
