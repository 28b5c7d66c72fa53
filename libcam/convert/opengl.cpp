#include "libcam/convert/opengl.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "libcam/error.hpp"

namespace libcam {

namespace {

void validate_depth(double near, double far) {
    require_finite("near", near);
    require_finite("far", far);
    if (!(near > 0.0)) throw InvalidArgument("near: must be > 0, got " + format_number(near));
    if (!(far > near)) {
        throw InvalidArgument("far: must be > near (" + format_number(near) + "), got " + format_number(far));
    }
}

// (A, B) of the third row.
Vec2 depth_row(double near, double far, DepthRange depth_range) {
    const double range = far - near;
    if (depth_range == DepthRange::ZeroToOne) return {-far / range, -far * near / range};
    return {-(far + near) / range, -2.0 * far * near / range};
}

}  // namespace

GlCamera to_opengl(const Camera& camera, double near, double far, DepthRange depth_range) {
    camera.validate();
    if (camera.lens.type != LensType::Pinhole) {
        throw InvalidArgument("lens: an OpenGL projection matrix holds no distortion; model " +
                              std::string(lens_info(camera.lens.type).name) + " is not PINHOLE");
    }
    validate_depth(near, far);
    const Intrinsics& k = camera.intrinsics;
    const double width = static_cast<double>(camera.size.width);
    const double height = static_cast<double>(camera.size.height);
    const Vec2 depth = depth_row(near, far, depth_range);

    GlCamera gl;
    gl.projection << 2.0 * k.fx / width, -2.0 * k.skew / width, 1.0 - (2.0 * k.cx + 1.0) / width, 0.0,  //
        0.0, 2.0 * k.fy / height, (2.0 * k.cy + 1.0) / height - 1.0, 0.0,                               //
        0.0, 0.0, depth.x(), depth.y(),                                                                 //
        0.0, 0.0, -1.0, 0.0;
    const Eigen::Vector3d flip(1.0, -1.0, -1.0);
    gl.view.setIdentity();
    gl.view.topLeftCorner<3, 3>() = flip.asDiagonal() * camera.pose.R;
    gl.view.topRightCorner<3, 1>() = flip.asDiagonal() * camera.pose.t;
    gl.viewport = {0, 0, camera.size.width, camera.size.height};
    gl.near = near;
    gl.far = far;
    gl.depth_range = depth_range;
    return gl;
}

GlIntrinsics intrinsics_from_opengl(const Mat4& P, const ImageSize& size, DepthRange depth_range) {
    size.validate("viewport");
    require_finite_all("projection", P);
    auto expect = [&](int row, int col, double value) {
        if (P(row, col) != value) {
            throw InvalidArgument("projection[" + std::to_string(row) + "][" + std::to_string(col) + "]: must be " +
                                  format_number(value) + " in a perspective projection, got " +
                                  format_number(P(row, col)));
        }
    };
    for (auto [row, col] : {std::pair{0, 3}, {1, 0}, {1, 3}, {2, 0}, {2, 1}, {3, 0}, {3, 1}, {3, 3}}) {
        expect(row, col, 0.0);
    }
    expect(3, 2, -1.0);

    const double width = static_cast<double>(size.width);
    const double height = static_cast<double>(size.height);
    GlIntrinsics result;
    Intrinsics& k = result.intrinsics;
    k.fx = 0.5 * P(0, 0) * width;
    k.fy = 0.5 * P(1, 1) * height;
    k.skew = -0.5 * P(0, 1) * width;
    k.cx = 0.5 * ((1.0 - P(0, 2)) * width - 1.0);
    k.cy = 0.5 * ((P(1, 2) + 1.0) * height - 1.0);
    k.validate("projection");

    const double a = P(2, 2);
    const double b = P(2, 3);
    if (depth_range == DepthRange::ZeroToOne) {
        result.near = b / a;
        result.far = b / (a + 1.0);
    } else {
        result.near = b / (a - 1.0);
        result.far = b / (a + 1.0);
    }
    validate_depth(result.near, result.far);
    return result;
}

GlWindowPoint gl_project(const GlCamera& gl, const Vec3& world_point) {
    const Eigen::Vector4d clip = gl.projection * gl.view * world_point.homogeneous();
    GlWindowPoint result;
    if (!(clip.w() > 0.0) || !clip.allFinite()) return result;  // behind the eye, or not a number: invalid
    const Eigen::Vector3d ndc = clip.head<3>() / clip.w();
    result.window = {static_cast<double>(gl.viewport[0]) + 0.5 * (ndc.x() + 1.0) * static_cast<double>(gl.viewport[2]),
                     static_cast<double>(gl.viewport[1]) + 0.5 * (ndc.y() + 1.0) * static_cast<double>(gl.viewport[3])};
    result.ndc_depth = ndc.z();
    result.valid = result.window.allFinite() && std::isfinite(result.ndc_depth);
    return result;
}

}  // namespace libcam
