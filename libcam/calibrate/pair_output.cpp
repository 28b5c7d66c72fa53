#include "libcam/calibrate/pair_output.hpp"

#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>
#include <opencv2/core/persistence.hpp>

#include "libcam/calibrate/calibration_json.hpp"
#include "libcam/error.hpp"
#include "libcam/lens/lens_model.hpp"

namespace libcam {

namespace {

using Json = nlohmann::ordered_json;

cv::Mat camera_matrix(const Camera& camera) {
    const Intrinsics& k = camera.intrinsics;
    return (cv::Mat_<double>(3, 3) << k.fx, k.skew, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0);
}

// OpenCV's distortion vector (k1 k2 p1 p2 [k3 [k4 k5 k6]]; none for PINHOLE: five zeros).
cv::Mat distortion(const Camera& camera, const char* name) {
    const LensType type = camera.lens.type;
    if (type != LensType::Pinhole && type != LensType::OpenCv4 && type != LensType::OpenCv5 && type != LensType::OpenCv8) {
        throw NotRepresentable(std::string("OpenCV's stereo files hold OpenCV's pinhole models; the ") + name +
                               " camera is " + std::string(lens_info(type).name));
    }
    std::vector<double> coefficients = camera.lens.coefficients;
    if (coefficients.empty()) coefficients.assign(5, 0.0);
    return cv::Mat(coefficients, true).reshape(1, 1);
}

// JSON has no infinity or NaN: a value without a finite number is null.
Json finite_or_null(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

Json camera_json(const char* name, const Camera& camera, const PairUncertainty& uncertainty) {
    const Intrinsics& k = camera.intrinsics;
    Json out = {{"name", name},
                {"model", std::string(lens_info(camera.lens.type).name)},
                {"image_size", {camera.size.width, camera.size.height}},
                {"K", {{k.fx, k.skew, k.cx}, {0.0, k.fy, k.cy}, {0.0, 0.0, 1.0}}},
                {"dist", camera.lens.coefficients},
                {"uncertainty", Json::array()}};
    for (std::size_t i = 0; i < uncertainty.pixels.size(); ++i) {
        const Vec2& pixel = uncertainty.pixels[i];
        out["uncertainty"].push_back({{"pixel", {pixel.x(), pixel.y()}}, {"sigma_px", finite_or_null(uncertainty.sigma_px[i])}});
    }
    if (!uncertainty.failure.empty()) out["uncertainty_failure"] = uncertainty.failure;
    return out;
}

Json vec_json(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

Json alone_json(const Calibration& c) {
    const std::vector<Vec2> centre = {Vec2(c.size.centre_x(), c.size.centre_y())};
    return Json::parse(calibration_json(c, centre, chosen_sigma_px(c, centre)));
}

}  // namespace

OpenCvStereoFiles format_opencv_stereo(const PairCalibration& pair) {
    const cv::Mat D1 = distortion(pair.first_camera, "left"), D2 = distortion(pair.second_camera, "right");
    OpenCvStereoFiles out;
    {
        cv::FileStorage file(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
        file << "image_width" << static_cast<int>(pair.first_camera.size.width) << "image_height"
             << static_cast<int>(pair.first_camera.size.height);
        file << "M1" << camera_matrix(pair.first_camera) << "D1" << D1;
        file << "M2" << camera_matrix(pair.second_camera) << "D2" << D2;
        out.intrinsics = file.releaseAndGetString();
    }
    {
        const Pose& pose = pair.second_camera.pose;
        cv::Mat R(3, 3, CV_64F), T(3, 1, CV_64F);
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) R.at<double>(r, c) = pose.R(r, c);
            T.at<double>(r) = pose.t[r];
        }
        cv::FileStorage file(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
        file << "R" << R << "T" << T;
        out.extrinsics = file.releaseAndGetString();
    }
    return out;
}

PairUncertainty pair_uncertainty(const PairCalibration& pair, int side, const std::vector<Vec2>& pixels) {
    const Camera& camera = side == 0 ? pair.first_camera : pair.second_camera;
    PairUncertainty out;
    out.pixels = pixels.empty() ? std::vector<Vec2>{Vec2(camera.size.centre_x(), camera.size.centre_y())} : pixels;
    try {
        const ProjectionUncertainty uncertainty(solved_pair(pair, side));
        out.sigma_px = uncertainty.sigma_px(out.pixels);
        out.noise_px = uncertainty.observed_pixel_uncertainty_px();
    } catch (const InvalidArgument& error) {
        out.failure = error.what();
        out.sigma_px.assign(out.pixels.size(), std::numeric_limits<double>::quiet_NaN());
        out.noise_px = std::numeric_limits<double>::quiet_NaN();
    }
    return out;
}

std::string pair_calibration_json(const PairCalibration& pair, const std::vector<Vec2>& at) {
    const PairUncertainty left = pair_uncertainty(pair, 0, at), right = pair_uncertainty(pair, 1, at);
    Json out;
    out["pairs"] = pair.pairs;  // the views both cameras used: their places in the image lists, from 0
    out["rms_px"] = pair.rms_px;
    out["noise_px"] = finite_or_null(std::isfinite(left.noise_px) ? left.noise_px : right.noise_px);
    const Pose& pose = pair.second_camera.pose;
    out["R"] = {{pose.R(0, 0), pose.R(0, 1), pose.R(0, 2)},
                {pose.R(1, 0), pose.R(1, 1), pose.R(1, 2)},
                {pose.R(2, 0), pose.R(2, 1), pose.R(2, 2)}};
    out["T"] = {pose.t.x(), pose.t.y(), pose.t.z()};
    out["cameras"] = {camera_json("left", pair.first_camera, left), camera_json("right", pair.second_camera, right)};
    out["views"] = Json::array();
    for (std::size_t v = 0; v < pair.board_poses.size(); ++v) {
        const Pose& board = pair.board_poses[v];
        out["views"].push_back({{"left", pair.first_views[v].name},
                                {"right", pair.second_views[v].name},
                                {"rvec", vec_json(board.rvec())},
                                {"tvec", vec_json(board.t)}});
    }
    out["left"] = alone_json(pair.first);
    out["right"] = alone_json(pair.second);
    return out.dump(2) + "\n";
}

}  // namespace libcam
