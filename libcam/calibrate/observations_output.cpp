#include "libcam/calibrate/observations_output.hpp"

#include <cmath>
#include <optional>

#include "libcam/error.hpp"
#include "libcam/fit/fit.hpp"
#include "libcam/io/detail/opencv_storage.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

// The view's corners in the board's order, its outliers back in their places; none when
// the view did not see the whole board.
std::optional<std::vector<Vec2>> whole_board(const CalibrationView& view, std::size_t corners) {
    if (view.ids.size() + view.outlier_ids.size() != corners) return std::nullopt;
    std::vector<Vec2> pixels(corners);
    for (std::size_t k = 0; k < view.ids.size(); ++k) pixels[static_cast<std::size_t>(view.ids[k])] = view.pixels[k];
    for (std::size_t k = 0; k < view.outlier_ids.size(); ++k) {
        pixels[static_cast<std::size_t>(view.outlier_ids[k])] = view.outlier_pixels[k];
    }
    return pixels;
}

}  // namespace

ObservationsText format_opencv_observations(const Calibration& calibration) {
    const ObservationCandidate& chosen = calibration.chosen();
    const OpenCvFunction function = lens_info(chosen.camera.lens.type).opencv;
    if (function != OpenCvFunction::ProjectPoints && function != OpenCvFunction::Fisheye) {
        throw NotRepresentable("OpenCV's calibration output holds OpenCV's radial-tangential models and cv::fisheye's, "
                               "not the chosen " + std::string(lens_info(chosen.camera.lens.type).name) +
                               " (choose among them with --model)");
    }
    const std::vector<Vec3> board_points = calibration.board.corner_points();
    OpenCvMatrix image_points{0, static_cast<long long>(board_points.size()), {}, 2, 'd'};
    OpenCvMatrix extrinsics{0, 6, {}, 1, 'd'};
    OpenCvMatrix per_view{0, 1, {}, 1, 'd'};
    double sum = 0.0;
    std::size_t count = 0;
    ObservationsText out;
    for (std::size_t v = 0; v < calibration.views.size(); ++v) {
        const std::optional<std::vector<Vec2>> pixels = whole_board(calibration.views[v], board_points.size());
        if (!pixels) {
            ++out.left_out;
            continue;
        }
        Camera camera = chosen.camera;
        camera.pose = chosen.poses[v];
        std::vector<FitSample> samples;
        for (std::size_t k = 0; k < board_points.size(); ++k) samples.push_back({board_points[k], (*pixels)[k]});
        double view_sum = 0.0;
        for (const double e : reprojection_errors(camera, samples)) view_sum += e * e;
        sum += view_sum;
        count += samples.size();
        per_view.values.push_back(std::sqrt(view_sum / static_cast<double>(samples.size())));
        for (const Vec2& p : *pixels) image_points.values.insert(image_points.values.end(), {p.x(), p.y()});
        const Vec3 rvec = camera.pose.rvec();
        extrinsics.values.insert(extrinsics.values.end(),
                                 {rvec.x(), rvec.y(), rvec.z(), camera.pose.t.x(), camera.pose.t.y(), camera.pose.t.z()});
        ++out.views;
    }
    if (out.views == 0) {
        throw NotRepresentable("OpenCV's calibration output holds views of the whole board, and no view saw all of its " +
                               std::to_string(board_points.size()) + " corners");
    }
    image_points.rows = extrinsics.rows = per_view.rows = static_cast<long long>(out.views);
    // The sample's board is width x height corners, corner i * width + j at (j, i, 0) *
    // square unless grid_points says where they are: a ChArUco board's inner corners start
    // one square in, and are written.
    const int inset = calibration.board.kind == BoardKind::Charuco ? 1 : 0;
    out.text = format_opencv_storage(chosen.camera, OpenCvStorage::Yaml);
    out.text += "board_width: " + std::to_string(calibration.board.columns - inset) + "\n";
    out.text += "board_height: " + std::to_string(calibration.board.rows - inset) + "\n";
    out.text += "square_size: " + format_number(calibration.board.square) + "\n";
    out.text += "avg_reprojection_error: " + format_number(std::sqrt(sum / static_cast<double>(count))) + "\n";
    out.text += yaml_matrix("per_view_reprojection_errors", per_view);
    out.text += yaml_matrix("extrinsic_parameters", extrinsics);
    out.text += yaml_matrix("image_points", image_points);
    if (inset != 0) {
        OpenCvMatrix grid{static_cast<long long>(board_points.size()), 1, {}, 3, 'd'};
        for (const Vec3& p : board_points) grid.values.insert(grid.values.end(), {p.x(), p.y(), p.z()});
        out.text += yaml_matrix("grid_points", grid);
    }
    return out;
}

}  // namespace libcam
