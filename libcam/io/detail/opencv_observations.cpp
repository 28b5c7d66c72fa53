#include "libcam/io/detail/opencv_observations.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/io/detail/document.hpp"
#include "libcam/io/detail/opencv_storage.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

// The most numbers one matrix of the file may declare: far past any calibration
// (hundreds of views of a board of hundreds of corners), and small enough that
// rows x cols x channels cannot overflow.
constexpr long long kMaxNumbers = 100'000'000;
constexpr long long kMaxBoardSide = 100'000;

struct Board {
    ObservedBoard shape;
    std::vector<Vec3> corners;
};

// The sample keeps corners and image points as float (Point3f, Point2f): the value it
// held is the float nearest the digits it wrote.
double as_float(double value) { return static_cast<double>(static_cast<float>(value)); }

// calcBoardCornerPositions for a chessboard (and a symmetric circles grid): in float,
// as the sample computes them.
std::vector<Vec3> sample_corners(int width, int height, double square_size) {
    const float square = static_cast<float>(square_size);
    std::vector<Vec3> corners;
    corners.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (int i = 0; i < height; ++i)
        for (int j = 0; j < width; ++j)
            corners.emplace_back(static_cast<float>(j) * square, static_cast<float>(i) * square, 0.0);
    return corners;
}

std::vector<Vec3> grid_points(const Field& field, std::size_t count) {
    const OpenCvMatrix m = read_opencv_matrix(field, kMaxNumbers, 3);
    if (m.values.size() != 3 * count) {
        field.fail("holds " + std::to_string(m.values.size()) + " numbers, expected 3 for each of the board's " +
                   std::to_string(count) + " corners");
    }
    std::vector<Vec3> corners;
    corners.reserve(count);
    for (std::size_t k = 0; k < count; ++k)
        corners.emplace_back(as_float(m.values[3 * k]), as_float(m.values[3 * k + 1]), as_float(m.values[3 * k + 2]));
    return corners;
}

Board read_board(const Field& file) {
    Board board;
    board.shape.width = static_cast<int>(file.at({"board_width", "board_Width"}).integer(1, kMaxBoardSide));
    board.shape.height = static_cast<int>(file.at({"board_height", "board_Height"}).integer(1, kMaxBoardSide));
    const Field square = file.at({"square_size", "square_Size"});
    board.shape.spacing = square.number();
    if (!(board.shape.spacing > 0)) square.fail("must be > 0, got " + shown_value(square.text()));
    const std::size_t count = static_cast<std::size_t>(board.shape.width) * static_cast<std::size_t>(board.shape.height);
    if (const std::optional<Field> grid = file.find({"grid_points"})) {
        board.corners = grid_points(*grid, count);
    } else {
        board.corners = sample_corners(board.shape.width, board.shape.height, board.shape.spacing);
    }
    return board;
}

// image_points: one row per view, one 2-channel element per corner.
OpenCvMatrix read_image_points(const Field& field, std::size_t corners) {
    const OpenCvMatrix m = read_opencv_matrix(field, kMaxNumbers, 2);
    if (m.channels != 2) field.fail("expected 2-channel points (dt \"2f\"), got " + std::to_string(m.channels) + " channel");
    if (m.rows < 1) field.fail("holds no views");
    if (static_cast<std::size_t>(m.cols) != corners) {
        field.fail("has " + std::to_string(m.cols) + " points per view, but the board has " + std::to_string(corners) +
                   " corners (board_width x board_height)");
    }
    return m;
}

// One pose per view: rows of rvec | tvec, as the sample writes them, or the 3 x 4 [R | t]
// blocks some copies of it write.
std::vector<Pose> read_poses(const Field& field, std::size_t views) {
    const OpenCvMatrix m = read_opencv_matrix(field, kMaxNumbers, 1);
    const auto value = [&](std::size_t row, std::size_t col) { return m.values[row * static_cast<std::size_t>(m.cols) + col]; };
    std::vector<Pose> poses;
    if (m.cols == 6 && static_cast<std::size_t>(m.rows) == views) {
        for (std::size_t v = 0; v < views; ++v) {
            poses.push_back(Pose::from_rvec({value(v, 0), value(v, 1), value(v, 2)}, {value(v, 3), value(v, 4), value(v, 5)}));
        }
    } else if (m.cols == 4 && static_cast<std::size_t>(m.rows) == 3 * views) {
        for (std::size_t v = 0; v < views; ++v) {
            Pose pose;
            for (int r = 0; r < 3; ++r) {
                for (int c = 0; c < 3; ++c) pose.R(r, c) = value(3 * v + static_cast<std::size_t>(r), static_cast<std::size_t>(c));
                pose.t(r) = value(3 * v + static_cast<std::size_t>(r), 3);
            }
            pose.R = nearest_rotation_if_rounded(pose.R);
            poses.push_back(pose);
        }
    } else {
        field.fail("is " + std::to_string(m.rows) + "x" + std::to_string(m.cols) + ", expected " + std::to_string(views) +
                   "x6 (rvec and tvec of each of the " + std::to_string(views) + " views of image_points) or " +
                   std::to_string(3 * views) + "x4 ([R | t] of each)");
    }
    for (std::size_t v = 0; v < poses.size(); ++v) {
        try {
            poses[v].validate("R");
        } catch (const InvalidArgument& error) {
            field.fail("view " + std::to_string(v) + ": " + error.what());
        }
    }
    return poses;
}

std::vector<double> read_per_view_errors(const Field& field, std::size_t views) {
    const OpenCvMatrix m = read_opencv_matrix(field, kMaxNumbers, 1);
    if (m.values.size() != views) {
        field.fail("holds " + std::to_string(m.values.size()) + " numbers, expected one for each of the " +
                   std::to_string(views) + " views of image_points");
    }
    return m.values;
}

}  // namespace

ObservationSet read_opencv_observations(const std::filesystem::path& file, std::string_view text,
                                        const ObservationReadOptions&) {
    const std::string source = file.string();
    const DocumentNode tree = parse_opencv_storage_tree(text, source);
    const Field root(tree, "", source);
    const std::optional<Field> image_points = root.find({"image_points", "Image_points"});
    if (!image_points) {
        throw FileError(source + ": \"image_points\": missing: the file holds a camera but no observations (OpenCV's "
                                 "calibration sample writes them with Write_DetectedFeaturePoints)");
    }
    ObservationSet set;
    set.tool = ObservationTool::OpenCvCalibration;
    set.source = source;
    set.cameras.push_back({"camera", read_opencv_storage_camera(root, source)});

    const Board board = read_board(root);
    set.board = board.shape;
    set.points = board.corners;
    for (std::size_t k = 0; k < set.points.size(); ++k) set.point_ids.push_back(static_cast<std::int64_t>(k));

    const OpenCvMatrix pixels = read_image_points(*image_points, set.points.size());
    const auto views = static_cast<std::size_t>(pixels.rows);
    const std::vector<Pose> poses = read_poses(root.at({"extrinsic_parameters", "Extrinsic_Parameters"}), views);
    // The float the sample held is the float nearest the digits it wrote (dt "2f").
    std::vector<double> values = pixels.values;
    if (pixels.depth == 'f') {
        for (double& value : values) value = as_float(value);
    }
    for (std::size_t v = 0; v < views; ++v) {
        set.views.push_back({"view " + std::to_string(v), 0, poses[v]});
        for (std::size_t k = 0; k < set.points.size(); ++k) {
            const std::size_t at = 2 * (v * set.points.size() + k);
            set.observations.push_back({static_cast<int>(v), static_cast<int>(k), Vec2(values[at], values[at + 1])});
        }
    }

    if (const std::optional<Field> average = root.find({"avg_reprojection_error", "Avg_Reprojection_Error"})) {
        set.reported.push_back({average->name(), average->number(), ReportedMeasure::RmsOverObservations});
    }
    if (const std::optional<Field> per_view =
            root.find({"per_view_reprojection_errors", "Per_View_Reprojection_Errors"})) {
        set.reported_per_view = read_per_view_errors(*per_view, views);
    }
    return set;
}

}  // namespace libcam
