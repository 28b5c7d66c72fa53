#include "libcam/calibrate/mrcal_solve.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/io/observations.hpp"
#include "libcam/lens/lens_model.hpp"

namespace libcam {

namespace {

// Why mrcal, which frees every intrinsic or none, cannot take the candidate's fit as it
// was solved; empty where it can.
std::string held_in(const Candidate& candidate) {
    if (candidate.look_at) return "the model is a graphics camera (one focal length, the centre held)";
    if (candidate.sensor_width_mm > 0.0) return "the model's pixels are held square at the sensor's scale";
    if (candidate.held_coefficients > 0) return "the model holds its leading coefficients at 0";
    if (candidate.held.any()) return "the fit held " + candidate.held.text();
    return "";
}

void require_free(const Candidate& candidate, const char* camera) {
    const std::string held = held_in(candidate);
    if (!held.empty()) {
        throw NotRepresentable(std::string("mrcal frees every intrinsic of a camera or none: ") + camera + held +
                               ", which mrcal's solve would free");
    }
}

// The board as mrcal's and the shift of each libcam board pose that makes it so: the
// board's first corner, which mrcal puts at the origin.
struct MrcalBoard {
    ObservedBoard board;
    std::vector<Vec3> points;
    Vec3 origin = Vec3::Zero();
};

MrcalBoard mrcal_board(const BoardSpec& spec) {
    const std::vector<Vec3> corners = spec.corner_points();
    const int inset = spec.kind == BoardKind::Charuco ? 1 : 0;
    MrcalBoard out;
    out.board.width = spec.columns - inset;
    out.board.height = spec.rows - inset;
    out.board.spacing = spec.square;
    out.origin = corners.front();
    for (const Vec3& corner : corners) out.points.push_back(corner - out.origin);
    return out;
}

// A pose of libcam's board as a pose of mrcal's: X_cam = R (p + origin) + t.
Pose mrcal_pose(const Pose& board_pose, const Vec3& origin) {
    Pose out = board_pose;
    out.t = board_pose.R * origin + board_pose.t;
    return out;
}

// One view's corners: the kept ones as inliers, the outliers dropped weighed -1.
void add_view(ObservationSet& set, const CalibrationView& view, int camera, const Pose& pose, int frame, bool solved) {
    const int index = static_cast<int>(set.views.size());
    set.views.push_back({view.image, camera, pose, frame, solved});
    for (std::size_t k = 0; k < view.ids.size(); ++k) {
        set.observations.push_back({.view = index, .point = view.ids[k], .pixel = view.pixels[k]});
    }
    for (std::size_t k = 0; k < view.outlier_ids.size(); ++k) {
        set.observations.push_back(
            {.view = index, .point = view.outlier_ids[k], .pixel = view.outlier_pixels[k], .weight = -1.0, .inlier = false});
    }
}

ObservationSet board_set(const MrcalBoard& board) {
    ObservationSet set;
    set.tool = ObservationTool::Mrcal;
    set.board = board.board;
    set.points = board.points;
    for (std::size_t i = 0; i < set.points.size(); ++i) set.point_ids.push_back(static_cast<std::int64_t>(i));
    return set;
}

}  // namespace

std::string mrcal_solve_inputs(const Calibration& c) {
    const ObservationCandidate& chosen = c.chosen();
    require_free(chosen.candidate, "");
    const MrcalBoard board = mrcal_board(c.board);
    ObservationSet set = board_set(board);
    set.cameras.push_back({"0", chosen.camera});
    set.cameras.back().camera.pose = Pose{};
    for (std::size_t v = 0; v < c.views.size(); ++v) {
        add_view(set, c.views[v], 0, mrcal_pose(chosen.poses[v], board.origin), static_cast<int>(v), false);
    }
    return mrcal_optimization_inputs(set, c.noise_px);
}

std::string mrcal_solve_inputs(const PairCalibration& pair) {
    require_free(pair.first.chosen().candidate, "the left camera: ");
    require_free(pair.second.chosen().candidate, "the right camera: ");
    const MrcalBoard board = mrcal_board(pair.first.board);
    ObservationSet set = board_set(board);
    set.cameras.push_back({"0", pair.first_camera});
    set.cameras.push_back({"1", pair.second_camera});
    for (ObservedCamera& camera : set.cameras) camera.camera.pose = Pose{};
    for (std::size_t v = 0; v < pair.board_poses.size(); ++v) {
        const Pose frame = mrcal_pose(pair.board_poses[v], board.origin);
        set.frames.push_back(frame);
        const int f = static_cast<int>(v);
        add_view(set, pair.first.views[pair.first_view_of_pair[v]], 0, frame, f, false);
        add_view(set, pair.second.views[pair.second_view_of_pair[v]], 1, pair.second_camera.pose.after(frame), f, true);
    }
    const double noise = std::sqrt(0.5) * pair.rms_px;  // the RMS per coordinate
    return mrcal_optimization_inputs(set, noise);
}

}  // namespace libcam
