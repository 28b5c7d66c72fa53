#include "libcam/calibrate/calibrate_pair.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "libcam/error.hpp"
#include "libcam/fit/least_squares.hpp"

namespace libcam {

namespace {

// The view of one camera's calibration that came from `image`, if it was used.
std::optional<std::size_t> view_of(const Calibration& c, const std::string& image) {
    for (std::size_t v = 0; v < c.views.size(); ++v) {
        if (c.views[v].image == image) return v;
    }
    return std::nullopt;
}

std::vector<FitSample> samples_of(const Calibration& c, std::size_t v) {
    const std::vector<Vec3> corners = c.board.corner_points();
    std::vector<FitSample> out;
    for (std::size_t k = 0; k < c.views[v].ids.size(); ++k) {
        out.push_back({corners[static_cast<std::size_t>(c.views[v].ids[k])], c.views[v].pixels[k]});
    }
    return out;
}

double median(std::vector<double> values) {
    std::nth_element(values.begin(), values.begin() + static_cast<long>(values.size() / 2), values.end());
    return values[values.size() / 2];
}

// The pair's pose where the joint fit starts: each view's second-camera board pose after
// the inverse of its first-camera one, the median of each rotation and shift component
// (a view whose board pose one camera solved poorly does not pull it).
Pose start_pose(const std::vector<Pose>& first, const std::vector<Pose>& second) {
    std::vector<std::vector<double>> components(6);
    for (std::size_t v = 0; v < first.size(); ++v) {
        const Pose relative = second[v].after(first[v].inverse());
        const Vec3 r = relative.rvec();
        for (int k = 0; k < 3; ++k) {
            components[static_cast<std::size_t>(k)].push_back(r[k]);
            components[static_cast<std::size_t>(3 + k)].push_back(relative.t[k]);
        }
    }
    Vec3 rvec, t;
    for (int k = 0; k < 3; ++k) {
        rvec[k] = median(components[static_cast<std::size_t>(k)]);
        t[k] = median(components[static_cast<std::size_t>(3 + k)]);
    }
    return Pose::from_rvec(rvec, t);
}

}  // namespace

PairCalibration calibrate_pair(const std::vector<BoardDetection>& first, const std::vector<BoardDetection>& second,
                               const BoardSpec& board, const CalibrationOptions& options) {
    if (first.size() != second.size()) {
        throw Error("calibrate: " + std::to_string(first.size()) + " images of the first camera and " +
                    std::to_string(second.size()) + " of the second: a pair needs one of each per view");
    }
    PairCalibration out;
    out.first = calibrate(first, board, options);
    out.second = calibrate(second, board, options);
    std::vector<std::vector<FitSample>> first_views, second_views;
    std::vector<Pose> first_poses, second_poses;
    for (std::size_t i = 0; i < first.size(); ++i) {
        const std::optional<std::size_t> a = view_of(out.first, first[i].image);
        const std::optional<std::size_t> b = view_of(out.second, second[i].image);
        if (!a || !b) continue;
        out.pairs.push_back(i);
        out.first_view_of_pair.push_back(*a);
        out.second_view_of_pair.push_back(*b);
        first_views.push_back(samples_of(out.first, *a));
        second_views.push_back(samples_of(out.second, *b));
        first_poses.push_back(out.first.chosen().poses[*a]);
        second_poses.push_back(out.second.chosen().poses[*b]);
    }
    if (out.pairs.size() < 2) {
        throw Error("calibrate: " + std::to_string(out.pairs.size()) +
                    " views were used by both cameras; a pair's pose needs at least two");
    }
    const ObservationCandidate& first_fit = out.first.chosen();
    const ObservationCandidate& second_fit = out.second.chosen();
    detail::PairState state;
    state.first.params = first_fit.params;
    for (const Pose& pose : first_poses) {
        state.first.rotations.push_back(pose.rvec());
        state.first.shifts.push_back(pose.t);
    }
    state.second = second_fit.params;
    const Pose relative = start_pose(first_poses, second_poses);
    state.rotation = relative.rvec();
    state.shift = relative.t;
    try {
        state = detail::solve_pair(first_fit.candidate, out.first.size, second_fit.candidate, out.second.size, first_views,
                                   second_views, state);
    } catch (const InvalidArgument& error) {
        throw Error(std::string("calibrate: the pair's joint fit failed: ") + error.what());
    }
    out.first_camera = detail::camera_from_params(first_fit.candidate, out.first.size, state.first.params, Pose{});
    out.second_camera = detail::camera_from_params(second_fit.candidate, out.second.size, state.second,
                                                   Pose::from_rvec(state.rotation, state.shift));
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t v = 0; v < out.pairs.size(); ++v) {
        const Pose board_pose = Pose::from_rvec(state.first.rotations[v], state.first.shifts[v]);
        out.board_poses.push_back(board_pose);
        Camera in_first = out.first_camera, in_second = out.second_camera;
        in_first.pose = board_pose;
        in_second.pose = out.second_camera.pose.after(board_pose);
        for (const double e : reprojection_errors(in_first, first_views[v])) sum += e * e;
        for (const double e : reprojection_errors(in_second, second_views[v])) sum += e * e;
        count += first_views[v].size() + second_views[v].size();
        const std::string& first_image = first[out.pairs[v]].image;
        const std::string& second_image = second[out.pairs[v]].image;
        out.first_views.push_back({first_image, in_first.pose, std::move(first_views[v])});
        out.second_views.push_back({second_image, in_second.pose, std::move(second_views[v])});
    }
    out.rms_px = std::sqrt(sum / static_cast<double>(count));
    return out;
}

SolvedCalibration solved_pair(const PairCalibration& pair, int side) {
    if (side != 0 && side != 1) throw InvalidArgument("solved_pair: side " + std::to_string(side) + " is not 0 or 1");
    const auto camera_alone = [&](int which) {
        SolvedCalibration out;
        out.camera = which == 0 ? pair.first_camera : pair.second_camera;
        out.views = which == 0 ? pair.first_views : pair.second_views;
        out.held = (which == 0 ? pair.first : pair.second).chosen().candidate.held;
        out.frame_of_view.resize(out.views.size());
        for (std::size_t v = 0; v < out.views.size(); ++v) out.frame_of_view[v] = static_cast<int>(v);
        out.pose_solved = which == 1;  // the first camera is the reference: its pose is the identity
        return out;
    };
    SolvedCalibration out = camera_alone(side);
    out.frames = pair.board_poses;
    out.others.push_back(camera_alone(1 - side));
    return out;
}

}  // namespace libcam
