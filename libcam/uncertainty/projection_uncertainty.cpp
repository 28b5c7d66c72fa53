#include "libcam/uncertainty/projection_uncertainty.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>

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

// [v]x: the cross product's matrix, v x w = [v]x w. A turn by a small rotation vector w
// moves a point p by w x p = -[p]x w.
Mat3 cross_matrix(const Vec3& v) {
    Mat3 m;
    m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
    return m;
}

// One camera of the solve: its parameters and where its columns are among the free ones.
struct Member {
    const SolvedCalibration* solved = nullptr;
    CameraParameters parameters;
    Eigen::MatrixXd directions;
    Eigen::Index intrinsics_at = 0;
    Eigen::Index pose_at = -1;  // -1: its pose from the reference is not solved
};

// Each observation's weight on both of its rows.
void weigh_rows(ResidualDerivatives& d, const std::vector<double>& weights) {
    for (std::size_t i = 0; i < weights.size(); ++i) {
        const auto row = static_cast<Eigen::Index>(2 * i);
        d.residuals.segment(row, 2) *= weights[i];
        d.by_intrinsics.middleRows(row, 2) *= weights[i];
        d.by_pose.middleRows(row, 2) *= weights[i];
    }
}

// One view's rows of J (each observation's weight applied): by the free parameters (its
// camera's intrinsics, its camera's pose where solved, the bow) and by its board pose, a
// turn and a shift in the reference frame (`to_reference`: the board to that frame).
struct ViewRows {
    Eigen::VectorXd residuals;
    Eigen::MatrixXd by_free;
    Eigen::MatrixXd by_frame;
};

ViewRows view_rows(const Member& member, std::size_t v, const Pose& to_reference, bool rig,
                   const std::optional<SolvedCalibration::BoardBow>& bow, Eigen::Index bow_at, Eigen::Index count) {
    const SolvedCalibration& camera = *member.solved;
    const FitView& view = camera.views[v];
    ResidualDerivatives d = residual_derivatives(member.parameters.candidate, camera.camera.size, member.parameters.params,
                                                 view.pose, view.observations);
    if (!camera.weights.empty()) {
        if (camera.weights[v].size() != view.observations.size()) {
            throw InvalidArgument("uncertainty: view " + view.name + ": " + std::to_string(camera.weights[v].size()) +
                                  " weights for " + std::to_string(view.observations.size()) + " observations");
        }
        weigh_rows(d, camera.weights[v]);
    }
    // d.by_pose's shift columns are d(residuals)/d(the corner in the camera's frame).
    const Pose to_camera = rig ? camera.camera.pose : Pose{};
    const Eigen::Index rows = d.residuals.size();
    ViewRows out{d.residuals, Eigen::MatrixXd::Zero(rows, count), Eigen::MatrixXd(rows, 6)};
    out.by_free.middleCols(member.intrinsics_at, member.directions.cols()) = d.by_intrinsics * member.directions;
    for (std::size_t k = 0; k < view.observations.size(); ++k) {
        const auto row = static_cast<Eigen::Index>(2 * k);
        const Eigen::Matrix<double, 2, 3> by_corner = d.by_pose.block(row, 3, 2, 3);
        const Vec3& corner = view.observations[k].point;
        const Eigen::Matrix<double, 2, 3> by_reference = by_corner * to_camera.R;
        out.by_frame.block(row, 0, 2, 3) = -by_reference * cross_matrix(to_reference.R * corner + to_reference.t);
        out.by_frame.block(row, 3, 2, 3) = by_reference;
        if (member.pose_at >= 0) {
            out.by_free.block(row, member.pose_at, 2, 3) = -by_corner * cross_matrix(view.pose.R * corner + view.pose.t);
            out.by_free.block(row, member.pose_at + 3, 2, 3) = by_corner;
        }
        if (bow) {
            // The bow lifts a corner along the board's z, R's third column in the camera's frame.
            const Eigen::Vector2d by_lift = by_corner * view.pose.R.col(2);
            const double xr = corner.x() / bow->width, yr = corner.y() / bow->height;
            out.by_free.block(row, bow_at, 2, 1) = by_lift * (4.0 * xr * (1.0 - xr));
            out.by_free.block(row, bow_at + 1, 2, 1) = by_lift * (4.0 * yr * (1.0 - yr));
        }
    }
    return out;
}

}  // namespace

double worst_direction_stdev(const Mat2& c) {
    const double a = c(0, 0), b = c(1, 0), d = c(1, 1);
    return std::sqrt(0.5 * (a + d) + std::sqrt(0.25 * (a - d) * (a - d) + b * b));
}

ProjectionUncertainty::ProjectionUncertainty(const SolvedCalibration& solved)
    : camera_(solved.camera), parameters_(parameters_of(solved.camera)) {
    const bool rig = !solved.frames.empty();
    from_reference_ = rig ? solved.camera.pose : Pose{};
    camera_.pose = Pose{};
    parameters_.candidate.held = solved.held;
    directions_ = free_directions(parameters_.candidate);
    unprojector_ = std::make_shared<const Unprojector<double>>(camera_, UnprojectorOptions{.table_nodes = 4, .threads = 1});
    if (solved.bow && !(solved.bow->width > 0.0 && solved.bow->height > 0.0)) {
        throw InvalidArgument("uncertainty: the board's bow over an extent of " + format_short(solved.bow->width) +
                              " x " + format_short(solved.bow->height) + ": both must be above 0");
    }
    if (!rig && !solved.others.empty()) throw InvalidArgument("uncertainty: other cameras without the boards' poses");

    // The free parameters' columns: every camera's intrinsics, the solved poses, the bow.
    std::vector<Member> members{{&solved, parameters_, directions_, 0, -1}};
    for (const SolvedCalibration& other : solved.others) {
        Member member{&other, parameters_of(other.camera), {}, 0, -1};
        member.parameters.candidate.held = other.held;
        member.directions = free_directions(member.parameters.candidate);
        members.push_back(std::move(member));
    }
    Eigen::Index count = 0;
    for (Member& member : members) {
        member.intrinsics_at = count;
        count += member.directions.cols();
    }
    for (Member& member : members) {
        if (rig && member.solved->pose_solved) member.pose_at = std::exchange(count, count + 6);
    }
    pose_at_ = members[0].pose_at;
    const Eigen::Index bow_at = count;
    if (solved.bow) count += 2;

    // Each board pose's views (camera, view): a board alone per view, or mrcal's frames.
    const std::size_t frame_count = rig ? solved.frames.size() : solved.views.size();
    std::vector<std::vector<std::pair<const Member*, std::size_t>>> seen_in(frame_count);
    for (const Member& member : members) {
        const SolvedCalibration& camera = *member.solved;
        if (!camera.weights.empty() && camera.weights.size() != camera.views.size()) {
            throw InvalidArgument("uncertainty: weights for " + std::to_string(camera.weights.size()) + " views of " +
                                  std::to_string(camera.views.size()));
        }
        if (rig && camera.frame_of_view.size() != camera.views.size()) {
            throw InvalidArgument("uncertainty: frames for " + std::to_string(camera.frame_of_view.size()) +
                                  " views of " + std::to_string(camera.views.size()));
        }
        for (std::size_t v = 0; v < camera.views.size(); ++v) {
            const int frame = rig ? camera.frame_of_view[v] : static_cast<int>(v);
            if (frame < 0 || static_cast<std::size_t>(frame) >= frame_count) {
                throw InvalidArgument("uncertainty: view " + camera.views[v].name + ": frame " + std::to_string(frame) +
                                      " is not one of the " + std::to_string(frame_count));
            }
            if (!camera.views[v].observations.empty()) seen_in[static_cast<std::size_t>(frame)].emplace_back(&member, v);
        }
    }

    Eigen::MatrixXd schur = Eigen::MatrixXd::Zero(count, count);
    frame_coupling_sum_ = Eigen::MatrixXd::Zero(6, count);
    std::vector<double> residuals;
    for (std::size_t f = 0; f < frame_count; ++f) {
        if (seen_in[f].empty()) continue;
        // J's rows of this board pose's views: U (the free parameters), W (them by the
        // pose), V (the pose). The Schur complement U - sum W V^-1 W^T is the information
        // of the free parameters alone.
        Eigen::Matrix<double, 6, 6> pose_information = Eigen::Matrix<double, 6, 6>::Zero();
        Eigen::MatrixXd coupling = Eigen::MatrixXd::Zero(count, 6);
        for (const auto& [member, v] : seen_in[f]) {
            const FitView& view = member->solved->views[v];
            const ViewRows rows = view_rows(*member, v, rig ? solved.frames[f] : view.pose, rig, solved.bow,
                                            bow_at, count);
            residuals.insert(residuals.end(), rows.residuals.data(), rows.residuals.data() + rows.residuals.size());
            observations_ += view.observations.size();
            schur += rows.by_free.transpose() * rows.by_free;
            coupling += rows.by_free.transpose() * rows.by_frame;
            pose_information += rows.by_frame.transpose() * rows.by_frame;
        }
        const auto& [first, first_view] = seen_in[f].front();
        const std::string named = rig ? "frame " + std::to_string(f) : "view " + first->solved->views[first_view].name;
        const Eigen::Matrix<double, 6, 6> pose_inverse = inverse_of_information(pose_information, "the pose of " + named);
        schur -= coupling * pose_inverse * coupling.transpose();
        frame_inverse_sum_ += pose_inverse;
        frame_coupling_sum_ += pose_inverse * coupling.transpose();
        ++frames_;
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
    // dq/d(the free parameters) - dq/d(the board poses) V^-1 W^T, and dq/d(the board
    // poses) V^-1 dq/d(the board poses)^T. The point is the mean over the boards of each
    // one's board point carried back by its pose: each board pose's turn w and shift s (in
    // the reference frame) move that mean by (w x p + s) / (the number of boards), p the
    // point in the reference frame, then the camera's pose carries it into the camera.
    const ResidualDerivatives at_camera =
        residual_derivatives(parameters_.candidate, camera_.size, parameters_.params, Pose{}, points);
    Eigen::MatrixXd reduced = Eigen::MatrixXd::Zero(2 * n, intrinsics_inverse_.cols());
    reduced.leftCols(directions_.cols()) = at_camera.by_intrinsics * directions_;
    std::vector<Mat2> from_poses(points.size(), Mat2::Zero());
    const double share = 1.0 / static_cast<double>(frames_);
    for (Eigen::Index k = 0; k < n; ++k) {
        const Eigen::Matrix<double, 2, 3> by_point = at_camera.by_pose.block(2 * k, 3, 2, 3);
        const Vec3& point = points[static_cast<std::size_t>(k)].point;
        // At infinity only rotations carry a direction: the shifts move nothing.
        const Vec3 in_reference = from_reference_.R.transpose() * (at_infinity ? point : Vec3(point - from_reference_.t));
        if (pose_at_ >= 0) {
            reduced.block(2 * k, pose_at_, 2, 3) = -by_point * cross_matrix(point);
            if (!at_infinity) reduced.block(2 * k, pose_at_ + 3, 2, 3) = by_point;
        }
        Eigen::Matrix<double, 2, 6> by_board = Eigen::Matrix<double, 2, 6>::Zero();
        const Eigen::Matrix<double, 2, 3> by_reference = share * by_point * from_reference_.R;
        by_board.leftCols(3) = -by_reference * cross_matrix(in_reference);
        if (!at_infinity) by_board.rightCols(3) = by_reference;
        reduced.middleRows(2 * k, 2).noalias() -= by_board * frame_coupling_sum_;
        from_poses[static_cast<std::size_t>(k)] = by_board * frame_inverse_sum_ * by_board.transpose();
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
