#include "libcam/interop/opencv.hpp"

#include <algorithm>
#include <optional>

#include "libcam/error.hpp"

namespace libcam {

cv::Mat opencv_camera_matrix(const Intrinsics& k) {
    return (cv::Mat_<double>(3, 3) << k.fx, k.skew, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0);
}

namespace {

// OpenCV's radial-tangential models, told apart by their number of coefficients.
bool is_opencv_model(LensType type) { return lens_info(type).name.starts_with("OPENCV"); }

std::optional<LensType> opencv_model_with(std::size_t count) {
    for (const LensInfo& info : lens_models()) {
        if (is_opencv_model(info.type) && static_cast<std::size_t>(info.num_coefficients) == count) return info.type;
    }
    return std::nullopt;
}

}  // namespace

cv::Mat opencv_distortion(const Lens& lens) {
    if (lens.type != LensType::Pinhole && lens.type != LensType::Fisheye && !is_opencv_model(lens.type)) {
        throw NotRepresentable("lens: OpenCV has no model " + std::string(lens_info(lens.type).name));
    }
    cv::Mat dist(1, static_cast<int>(lens.coefficients.size()), CV_64F);
    std::copy(lens.coefficients.begin(), lens.coefficients.end(), dist.ptr<double>());
    return dist;
}

cv::Mat opencv_vector(const Vec3& v) { return (cv::Mat_<double>(3, 1) << v.x(), v.y(), v.z()); }

std::string format_opencv_storage(const Camera& camera, OpenCvStorage storage) {
    camera.validate();
    const int mode = cv::FileStorage::WRITE | cv::FileStorage::MEMORY |
                     (storage == OpenCvStorage::Yaml ? cv::FileStorage::FORMAT_YAML : cv::FileStorage::FORMAT_XML);
    cv::FileStorage fs(storage == OpenCvStorage::Yaml ? ".yaml" : ".xml", mode);
    fs << "image_width" << static_cast<int>(camera.size.width);
    fs << "image_height" << static_cast<int>(camera.size.height);
    fs << "camera_matrix" << opencv_camera_matrix(camera.intrinsics);
    if (camera.lens.type != LensType::Pinhole && !is_opencv_model(camera.lens.type)) {
        // FISHEYE's four coefficients would read back as OPENCV4: refuse, never convert silently.
        throw NotRepresentable("lens: OpenCV's camera file holds only OpenCV's radial-tangential models, not " +
                               std::string(lens_info(camera.lens.type).name));
    }
    const cv::Mat dist = camera.lens.type == LensType::Pinhole ? cv::Mat::zeros(5, 1, CV_64F)
                                                               : opencv_distortion(camera.lens).t();
    fs << "distortion_coefficients" << dist;
    fs << "rvec" << opencv_vector(camera.pose.rvec());
    fs << "tvec" << opencv_vector(camera.pose.t);
    return fs.releaseAndGetString();
}

namespace {

// A node as a CV_64F matrix; FileError naming the key unless it is a matrix of `count`
// finite numbers (count < 0: any count).
cv::Mat read_matrix(const cv::FileNode& node, const char* key, const std::string& source, int rows, int cols) {
    if (node.empty() || node.isNone()) throw FileError(source + ": \"" + key + "\": missing");
    cv::Mat m;
    try {
        node >> m;
    } catch (const cv::Exception& error) {
        throw FileError(source + ": \"" + key + "\": not a matrix: " + error.msg);
    }
    if (m.empty() && !(rows < 0 && cols < 0)) throw FileError(source + ": \"" + key + "\": not a matrix or empty");
    if (!m.empty()) m.convertTo(m, CV_64F);
    if ((rows >= 0 && m.rows != rows) || (cols >= 0 && m.cols != cols)) {
        throw FileError(source + ": \"" + key + "\": expected a " + std::to_string(rows) + "x" + std::to_string(cols) +
                        " matrix, got " + std::to_string(m.rows) + "x" + std::to_string(m.cols));
    }
    for (int i = 0; i < static_cast<int>(m.total()); ++i) {
        const double value = m.ptr<double>()[i];
        if (!std::isfinite(value)) {
            throw FileError(source + ": \"" + key + "\"[" + std::to_string(i) + "]: must be finite, got " +
                            format_number(value));
        }
    }
    return m;
}

long read_side(const cv::FileNode& node, const char* key, const std::string& source) {
    if (node.empty() || node.isNone()) throw FileError(source + ": \"" + key + "\": missing");
    if (!node.isInt()) throw FileError(source + ": \"" + key + "\": expected an integer");
    const long value = static_cast<int>(node);
    if (value < 1 || value > kMaxImageSide) {
        throw FileError(source + ": \"" + key + "\": must be in [1, " + std::to_string(kMaxImageSide) + "], got " +
                        std::to_string(value));
    }
    return value;
}

Vec3 read_vector3(const cv::FileNode& node, const char* key, const std::string& source) {
    cv::Mat m = read_matrix(node, key, source, -1, -1).reshape(1, 1);
    if (m.total() != 3) {
        throw FileError(source + ": \"" + key + "\": expected 3 numbers, got " + std::to_string(m.total()));
    }
    return {m.at<double>(0), m.at<double>(1), m.at<double>(2)};
}

}  // namespace

Camera parse_opencv_storage(std::string_view text, const std::string& source) {
    cv::FileStorage fs;
    try {
        if (!fs.open(std::string(text), cv::FileStorage::READ | cv::FileStorage::MEMORY)) {
            throw FileError(source + ": not an OpenCV YAML/XML file");
        }
    } catch (const cv::Exception& error) {
        throw FileError(source + ": not a valid OpenCV YAML/XML file: " + error.err);
    }
    try {
        Camera camera;
        camera.size = {read_side(fs["image_width"], "image_width", source),
                       read_side(fs["image_height"], "image_height", source)};
        const cv::Mat K = read_matrix(fs["camera_matrix"], "camera_matrix", source, 3, 3);
        Mat3 k;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) k(r, c) = K.at<double>(r, c);
        try {
            camera.intrinsics = Intrinsics::from_K(k, "camera_matrix");
        } catch (const InvalidArgument& error) {
            throw FileError(source + ": " + error.what());
        }

        const cv::FileNode dist_node = fs["distortion_coefficients"];
        if (!dist_node.empty() && !dist_node.isNone()) {
            const cv::Mat dist = read_matrix(dist_node, "distortion_coefficients", source, -1, -1);
            const bool all_zero = dist.empty() || cv::countNonZero(dist) == 0;
            if (!all_zero) {
                if (dist.rows != 1 && dist.cols != 1) {
                    throw FileError(source + ": \"distortion_coefficients\": expected a vector, got a " +
                                    std::to_string(dist.rows) + "x" + std::to_string(dist.cols) + " matrix");
                }
                const std::optional<LensType> type = opencv_model_with(dist.total());
                if (!type) {
                    throw FileError(source + ": \"distortion_coefficients\": expected 4, 5, 8, 12 or 14 coefficients, got " +
                                    std::to_string(dist.total()));
                }
                camera.lens.type = *type;
                const cv::Mat values = dist.reshape(1, 1);
                camera.lens.coefficients.assign(values.ptr<double>(), values.ptr<double>() + values.total());
            }
        }
        const cv::FileNode rvec = fs["rvec"];
        const cv::FileNode tvec = fs["tvec"];
        if (!rvec.empty() && !rvec.isNone()) camera.pose.R = rotation_from_rvec(read_vector3(rvec, "rvec", source));
        if (!tvec.empty() && !tvec.isNone()) camera.pose.t = read_vector3(tvec, "tvec", source);
        camera.validate();
        return camera;
    } catch (const cv::Exception& error) {
        throw FileError(source + ": malformed OpenCV file: " + error.err);
    }
}

}  // namespace libcam
