#include "calibrate_binding.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "camera_binding.hpp"
#include "libcam/calibrate/calibrate.hpp"
#include "libcam/calibrate/calibrate_pair.hpp"
#include "libcam/calibrate/calibration_json.hpp"
#include "libcam/calibrate/opencv_flags.hpp"
#include "libcam/calibrate/pair_output.hpp"
#include "libcam/error.hpp"

namespace py = pybind11;

namespace libcam::python {

namespace {

// One view's corners given as arrays: (N, 2) pixels of every corner in the board's order,
// or (ids, pixels) for the corners seen.
BoardDetection detection_of(const py::handle& view, const std::string& name, const ImageSize& size) {
    BoardDetection out;
    out.image = name;
    out.size = size;
    py::object pixels_object = py::reinterpret_borrow<py::object>(view);
    std::optional<std::vector<int>> ids;
    if (py::isinstance<py::tuple>(view) && py::len(view) == 2) {
        const py::tuple pair = py::reinterpret_borrow<py::tuple>(view);
        ids = py::cast<std::vector<int>>(pair[0]);
        pixels_object = pair[1];
    }
    const auto pixels = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(pixels_object);
    if (!pixels || pixels.ndim() != 2 || pixels.shape(1) != 2) {
        throw InvalidArgument("calibrate: " + name + ": corners must be an (N, 2) array of pixels");
    }
    const auto count = static_cast<std::size_t>(pixels.shape(0));
    if (ids && ids->size() != count) {
        throw InvalidArgument("calibrate: " + name + ": " + std::to_string(ids->size()) +
                              " ids for " + std::to_string(count) + " pixels");
    }
    for (std::size_t k = 0; k < count; ++k) {
        out.ids.push_back(ids ? (*ids)[k] : static_cast<int>(k));
        out.pixels.emplace_back(pixels.at(static_cast<py::ssize_t>(k), 0), pixels.at(static_cast<py::ssize_t>(k), 1));
    }
    return out;
}

// Corner ids must name the board's corners: the fit looks them up.
void check_ids(const BoardDetection& view, const BoardSpec& board) {
    for (const int id : view.ids) {
        if (id < 0 || static_cast<std::size_t>(id) >= board.corner_count()) {
            throw InvalidArgument("calibrate: " + view.image + ": corner id " + std::to_string(id) + " is not one of the " +
                                  std::to_string(board.corner_count()) + " corners of " + board.text());
        }
    }
    if (view.ids.size() < kMinCornersPerView) {
        throw InvalidArgument("calibrate: " + view.image + ": " + std::to_string(view.ids.size()) +
                              " corners, fewer than " + std::to_string(kMinCornersPerView));
    }
}

// `side` names a pair's camera in the views' names ("left view 3"), empty for one camera.
std::vector<BoardDetection> detections_of(const py::sequence& views, const BoardSpec& board,
                                          const std::optional<std::array<int, 2>>& image_size, CornerMethod method,
                                          int threads, const std::string& side = "") {
    std::vector<std::filesystem::path> images;
    std::vector<BoardDetection> given;
    for (std::size_t i = 0; i < py::len(views); ++i) {
        const py::handle view = views[i];
        if (py::isinstance<py::str>(view) || py::hasattr(view, "__fspath__")) {
            images.emplace_back(py::str(py::module_::import("os").attr("fspath")(view)).cast<std::string>());
            continue;
        }
        if (!image_size) throw InvalidArgument("calibrate: corners given as arrays need image_size=(width, height)");
        const std::string name = (side.empty() ? "" : side + " ") + "view " + std::to_string(i);
        given.push_back(detection_of(view, name, ImageSize{(*image_size)[0], (*image_size)[1]}));
        check_ids(given.back(), board);
    }
    if (!images.empty() && !given.empty()) {
        throw InvalidArgument("calibrate: views are either image files or corner arrays, not both");
    }
    if (given.empty()) {
        const py::gil_scoped_release release;
        return detect_boards(images, board, threads, {}, method);
    }
    return given;
}

py::object as_array(const py::handle& value) {
    return py::module_::import("numpy").attr("asarray")(value, "float64");
}

// calibrate's JSON, parsed, with numpy arrays for K, dist and each view's rvec and tvec,
// and every view's rvec and tvec stacked (rvecs, tvecs: (n, 3)).
py::dict with_arrays(py::dict out) {
    py::dict chosen = out["chosen"].cast<py::dict>();
    chosen["K"] = as_array(chosen["K"]);
    chosen["dist"] = as_array(chosen["dist"]);
    py::list rvecs, tvecs;
    for (const py::handle view : out["views"].cast<py::list>()) {
        py::dict entry = py::reinterpret_borrow<py::dict>(view);
        entry["rvec"] = as_array(entry["rvec"]);
        entry["tvec"] = as_array(entry["tvec"]);
        rvecs.append(entry["rvec"]);
        tvecs.append(entry["tvec"]);
    }
    out["rvecs"] = as_array(rvecs).attr("reshape")(-1, 3);
    out["tvecs"] = as_array(tvecs).attr("reshape")(-1, 3);
    return out;
}

py::dict parsed(const std::string& json) {
    return py::module_::import("json").attr("loads")(json).cast<py::dict>();
}

CornerMethod corner_method(const std::string& corners) {
    if (corners == "libcam") return CornerMethod::Libcam;
    if (corners == "opencv-sample") return CornerMethod::OpenCvSample;
    throw InvalidArgument("calibrate: corners '" + corners + "': libcam or opencv-sample");
}

CalibrationOptions options_of(const std::string& model, int folds, double margin,
                              const std::optional<std::string>& opencv_flags, bool keep_outliers) {
    CalibrationOptions options;
    if (model != "auto") {
        for (std::size_t begin = 0; begin <= model.size();) {
            const std::size_t end = std::min(model.find(',', begin), model.size());
            options.candidates.push_back(candidate_named(model.substr(begin, end - begin)));
            begin = end + 1;
        }
    }
    options.folds = folds;
    options.margin = margin;
    if (opencv_flags) options.held = held_by_opencv_flags(*opencv_flags);
    if (keep_outliers) options.outlier_sigmas = std::numeric_limits<double>::infinity();
    return options;
}

py::dict calibrate_views(const py::sequence& views, const std::string& board_text,
                         const std::optional<std::array<int, 2>>& image_size, const std::string& model, int folds,
                         double margin, const std::optional<std::string>& opencv_flags, const std::string& corners,
                         bool keep_outliers, const std::vector<std::array<double, 2>>& at, int threads) {
    const BoardSpec board = parse_board_spec(board_text);
    const CornerMethod method = corner_method(corners);
    const CalibrationOptions options = options_of(model, folds, margin, opencv_flags, keep_outliers);
    const std::vector<BoardDetection> detections = detections_of(views, board, image_size, method, threads);
    std::string json;
    {
        const py::gil_scoped_release release;
        const Calibration c = calibrate(detections, board, options);
        std::vector<Vec2> pixels;
        for (const auto& p : at) pixels.emplace_back(p[0], p[1]);
        if (pixels.empty()) pixels.emplace_back(c.size.centre_x(), c.size.centre_y());
        json = calibration_json(c, pixels, chosen_sigma_px(c, pixels));
    }
    return with_arrays(parsed(json));
}

// The pair as `libcam calibrate --left --right --json` reports it, with numpy arrays, and
// the two jointly refined cameras as libcam.Camera (posed: the left at the origin, the
// right at X_right = R X_left + T), ready for libcam.rectify.
py::dict calibrate_two(const py::sequence& left, const py::sequence& right, const std::string& board_text,
                       const std::optional<std::array<int, 2>>& image_size, const std::string& model, int folds,
                       double margin, const std::optional<std::string>& opencv_flags, const std::string& corners,
                       bool keep_outliers, const std::vector<std::array<double, 2>>& at, int threads) {
    const BoardSpec board = parse_board_spec(board_text);
    const CornerMethod method = corner_method(corners);
    const CalibrationOptions options = options_of(model, folds, margin, opencv_flags, keep_outliers);
    std::vector<Vec2> pixels;
    for (const auto& p : at) pixels.emplace_back(p[0], p[1]);
    const std::vector<BoardDetection> first = detections_of(left, board, image_size, method, threads, "left");
    const std::vector<BoardDetection> second = detections_of(right, board, image_size, method, threads, "right");
    std::optional<PairCalibration> pair;
    std::string json;
    {
        const py::gil_scoped_release release;
        pair = calibrate_pair(first, second, board, options);
        json = pair_calibration_json(*pair, pixels);
    }
    py::dict out = parsed(json);
    out["R"] = as_array(out["R"]);
    out["T"] = as_array(out["T"]);
    for (const py::handle camera : out["cameras"].cast<py::list>()) {
        py::dict entry = py::reinterpret_borrow<py::dict>(camera);
        entry["K"] = as_array(entry["K"]);
        entry["dist"] = as_array(entry["dist"]);
    }
    for (const py::handle view : out["views"].cast<py::list>()) {
        py::dict entry = py::reinterpret_borrow<py::dict>(view);
        entry["rvec"] = as_array(entry["rvec"]);
        entry["tvec"] = as_array(entry["tvec"]);
    }
    out["left"] = with_arrays(out["left"].cast<py::dict>());
    out["right"] = with_arrays(out["right"].cast<py::dict>());
    out["left_camera"] = py::cast(PythonCamera(pair->first_camera));
    out["right_camera"] = py::cast(PythonCamera(pair->second_camera));
    return out;
}

}  // namespace

void bind_calibrate(py::module_& m) {
    m.def("calibrate", &calibrate_views, py::arg("views"), py::arg("board"), py::arg("image_size") = py::none(),
          py::arg("model") = "auto", py::arg("folds") = 5, py::arg("margin") = 0.05, py::arg("opencv_flags") = py::none(),
          py::arg("corners") = "libcam", py::arg("keep_outliers") = false,
          py::arg("at") = std::vector<std::array<double, 2>>{}, py::arg("threads") = 0, R"doc(
A calibration from board views, as the libcam program's calibrate command makes it: views
are image files (their board found as `corners` says: 'libcam' or 'opencv-sample'), or the
corners found in them, each an (N, 2) array of every corner's pixel in the board's order
(OpenCV's findChessboardCorners order) or an (ids, pixels) pair, with image_size=(w, h).
board: 'chessboard:CxR:SQUARE' or 'charuco:CxR:SQUARE:MARKER:DICT'; model: 'auto' or
models, comma-separated; opencv_flags: OpenCV's calibrateCamera flags to hold ('2',
'FIX_ASPECT_RATIO,ZERO_TANGENT_DIST', ...); at: pixels for the chosen model's projection
uncertainty (default: the image centre). Returns calibrate --json's dict, with numpy
arrays for chosen['K'] (3, 3), chosen['dist'] and each view's 'rvec' and 'tvec', and
'rvecs', 'tvecs' (n, 3) stacked: X_cam = R(rvec) X_board + tvec, in the board's unit.)doc");
    m.def("calibrate_pair", &calibrate_two, py::arg("left"), py::arg("right"), py::arg("board"),
          py::arg("image_size") = py::none(), py::arg("model") = "auto", py::arg("folds") = 5, py::arg("margin") = 0.05,
          py::arg("opencv_flags") = py::none(), py::arg("corners") = "libcam", py::arg("keep_outliers") = false,
          py::arg("at") = std::vector<std::array<double, 2>>{}, py::arg("threads") = 0, R"doc(
A stereo pair calibrated from the two cameras' views of the same boards, as the libcam
program's calibrate --left --right makes it: left[i] and right[i] are one board pose seen by
each camera, given as calibrate() takes views (image files, or corner arrays with
image_size). Each camera is calibrated alone (its model chosen), then both are refined with
the pair's pose on the views both used. at: pixels for each camera's projection
uncertainty in the pair's solve (default: each image's centre). Returns calibrate --left
--right --json's dict: 'pairs' (the views both used), 'rms_px', 'noise_px', 'R' (3, 3) and
'T' (3,) (X_right = R X_left + T, cv2.stereoCalibrate's convention, in the board's unit),
'cameras' (each refined camera's 'K' and 'dist' as numpy arrays, and its 'uncertainty':
[{'pixel', 'sigma_px'}]), 'views' (each pair's images and its board pose in the left
camera, 'rvec' and 'tvec' as numpy arrays), 'left' and 'right' (each camera alone, as
calibrate() returns it), and 'left_camera', 'right_camera': the refined cameras as
libcam.Camera, posed, for libcam.rectify.)doc");
}

}  // namespace libcam::python
