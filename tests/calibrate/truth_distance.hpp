#pragma once
// How far a calibration of rendered board images is from the truth that rendered them,
// measured as mrcal measures a solve against a known camera: points fixed to each board,
// carried by the true board pose through the true camera and by the solved pose through
// the solved camera; the RMS of the two pixels' distance over a grid covering the
// corners each view used. The board poses take part because the data cannot tell a
// principal-point shift from a common turn of every board: the solved camera is right
// where it images the boards where the truth does.

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "libcam/calibrate/board.hpp"
#include "libcam/camera/camera.hpp"

namespace libcam::test {

// A view as a calibration solved it: the board corners it used, and the board's pose.
struct SolvedView {
    std::vector<int> ids;
    Pose pose;
};

// The solved camera: board points under a view's solved pose to pixels.
using SolvedProjection = std::function<std::vector<Vec2>(const Pose& pose, const std::vector<Vec3>& board_points)>;

// The true pose of the board as a detector numbered its corners: a chessboard found from
// its other end is the board turned half a turn about its middle (corner k is corner
// N-1-k), which is the same board to a calibration.
inline Pose true_pose_as_numbered(const Camera& truth, const Pose& pose, const BoardSpec& board, int first_id,
                                  const Vec2& first_pixel) {
    Camera camera = truth;
    camera.pose = pose;
    const PreparedCamera prepared(camera);
    const std::vector<Vec3> corners = board.corner_points();
    if ((prepared.project(corners[static_cast<std::size_t>(first_id)]).pixel - first_pixel).norm() < 2.0) return pose;
    // X -> (far corner) - X: the half turn about the board's normal that maps corner k to N-1-k.
    const Vec3 far = corners.front() + corners.back();
    Mat3 half_turn = Mat3::Identity();
    half_turn(0, 0) = half_turn(1, 1) = -1.0;
    return {pose.R * half_turn, pose.t + pose.R * far};
}

// Board points every quarter square over the box of the corners `ids` (the region the view observed).
inline std::vector<Vec3> observed_region(const BoardSpec& board, const std::vector<int>& ids) {
    const std::vector<Vec3> corners = board.corner_points();
    Vec2 low(1e9, 1e9), high(-1e9, -1e9);
    for (const int id : ids) {
        const Vec3& p = corners[static_cast<std::size_t>(id)];
        low = low.cwiseMin(p.head<2>());
        high = high.cwiseMax(p.head<2>());
    }
    const double step = board.square / 4.0;
    std::vector<Vec3> points;
    for (double y = low.y(); y <= high.y() + 1e-9; y += step) {
        for (double x = low.x(); x <= high.x() + 1e-9; x += step) points.emplace_back(x, y, 0.0);
    }
    return points;
}

// The RMS, in pixels, over every view's observed region; true_poses[v] pairs with solved[v].
inline double rms_from_truth(const Camera& truth, const std::vector<Pose>& true_poses,
                             const std::vector<SolvedView>& solved, const BoardSpec& board,
                             const SolvedProjection& project) {
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t v = 0; v < solved.size(); ++v) {
        const std::vector<Vec3> points = observed_region(board, solved[v].ids);
        Camera camera = truth;
        camera.pose = true_poses[v];
        const PreparedCamera prepared(camera);
        const std::vector<Vec2> pixels = project(solved[v].pose, points);
        for (std::size_t k = 0; k < points.size(); ++k) {
            sum += (prepared.project(points[k]).pixel - pixels[k]).squaredNorm();
            ++count;
        }
    }
    return std::sqrt(sum / static_cast<double>(count));
}

// A libcam camera as a SolvedProjection.
inline SolvedProjection projection_of(const Camera& solved) {
    return [solved](const Pose& pose, const std::vector<Vec3>& points) {
        Camera camera = solved;
        camera.pose = pose;
        const PreparedCamera prepared(camera);
        std::vector<Vec2> pixels;
        for (const Vec3& p : points) pixels.push_back(prepared.project(p).pixel);
        return pixels;
    };
}

}  // namespace libcam::test
