#include "libcam/convert/look_at_convert.hpp"

#include <algorithm>
#include <cmath>

#include "libcam/error.hpp"

namespace libcam {

Camera to_camera(const LookAtCamera& look_at_camera) {
    look_at_camera.validate();
    const FovPinholeT<double> pinhole = pinhole_from_fov<double>(look_at_camera);
    Camera camera;
    camera.size = look_at_camera.size;
    camera.intrinsics = Intrinsics{pinhole.focal.x(), pinhole.focal.y(), pinhole.principal_point.x(),
                                   pinhole.principal_point.y(), 0.0};
    camera.pose = Pose{pinhole.R, pinhole.t};
    return camera;
}

double FovAngles::on_axis(FovAxis axis) const {
    switch (axis) {
        case FovAxis::Horizontal: return horizontal;
        case FovAxis::Vertical: return vertical;
        case FovAxis::Diagonal: return diagonal;
        case FovAxis::Both: return horizontal;
    }
    return horizontal;
}

bool FovDescription::fits_axis(FovAxis axis) const {
    return std::find(fov_axes.begin(), fov_axes.end(), axis) != fov_axes.end();
}

namespace {

Frustum frustum_of(const Camera& camera) {
    const Intrinsics& k = camera.intrinsics;
    const double width = static_cast<double>(camera.size.width);
    const double height = static_cast<double>(camera.size.height);
    // The image spans [-0.5, W - 0.5] x [-0.5, H - 0.5] in OpenCV pixels; y flips to up.
    return {(-0.5 - k.cx) / k.fx, (width - 0.5 - k.cx) / k.fx, -(height - 0.5 - k.cy) / k.fy,
            (k.cy + 0.5) / k.fy};
}

// The angle between the rays through two opposite image edges, at tangents low < high
// on the plane z = 1, with span = high - low given exactly (side / f). Centred: 2 atan of
// the half tangent. Off centre: atan2(span, 1 + low high), which is atan(high) - atan(low)
// without the cancellation of two nearly equal arctangents (a narrow field far off centre
// lost up to 13 digits that way), and lands in (0, pi) by itself.
double spanned_angle_deg(double low, double high, double span) {
    if (low == -high) return angle_deg_from_half_tangent(high);
    return degrees_from_radians(std::atan2(span, std::fma(low, high, 1.0)));
}

FovAngles angles_of(const Frustum& f, const Camera& camera) {
    const double width = static_cast<double>(camera.size.width);
    const double height = static_cast<double>(camera.size.height);
    FovAngles angles;
    angles.horizontal = spanned_angle_deg(f.left, f.right, width / camera.intrinsics.fx);
    angles.vertical = spanned_angle_deg(f.bottom, f.top, height / camera.intrinsics.fy);
    if (f.left == -f.right && f.bottom == -f.top) {
        angles.diagonal = angle_deg_from_half_tangent(std::hypot(f.right, f.top));
    } else {
        const double one = angle_between(Vec3(f.left, f.bottom, 1.0), Vec3(f.right, f.top, 1.0));
        const double other = angle_between(Vec3(f.left, f.top, 1.0), Vec3(f.right, f.bottom, 1.0));
        angles.diagonal = degrees_from_radians(std::max(one, other));
    }
    return angles;
}

bool nearly_equal(double a, double b, double scale) { return std::abs(a - b) <= kLookAtCameraTolerance * scale; }

}  // namespace

FovDescription describe_fov(const Camera& camera) {
    camera.validate();
    const Intrinsics& k = camera.intrinsics;
    const double width = static_cast<double>(camera.size.width);
    const double height = static_cast<double>(camera.size.height);

    FovDescription description;
    description.frustum = frustum_of(camera);
    description.fov_deg = angles_of(description.frustum, camera);
    description.eye = camera.pose.centre();
    description.gaze = camera.pose.R.row(2).transpose();
    description.up = -camera.pose.R.row(1).transpose();

    auto& why = description.deviations;
    bool shape_free = true;  // no defect that rules out every axis
    if (camera.lens.type != LensType::Pinhole) {
        why.push_back("lens model " + std::string(lens_info(camera.lens.type).name) + " is not PINHOLE");
        shape_free = false;
    }
    if (!nearly_equal(k.skew, 0.0, k.fx)) {
        why.push_back("skew " + format_number(k.skew) + " is not 0");
        shape_free = false;
    }
    if (!nearly_equal(k.cx, camera.size.centre_x(), width)) {
        why.push_back("principal point cx " + format_number(k.cx) + " is off the image centre " +
                      format_number(camera.size.centre_x()));
        shape_free = false;
    }
    if (!nearly_equal(k.cy, camera.size.centre_y(), height)) {
        why.push_back("principal point cy " + format_number(k.cy) + " is off the image centre " +
                      format_number(camera.size.centre_y()));
        shape_free = false;
    }
    const bool square_pixels = nearly_equal(k.fx, k.fy, k.fx);
    // tan_x = W / (2 fx) equals tan_y = H / (2 fy)  <=>  W fy = H fx.
    const bool equal_tangents = nearly_equal(width * k.fy, height * k.fx, width * k.fy);
    if (!square_pixels) {
        why.push_back("pixels are not square (fx " + format_number(k.fx) + ", fy " + format_number(k.fy) +
                      "): no single horizontal, vertical or diagonal fov");
    }
    if (!equal_tangents) {
        why.push_back("W/fx " + format_number(width / k.fx) + " differs from H/fy " + format_number(height / k.fy) +
                      ": not the same angle on both axes (fov axis 'both')");
    }
    if (shape_free) {
        if (square_pixels) description.fov_axes = {FovAxis::Horizontal, FovAxis::Vertical, FovAxis::Diagonal};
        if (equal_tangents) description.fov_axes.push_back(FovAxis::Both);
    }
    return description;
}

LookAtCamera to_look_at_camera(const Camera& camera, FovAxis axis) {
    const FovDescription description = describe_fov(camera);
    if (!description.fits_axis(axis)) {
        std::string reasons;
        for (const std::string& reason : description.deviations) reasons += (reasons.empty() ? "" : "; ") + reason;
        throw NotRepresentable("not a look-at camera on the " + std::string(to_string(axis)) + " axis: " + reasons);
    }
    return LookAtCamera{description.eye,
                     description.gaze,
                     description.up,
                     description.fov_deg.on_axis(axis),
                     axis,
                     camera.size};
}

}  // namespace libcam
