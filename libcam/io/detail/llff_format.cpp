#include "libcam/io/detail/llff_format.hpp"

#include <cmath>
#include <span>
#include <string>

#include "libcam/error.hpp"
#include "libcam/geometry/pose.hpp"
#include "libcam/io/detail/npz_archive.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

constexpr std::size_t kColumns = 17;  // 3x5 matrix, near, far
constexpr const char* kHwfNames[] = {"H", "W", "focal"};

// A row's numbers, with messages naming the row and the column.
struct Row {
    std::span<const double> numbers;
    std::string where;  // "<file>: row 3"

    double matrix(std::size_t r, std::size_t c) const { return numbers[r * 5 + c]; }
    [[noreturn]] void fail(std::size_t r, std::size_t c, const std::string& what) const {
        throw FileError(where + ": column " + std::to_string(r * 5 + c) + ": " + what);
    }
};

long side(const Row& row, std::size_t r) {
    const double value = row.matrix(r, 4);
    if (!(value >= 1.0 && value <= static_cast<double>(kMaxImageSide)) || value != std::floor(value)) {
        row.fail(r, 4, std::string(kHwfNames[r]) + " must be a whole number of pixels in [1, " +
                           std::to_string(kMaxImageSide) + "], got " + std::to_string(value));
    }
    return static_cast<long>(value);
}

Pose read_pose(const Row& row) {
    // LLFF's columns are the camera's down, right and backwards axes; OpenCV's are right,
    // down and forwards.
    Mat3 llff;
    Vec3 centre;
    for (long r = 0; r < 3; ++r) {
        for (long c = 0; c < 3; ++c) llff(r, c) = row.matrix(static_cast<std::size_t>(r), static_cast<std::size_t>(c));
        centre(r) = row.matrix(static_cast<std::size_t>(r), 3);
    }
    Mat3 camera_to_world;
    camera_to_world << llff.col(1), llff.col(0), -llff.col(2);
    const Pose pose = Pose::from_centre(nearest_rotation_if_rounded(camera_to_world).transpose(), centre);
    try {
        pose.validate("rotation");
    } catch (const InvalidArgument& error) {
        throw FileError(row.where + ": columns 0-2, 5-7, 10-12 (the camera-to-world rotation): " + error.what() +
                        " (a scaled or sheared matrix is not a camera's rotation)");
    }
    return pose;
}

Camera read_camera(const Row& row, NerfPrincipalPoint principal_point) {
    for (std::size_t r = 0; r < 3; ++r) {
        for (std::size_t c = 0; c < 5; ++c) {
            const double value = row.matrix(r, c);
            if (!std::isfinite(value)) row.fail(r, c, "must be finite, got " + std::to_string(value));
        }
    }
    Camera camera;
    camera.size = {side(row, 1), side(row, 0)};
    const double focal = row.matrix(2, 4);
    // COLMAP's image centre, or NeRF's W / 2 on request (llff_format.hpp).
    const double shift = principal_point == NerfPrincipalPoint::HalfSize ? 0.0 : 0.5;
    camera.intrinsics = {focal, focal, static_cast<double>(camera.size.width) / 2.0 - shift,
                         static_cast<double>(camera.size.height) / 2.0 - shift, 0.0};
    camera.lens = {LensType::Pinhole, {}};
    camera.pose = read_pose(row);
    return validated_camera(camera, row.where + ": column 14 (focal)");
}

}  // namespace

std::vector<NamedCamera> read_llff_poses(std::string_view bytes, const ReadContext& context) {
    const detail::NpyArray array = detail::parse_npy(bytes, context.source);
    if (array.is_text() || array.descr == "|b1") {
        throw FileError(context.source + ": dtype " + shown_value(array.descr) +
                        ": expected numbers (LLFF writes <f8)");
    }
    if (array.shape.size() != 2 || array.shape[1] != kColumns || array.shape[0] == 0) {
        std::string shape;
        for (const std::size_t n : array.shape) shape += (shape.empty() ? "" : ", ") + std::to_string(n);
        throw FileError(context.source + ": shape (" + shape + "): expected (N, 17) with N >= 1: per image a 3x5 "
                                         "[R | centre | H W focal] and near, far");
    }
    std::vector<NamedCamera> cameras;
    for (std::size_t i = 0; i < array.shape[0]; ++i) {
        const Row row{std::span<const double>(array.numbers).subspan(i * kColumns, kColumns),
                      context.source + ": row " + std::to_string(i)};
        cameras.push_back({std::to_string(i), {read_camera(row, context.options.nerf_principal_point), std::nullopt}});
    }
    return cameras;
}

}  // namespace libcam
