#pragma once
// OpenGL projection for a calibrated pinhole camera.
//
// OpenGL's camera looks along -z with y up: X_gl = diag(1, -1, -1) X_cv. Window
// coordinates put the origin at the bottom-left corner of the image with pixel centres
// at +0.5, so for viewport (0, 0, W, H):
//     x_win = x_cv + 0.5,    y_win = H - 0.5 - y_cv.
// With those, the projection matrix that reproduces K exactly is
//
//     [2fx/W  -2s/W   1 - (2cx+1)/W   0]
//     [  0    2fy/H   (2cy+1)/H - 1   0]
//     [  0      0          A          B]     A, B: the depth mapping (near, far)
//     [  0      0         -1          0]
//
// with A = -(f+n)/(f-n), B = -2fn/(f-n) for OpenGL's depth in [-1, 1], and
// A = -f/(f-n), B = -fn/(f-n) for Direct3D/Vulkan's [0, 1]. Matrices are given
// row-major here; pass the transpose (or GL_TRUE) to glUniformMatrix4fv.

#include <Eigen/Core>
#include <array>

#include "libcam/camera/camera.hpp"

namespace libcam {

using Mat4 = Eigen::Matrix4d;

enum class DepthRange { MinusOneToOne, ZeroToOne };

struct GlCamera {
    Mat4 projection = Mat4::Identity();
    Mat4 view = Mat4::Identity();  // world -> OpenGL camera frame
    std::array<long, 4> viewport{0, 0, 1, 1};
    double near = 0.1;
    double far = 1000.0;
    DepthRange depth_range = DepthRange::MinusOneToOne;
};

// Throws InvalidArgument unless the lens is PINHOLE and 0 < near < far (finite).
GlCamera to_opengl(const Camera& camera, double near, double far,
                   DepthRange depth_range = DepthRange::MinusOneToOne);

struct GlIntrinsics {
    Intrinsics intrinsics;
    double near = 0.0;
    double far = 0.0;
};

// K, near and far from a projection matrix of the form above for an image of `size`.
// Throws InvalidArgument naming the entry when the matrix is not of that form.
GlIntrinsics intrinsics_from_opengl(const Mat4& projection, const ImageSize& size,
                                    DepthRange depth_range = DepthRange::MinusOneToOne);

// The OpenGL pipeline: clip = projection * view * X, NDC = clip / w, then the viewport.
// Returns window coordinates (x, y) and depth in NDC; valid is false behind the camera.
struct GlWindowPoint {
    Vec2 window = Vec2::Zero();
    double ndc_depth = 0.0;
    bool valid = false;
};
GlWindowPoint gl_project(const GlCamera& gl, const Vec3& world_point);

// Pixel-centre and row-origin shift between OpenCV pixels and OpenGL window coordinates.
inline Vec2 gl_window_from_opencv(const Vec2& pixel, const ImageSize& size) {
    return {pixel.x() + 0.5, static_cast<double>(size.height) - 0.5 - pixel.y()};
}
inline Vec2 opencv_from_gl_window(const Vec2& window, const ImageSize& size) {
    return {window.x() - 0.5, static_cast<double>(size.height) - 0.5 - window.y()};
}

}  // namespace libcam
