#include "libcam/remap/derived_camera.hpp"

#include <cmath>
#include <string>

#include "libcam/error.hpp"
#include "libcam/text/number_format.hpp"

// Every switch over LensType here names every model, with no default: a new model stops
// the build until someone decides what this file does with it.
#pragma GCC diagnostic error "-Wswitch"

namespace libcam {

namespace {

// Each axis scaled by its own factor, with the half-pixel rule (derived_camera.hpp).
Camera scaled_axes(const Camera& camera, double sx, double sy, const ImageSize& size) {
    Camera out = camera;
    out.size = size;
    Intrinsics& k = out.intrinsics;
    k.fx *= sx;
    k.skew *= sx;
    k.fy *= sy;
    k.cx = sx * (camera.intrinsics.cx + 0.5) - 0.5;
    k.cy = sy * (camera.intrinsics.cy + 0.5) - 0.5;
    out.validate();
    return out;
}

ImageSize checked_size(long width, long height, const std::string& what) {
    const ImageSize size{width, height};
    try {
        size.validate(what.c_str());
    } catch (const InvalidArgument&) {
        throw InvalidArgument(what + ": the image would be " + std::to_string(width) + "x" + std::to_string(height) +
                              " pixels");
    }
    return size;
}

// The lens's coefficients for the image turned clockwise by a quarter: normalised points
// m' = Q m with Q = [0 -1; 1 0], so the lens becomes Q D(Q^T m'). Radial terms stay;
// tangential terms (p1, p2) become (p2, -p1); thin prism terms (x: s1 r^2 + s2 r^4,
// y: s3 r^2 + s4 r^4) become (-s3, -s4, s1, s2).
Lens lens_turned(const Lens& lens) {
    Lens out = lens;
    std::vector<double>& c = out.coefficients;
    // OpenCV's p1 at index p1 and its p2 at p2.
    const auto tangential = [&](std::size_t p1, std::size_t p2) {
        const double old_p1 = c[p1];
        c[p1] = c[p2];
        c[p2] = -old_p1;
    };
    const auto prism = [&](std::size_t s1, std::size_t count) {
        if (count == 4) {
            const double a = c[s1], b = c[s1 + 1];
            c[s1] = -c[s1 + 2];
            c[s1 + 1] = -c[s1 + 3];
            c[s1 + 2] = a;
            c[s1 + 3] = b;
        } else {  // COLMAP's sx1, sy1: x gets sx1 r^2, y sy1 r^2
            const double a = c[s1];
            c[s1] = -c[s1 + 1];
            c[s1 + 1] = a;
        }
    };
    switch (lens.type) {
        case LensType::Pinhole:
        case LensType::Fisheye:
        case LensType::Stereographic:
        case LensType::DoubleSphere:
        case LensType::Ucm:
        case LensType::Eucm:
        case LensType::Fov:
        case LensType::Division:  // radial only
        case LensType::Equisolid:
        case LensType::LensPolynomial:
        case LensType::Ptlens:
        case LensType::EquidistantRadial:
        case LensType::EquisolidRadial:
        case LensType::StereographicRadial: return out;
        case LensType::OcamCalib:  // radial about the axis when its affine is the identity
            if (c[0] == 1.0 && c[1] == 0.0 && c[2] == 0.0) return out;
            break;  // the affine turned puts its 1 on the other diagonal: another scale, not yet turned
        case LensType::ThetaPolynomial: return out;
        case LensType::FTheta:  // radial about the axis when its affine is the identity
        case LensType::FThetaForward:
            if (c[0] == 1.0 && c[1] == 0.0 && c[2] == 0.0) return out;
            break;  // the affine turned is not of the form [c d; e 1] with the same polynomial
        case LensType::OpenCv4:
        case LensType::OpenCv5:
        case LensType::OpenCv8:
        case LensType::BrownK4: tangential(2, 3); return out;
        case LensType::OpenCv12:
            tangential(2, 3);
            prism(8, 4);
            return out;
        case LensType::Mei: tangential(3, 4); return out;
        case LensType::ThinPrismFisheye:  // k1 k2 p1 p2 k3 k4 sx1 sy1
            tangential(2, 3);
            prism(6, 2);
            return out;
        case LensType::RadTanThinPrismFisheye:  // k0..k5 p0 p1 s0..s3; its p0 is OpenCV's p2
            tangential(7, 6);
            prism(8, 4);
            return out;
        // Every model below is named, with no default, so that the compiler asks about a
        // new model here: can its coefficients be turned?
        case LensType::OpenCv14:  // the tilt (tauX, tauY) not yet turned
        case LensType::Lonlat:    // the longitude runs across, the latitude down
        case LensType::Latlon:
        case LensType::Cylindrical:
        case LensType::Cahvor:  // the axis's offset (alpha, beta) not yet turned
        case LensType::Cahvore:
        case LensType::SplinedStereographic:  // a grid of control points not yet turned
            break;
    }
    throw InvalidArgument("quarter turn: a " + std::string(lens_info(lens.type).name) +
                          " lens does not look the same turned about its axis, and libcam cannot turn its "
                          "coefficients");
}

Camera turned_once(const Camera& camera) {
    if (camera.intrinsics.skew != 0.0) {
        throw InvalidArgument("quarter turn: skew " + format_number(camera.intrinsics.skew) +
                              " would move below K's diagonal (a turned skewed camera has no K)");
    }
    Camera out = camera;
    out.lens = lens_turned(camera.lens);
    out.size = {camera.size.height, camera.size.width};
    // Pixel (x, y) goes to (H - 1 - y, x).
    const Intrinsics& k = camera.intrinsics;
    out.intrinsics = {k.fy, k.fx, static_cast<double>(camera.size.height - 1) - k.cy, k.cx, 0.0};
    Mat3 q;
    q << 0, -1, 0, 1, 0, 0, 0, 0, 1;
    out.pose = {q * camera.pose.R, q * camera.pose.t};
    return out;
}

}  // namespace

Camera resized(const Camera& camera, const ImageSize& size) {
    camera.validate();
    const ImageSize checked = checked_size(size.width, size.height, "resize");
    return scaled_axes(camera, static_cast<double>(checked.width) / static_cast<double>(camera.size.width),
                       static_cast<double>(checked.height) / static_cast<double>(camera.size.height), checked);
}

Camera scaled(const Camera& camera, double scale) {
    if (!(scale > 0) || !std::isfinite(scale)) {
        throw InvalidArgument("resize: the scale must be a positive number, got " + format_number(scale));
    }
    camera.validate();
    const auto side = [&](long pixels) {
        return static_cast<long>(std::max(1.0, std::round(std::min(scale * static_cast<double>(pixels), 1e9))));
    };
    return resized(camera, {side(camera.size.width), side(camera.size.height)});
}

Camera cropped(const Camera& camera, long x0, long y0, long x1, long y1) {
    camera.validate();
    if (x1 <= x0 || y1 <= y0) {
        throw InvalidArgument("crop: x1 must exceed x0 and y1 y0, got " + std::to_string(x0) + "," + std::to_string(y0) +
                              "," + std::to_string(x1) + "," + std::to_string(y1));
    }
    Camera out = camera;
    out.size = checked_size(x1 - x0, y1 - y0, "crop");
    out.intrinsics.cx -= static_cast<double>(x0);
    out.intrinsics.cy -= static_cast<double>(y0);
    return out;
}

Camera padded(const Camera& camera, long left, long top, long right, long bottom) {
    return cropped(camera, -left, -top, camera.size.width + right, camera.size.height + bottom);
}

Camera binned(const Camera& camera, int factor) {
    if (factor < 1) throw InvalidArgument("bin: the factor must be 1 or more, got " + std::to_string(factor));
    camera.validate();
    const ImageSize size = checked_size(camera.size.width / factor, camera.size.height / factor, "bin");
    return scaled_axes(camera, 1.0 / factor, 1.0 / factor, size);
}

Camera quarter_turns(const Camera& camera, int turns) {
    camera.validate();
    Camera out = camera;
    for (int i = 0; i < ((turns % 4) + 4) % 4; ++i) out = turned_once(out);
    return out;
}

}  // namespace libcam
