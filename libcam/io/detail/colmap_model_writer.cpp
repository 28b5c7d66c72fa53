// A whole COLMAP model written back (colmap_format.hpp's write_colmap_files): the layout
// of COLMAP's own writers (src/colmap/scene/reconstruction_io.cc), text and binary.

#include <Eigen/Geometry>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>

#include "libcam/convert/colmap_models.hpp"
#include "libcam/error.hpp"
#include "libcam/io/detail/colmap_format.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

static_assert(std::endian::native == std::endian::little, "COLMAP's .bin files are little-endian");

template <class T>
void put(std::string& out, T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out.append(bytes, sizeof(T));
}

std::string number(double value) { return format_number(value + 0.0); }

// The rotation as a unit quaternion, w first, with w >= 0 (q and -q are the same rotation).
Eigen::Quaterniond quaternion_of(const Pose& pose) {
    Eigen::Quaterniond q(pose.R);
    q.normalize();
    if (q.w() < 0) q.coeffs() *= -1.0;
    return q;
}

// The record's camera as COLMAP's model, with COLMAP's principal point (libcam's + 0.5).
ColmapCamera colmap_camera_of(const ColmapCameraRecord& record) {
    if (record.camera.intrinsics.skew != 0.0) {
        throw NotRepresentable("camera " + std::to_string(record.id) + ": COLMAP's models have no skew");
    }
    return colmap_from_camera(record.camera);
}

std::string cameras_text(const std::vector<ColmapCameraRecord>& cameras) {
    std::string out = "# Camera list with one line of data per camera:\n"
                      "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
                      "# Number of cameras: " + std::to_string(cameras.size()) + "\n";
    for (const ColmapCameraRecord& record : cameras) {
        const ColmapCamera colmap = colmap_camera_of(record);
        out += std::to_string(record.id) + " " + std::string(colmap.model) + " " + std::to_string(record.camera.size.width) +
               " " + std::to_string(record.camera.size.height);
        for (const double value : colmap.params) out += " " + number(value);
        out += "\n";
    }
    return out;
}

std::string cameras_binary(const std::vector<ColmapCameraRecord>& cameras) {
    std::string out;
    put<std::uint64_t>(out, cameras.size());
    for (const ColmapCameraRecord& record : cameras) {
        const ColmapCamera colmap = colmap_camera_of(record);
        put<std::uint32_t>(out, static_cast<std::uint32_t>(record.id));
        put<std::int32_t>(out, colmap_model(colmap.model)->id);
        put<std::uint64_t>(out, static_cast<std::uint64_t>(record.camera.size.width));
        put<std::uint64_t>(out, static_cast<std::uint64_t>(record.camera.size.height));
        for (const double value : colmap.params) put<double>(out, value);
    }
    return out;
}

std::string images_text(const std::vector<ColmapImage>& images) {
    std::size_t observations = 0;
    for (const ColmapImage& image : images) observations += image.points.size();
    std::string out = "# Image list with two lines of data per image:\n"
                      "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
                      "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
                      "# Number of images: " + std::to_string(images.size()) + ", mean observations per image: " +
                      format_short(images.empty() ? 0.0 : static_cast<double>(observations) / static_cast<double>(images.size()), 6) +
                      "\n";
    for (const ColmapImage& image : images) {
        const Eigen::Quaterniond q = quaternion_of(image.pose);
        out += std::to_string(image.id);
        for (const double value : {q.w(), q.x(), q.y(), q.z(), image.pose.t.x(), image.pose.t.y(), image.pose.t.z()}) {
            out += " " + number(value);
        }
        out += " " + std::to_string(image.camera_id) + " " + image.name + "\n";
        for (std::size_t k = 0; k < image.points.size(); ++k) {
            const ColmapPoint2D& point = image.points[k];
            if (k != 0) out += " ";
            out += number(point.x) + " " + number(point.y) + " " +
                   (point.point3d_id == kColmapNoPoint3D ? std::string("-1") : std::to_string(point.point3d_id));
        }
        out += "\n";
    }
    return out;
}

std::string images_binary(const std::vector<ColmapImage>& images) {
    std::string out;
    put<std::uint64_t>(out, images.size());
    for (const ColmapImage& image : images) {
        const Eigen::Quaterniond q = quaternion_of(image.pose);
        put<std::uint32_t>(out, static_cast<std::uint32_t>(image.id));
        for (const double value : {q.w(), q.x(), q.y(), q.z(), image.pose.t.x(), image.pose.t.y(), image.pose.t.z()}) {
            put<double>(out, value);
        }
        put<std::uint32_t>(out, static_cast<std::uint32_t>(image.camera_id));
        out += image.name;
        out += '\0';
        put<std::uint64_t>(out, image.points.size());
        for (const ColmapPoint2D& point : image.points) {
            put<double>(out, point.x);
            put<double>(out, point.y);
            put<std::uint64_t>(out, point.point3d_id);
        }
    }
    return out;
}

std::string points_text(const ColmapPoints3D& points) {
    const std::size_t n = points.ids.size();
    const double mean_track = n == 0 ? 0.0 : static_cast<double>(points.track.size()) / static_cast<double>(n);
    std::string out = "# 3D point list with one line of data per point:\n"
                      "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
                      "# Number of points: " + std::to_string(n) + ", mean track length: " + format_short(mean_track, 6) + "\n";
    for (std::size_t i = 0; i < n; ++i) {
        out += std::to_string(points.ids[i]);
        for (int k = 0; k < 3; ++k) out += " " + number(points.xyz[i][k]);
        for (const std::uint8_t channel : points.colours[i]) out += " " + std::to_string(channel);
        out += " " + number(points.errors[i]);
        for (std::size_t k = points.track_begin[i]; k < points.track_begin[i + 1]; ++k) {
            out += " " + std::to_string(points.track[k].image_id) + " " + std::to_string(points.track[k].point2d_index);
        }
        out += "\n";
    }
    return out;
}

std::string points_binary(const ColmapPoints3D& points) {
    std::string out;
    put<std::uint64_t>(out, points.ids.size());
    for (std::size_t i = 0; i < points.ids.size(); ++i) {
        put<std::uint64_t>(out, points.ids[i]);
        for (int k = 0; k < 3; ++k) put<double>(out, points.xyz[i][k]);
        for (const std::uint8_t channel : points.colours[i]) put<std::uint8_t>(out, channel);
        put<double>(out, points.errors[i]);
        put<std::uint64_t>(out, points.track_begin[i + 1] - points.track_begin[i]);
        for (std::size_t k = points.track_begin[i]; k < points.track_begin[i + 1]; ++k) {
            put<std::uint32_t>(out, points.track[k].image_id);
            put<std::uint32_t>(out, points.track[k].point2d_index);
        }
    }
    return out;
}

}  // namespace

ColmapModelBytes write_colmap_files(const std::vector<ColmapCameraRecord>& cameras, const std::vector<ColmapImage>& images,
                                    const ColmapPoints3D& points, bool binary) {
    if (binary) return {cameras_binary(cameras), images_binary(images), points_binary(points)};
    return {cameras_text(cameras), images_text(images), points_text(points)};
}

}  // namespace libcam
