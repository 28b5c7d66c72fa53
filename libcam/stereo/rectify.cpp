#include "libcam/stereo/rectify.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "libcam/camera/batch.hpp"
#include "libcam/camera/parallel.hpp"
#include "libcam/camera/projector.hpp"
#include "libcam/camera/unprojector.hpp"
#include "libcam/error.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr std::size_t kChunk = 8192;
// LATLON's elevation range leaves out the rays this close to the baseline's line (below).
constexpr double kNearPoleDeg = 10.0;
// The largest side a rectified image may have: a request past it is a mistake (a view
// wider than the lens, a resolution of a degenerate lens), not a picture.
constexpr long kLargestSide = 100000;

const char* kSide[2] = {"first", "second"};

// Every pixel's ray (exact unprojection) in its own camera's frame, row by row.
struct SourceRays {
    Points3<double> rays;
    ValidFlags has_ray;
};

SourceRays rays_of(const PreparedCamera& source, int threads) {
    SourceRays out;
    source.unprojector().unproject_image(UnprojectMethod::Exact, out.rays, out.has_ray, threads);
    return out;
}

Vec3 ray_at(const SourceRays& rays, std::size_t i) { return {rays.rays.x[i], rays.rays.y[i], rays.rays.z[i]}; }

// The rays of the pixels that look in front of the source (z > 0) and of those that land on
// the rectified image, counted in chunks turned by `rotation` and projected.
double kept_of(const SourceRays& source, const PreparedCamera& rectified, const Mat3& rotation, int threads) {
    const Projector<double> projector(rectified);
    const ImageSize& size = rectified.camera().size;
    const std::size_t n = source.has_ray.size();
    std::atomic<std::size_t> in_front{0}, landed{0};
    parallel_chunks(n, threads, kChunk, [&](std::size_t begin, std::size_t end) {
        Points3<double> turned;
        Points2<double> pixels;
        ValidFlags projected;
        std::size_t front = 0, on = 0;
        for (std::size_t first = begin; first < end; first += kChunk) {
            const std::size_t last = std::min(end, first + kChunk);
            turned.x.clear(), turned.y.clear(), turned.z.clear();
            for (std::size_t i = first; i < last; ++i) {
                if (source.has_ray[i] == 0 || !(source.rays.z[i] > 0)) continue;
                const Vec3 d = rotation * ray_at(source, i);
                turned.x.push_back(d.x()), turned.y.push_back(d.y()), turned.z.push_back(d.z());
            }
            projector.project(turned, pixels, projected);
            front += turned.size();
            for (std::size_t j = 0; j < turned.size(); ++j) {
                on += projected[j] != 0 && on_image(pixels.x[j], pixels.y[j], size) ? 1 : 0;
            }
        }
        in_front += front;
        landed += on;
    });
    return in_front == 0 ? 0.0 : static_cast<double>(landed) / static_cast<double>(in_front);
}

// Where the pair is, from the first camera's frame: the relative rotation and translation as
// OpenCV's stereo calibration gives them (X1 = R X0 + T), and the second centre.
struct PairGeometry {
    Mat3 R;            // first camera's frame into the second's
    Vec3 T;            // the first centre in the second camera's frame
    Vec3 second_centre; // in the first camera's frame
    double baseline;
};

PairGeometry geometry_of(const Camera& first, const Camera& second) {
    PairGeometry g;
    g.R = second.pose.R * first.pose.R.transpose();
    g.T = second.pose.t - g.R * first.pose.t;
    g.second_centre = first.pose.R * (second.pose.centre() - first.pose.centre());
    g.baseline = g.second_centre.norm();
    const double scale = std::max({first.pose.centre().norm(), second.pose.centre().norm(), 1e-300});
    if (!(g.baseline > 1e-12 * scale)) {
        throw InvalidArgument("rectify: the two cameras have the same centre (baseline " + format_number(g.baseline) +
                              "): a pair needs them apart to see depth");
    }
    return g;
}

// OpenCV's rectifying rotations (cv::stereoRectify): each camera turned by half the relative
// rotation towards the other, then both by the smallest rotation that lays the baseline on
// the x axis, the second centre on +x. The angle by atan2, accurate for small angles too.
std::array<Mat3, 2> opencv_rotations(const PairGeometry& g) {
    const Mat3 half = rotation_from_rvec(-0.5 * rvec_from_rotation(g.R));
    const Vec3 t = half * g.T;  // the first centre from the second, in the shared orientation
    const Vec3 towards(-1.0, 0.0, 0.0);
    const Vec3 axis = t.cross(towards);
    const double angle = std::atan2(axis.norm(), t.dot(towards));
    Mat3 level;
    if (axis.norm() > 0) {
        level = rotation_from_rvec(axis.normalized() * angle);
    } else {
        level = t.x() < 0 ? Mat3::Identity() : Mat3(Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal());
    }
    return {level * half.transpose(), level * half};
}

// mrcal's (mrcal.rectified_system): x towards the second centre, z the mean of the optical
// axes without its part along x, y completing them. Also the azimuth of the cameras' mean
// axis (mrcal's az0), the centre of the view.
struct MrcalFrame {
    std::array<Mat3, 2> rotations;
    double az0 = 0;
};

MrcalFrame mrcal_rotations(const PairGeometry& g) {
    const Vec3 right = g.second_centre / g.baseline;
    const Vec3 mean_axis = Vec3::UnitZ() + g.R.transpose().col(2);  // both optical axes in the first frame
    const double along = mean_axis.dot(right);
    const Vec3 forward_part = mean_axis - along * right;
    if (!(forward_part.norm() > 1e-12 * mean_axis.norm())) {
        throw InvalidArgument("rectify: the cameras look along their baseline (their mean optical axis is the line "
                              "between their centres): no rows to rectify");
    }
    const Vec3 forward = forward_part.normalized();
    const Vec3 down = forward.cross(right);
    Mat3 first;
    first.row(0) = right;
    first.row(1) = down;
    first.row(2) = forward;
    MrcalFrame frame;
    frame.rotations = {first, first * g.R.transpose()};
    frame.az0 = std::asin(std::clamp(along / mean_axis.norm(), -1.0, 1.0));
    return frame;
}

// Azimuth and elevation of a direction in the rectified frame (LatlonLens's m).
double azimuth_of(const Vec3& d) { return std::atan2(d.x(), std::hypot(d.y(), d.z())); }
double elevation_of(const Vec3& d) { return std::atan2(d.y(), d.z()); }

// The angles the rays of both cameras span in a rectified frame: azimuth and elevation, and
// whether any looks sideways or behind (z <= 0), where no pinhole reaches. Elevation is taken
// from the rays more than kNearPoleDeg from the baseline's line: near it a ray's elevation
// turns fast with its direction (on the line it has none), and a lens that sees just past 90
// degrees along the baseline would otherwise ask for every elevation, twice the rows, for a
// few pixels that see no depth.
struct AngleSpan {
    double az_low = std::numeric_limits<double>::infinity(), az_high = -az_low;
    double el_low = az_low, el_high = -az_low;
    double az_off_centre = 0;  // largest |az - centre|, for mrcal's symmetric view
    bool beside_or_behind = false;
    std::size_t rays = 0;

    double el_off_centre() const { return el_low > el_high ? 0.0 : std::max(std::abs(el_low), std::abs(el_high)); }
};

AngleSpan span_of(const std::array<const SourceRays*, 2>& sources, const std::array<Mat3, 2>& rotations, double az0) {
    AngleSpan span;
    for (std::size_t k = 0; k < 2; ++k) {
        const SourceRays& source = *sources[k];
        for (std::size_t i = 0; i < source.has_ray.size(); ++i) {
            if (source.has_ray[i] == 0) continue;
            const Vec3 d = rotations[k] * ray_at(source, i);
            const double az = azimuth_of(d), el = elevation_of(d);
            span.az_low = std::min(span.az_low, az), span.az_high = std::max(span.az_high, az);
            if (std::abs(az) <= (90.0 - kNearPoleDeg) * kDegree) {
                span.el_low = std::min(span.el_low, el), span.el_high = std::max(span.el_high, el);
            }
            span.az_off_centre = std::max(span.az_off_centre, std::abs(az - az0));
            span.beside_or_behind = span.beside_or_behind || !(d.z() > 0);
            ++span.rays;
        }
    }
    return span;
}

std::string degrees(double radians) { return format_short(radians / kDegree, 4) + " deg"; }

Pose turned_pose(const Camera& source, const Mat3& rotation) { return {rotation * source.pose.R, rotation * source.pose.t}; }

Camera rectified_camera(const Camera& source, const Mat3& rotation, LensType model, const Intrinsics& K,
                        const ImageSize& size) {
    Camera camera;
    camera.size = size;
    camera.intrinsics = K;
    camera.lens = {model, {}};
    camera.pose = turned_pose(source, rotation);
    return camera;
}

// ---- PINHOLE -------------------------------------------------------------------------------

// The normalised point (x / z, y / z) of a direction in front.
Vec2 normalised(const Vec3& d) { return {d.x() / d.z(), d.y() / d.z()}; }

// OpenCV's principal point: the image centre minus the mean of the eight source corners'
// rays projected with OpenCV's first focal length (the mean of the two fy, scaled to the new
// size) and no offset; the same for both cameras (its default CALIB_ZERO_DISPARITY).
Vec2 opencv_principal_point(const std::array<const PreparedCamera*, 2>& sources, const std::array<Mat3, 2>& rotations,
                            const ImageSize& size) {
    const ImageSize& source_size = sources[0]->camera().size;
    const double ratio_x = static_cast<double>(size.width) / static_cast<double>(source_size.width);
    const double ratio_y = static_cast<double>(size.height) / static_cast<double>(source_size.height);
    const double f0 = 0.5 * (sources[0]->camera().intrinsics.fy + sources[1]->camera().intrinsics.fy) * ratio_y;
    Vec2 sum = Vec2::Zero();
    int corners = 0;
    for (std::size_t k = 0; k < 2; ++k) {
        const ImageSize& s = sources[k]->camera().size;
        for (const Vec2& corner : {Vec2(0, 0), Vec2(static_cast<double>(s.width - 1), 0),
                                   Vec2(0, static_cast<double>(s.height - 1)),
                                   Vec2(static_cast<double>(s.width - 1), static_cast<double>(s.height - 1))}) {
            const Unprojection ray = sources[k]->unproject(corner);
            if (!ray.valid) continue;
            const Vec3 d = rotations[k] * ray.direction;
            if (!(d.z() > 0)) continue;
            sum += f0 * normalised(d);
            ++corners;
        }
    }
    const Vec2 mean = corners == 0 ? Vec2::Zero() : Vec2(sum / corners);
    return {(source_size.centre_x() - mean.x()) * ratio_x, (source_size.centre_y() - mean.y()) * ratio_y};
}

// Whether every pixel of the rectified view (its border, and a lattice every 16 pixels
// inside) has a source in both images: its ray lands on the source image's pixels' area,
// [-0.5, W - 0.5] x [-0.5, H - 0.5], where remap's map gives it a source (remap_map.hpp).
bool both_see_all(const Intrinsics& K, const ImageSize& size, const std::array<const PreparedCamera*, 2>& sources,
                  const std::array<Mat3, 2>& rotations) {
    Points3<double> rays;
    const auto add = [&](long x, long y) {
        rays.x.push_back((static_cast<double>(x) - K.cx) / K.fx);
        rays.y.push_back((static_cast<double>(y) - K.cy) / K.fy);
        rays.z.push_back(1.0);
    };
    for (long x = 0; x < size.width; ++x) add(x, 0), add(x, size.height - 1);
    for (long y = 0; y < size.height; ++y) add(0, y), add(size.width - 1, y);
    for (long y = 8; y < size.height; y += 16)
        for (long x = 8; x < size.width; x += 16) add(x, y);
    for (std::size_t k = 0; k < 2; ++k) {
        Points3<double> turned = rays;
        const Mat3 back = rotations[k].transpose();
        for (std::size_t j = 0; j < rays.size(); ++j) {
            const Vec3 d = back * Vec3(rays.x[j], rays.y[j], rays.z[j]);
            turned.x[j] = d.x(), turned.y[j] = d.y(), turned.z[j] = d.z();
        }
        Points2<double> pixels;
        ValidFlags projected;
        Projector<double>(*sources[k]).project(turned, pixels, projected);
        for (std::size_t j = 0; j < turned.size(); ++j) {
            if (projected[j] == 0 || !on_image(pixels.x[j], pixels.y[j], sources[k]->camera().size)) return false;
        }
    }
    return true;
}

// Keep::Valid: the smallest focal length (widest view) about the principal point with a
// source for every pixel in both images.
double widest_valid_focal(const Vec2& principal, const ImageSize& size, const std::array<const PreparedCamera*, 2>& sources,
                          const std::array<Mat3, 2>& rotations, double start) {
    const auto passes = [&](double f) { return both_see_all({f, f, principal.x(), principal.y(), 0.0}, size, sources, rotations); };
    // No wider than kWidestPinholeDeg across the diagonal, measured from the principal point.
    const double reach = std::max({std::hypot(principal.x(), principal.y()),
                                   std::hypot(static_cast<double>(size.width) - principal.x(), principal.y()),
                                   std::hypot(principal.x(), static_cast<double>(size.height) - principal.y()),
                                   std::hypot(static_cast<double>(size.width) - principal.x(),
                                              static_cast<double>(size.height) - principal.y())});
    const double widest = reach / std::tan(0.5 * kWidestPinholeDeg * kDegree);
    return smallest_passing_scale(widest, start, passes,
                                  "rectify: no pinhole view, however narrow, about the principal point has a source in "
                                  "both images for every pixel: the cameras do not see the same part of the scene");
}

// Keep::All: the largest focal length (narrowest view) that puts every pixel centre of both
// images that looks within kWidestPinholeDeg / 2 of the rectified axis on the image's pixel
// centres. Counts the rays left out for `why`.
double narrowest_whole_focal(const Vec2& principal, const ImageSize& size,
                             const std::array<const SourceRays*, 2>& sources, const std::array<Mat3, 2>& rotations,
                             std::size_t& left_out) {
    const double cos_widest = std::cos(0.5 * kWidestPinholeDeg * kDegree);
    const double last_x = static_cast<double>(size.width - 1), last_y = static_cast<double>(size.height - 1);
    double f = std::numeric_limits<double>::infinity();
    left_out = 0;
    const auto limit = [&](double m, double centre, double last) {
        if (m > 0) f = std::min(f, (last - centre) / m);
        if (m < 0) f = std::min(f, -centre / m);
    };
    for (std::size_t k = 0; k < 2; ++k) {
        for (std::size_t i = 0; i < sources[k]->has_ray.size(); ++i) {
            if (sources[k]->has_ray[i] == 0) continue;
            const Vec3 d = rotations[k] * ray_at(*sources[k], i);
            if (!(d.z() > cos_widest * d.norm())) {
                ++left_out;
                continue;
            }
            const Vec2 m = normalised(d);
            limit(m.x(), principal.x(), last_x);
            limit(m.y(), principal.y(), last_y);
        }
    }
    if (!(f > 0) || !std::isfinite(f)) {
        throw InvalidArgument("rectify: the principal point (" + format_short(principal.x(), 6) + ", " +
                              format_short(principal.y(), 6) +
                              ") is not inside the image: no pinhole view about it holds every pixel");
    }
    return f;
}

void rectify_to_pinhole(RectifiedPair& pair, const std::array<const Camera*, 2>& sources,
                        const std::array<const PreparedCamera*, 2>& prepared, const std::array<const SourceRays*, 2>& rays,
                        const PairGeometry& g, const RectifyRequest& request) {
    const std::array<Mat3, 2> rotations = opencv_rotations(g);
    const ImageSize size = request.size.value_or(sources[0]->size);
    const Vec2 principal = opencv_principal_point(prepared, rotations, size);
    double f = 0;
    std::string view;
    if (request.keep == Keep::Valid) {
        f = widest_valid_focal(principal, size, prepared, rotations, sources[0]->intrinsics.fy);
        view = "the widest view with a source in both images for every pixel (no black border, OpenCV's alpha 0)";
    } else {
        std::size_t left_out = 0;
        f = narrowest_whole_focal(principal, size, rays, rotations, left_out);
        view = "the narrowest view that keeps every pixel either camera sees (OpenCV's alpha 1)";
        if (left_out > 0) {
            view += ", but for " + std::to_string(left_out) + " pixels looking more than " +
                    format_short(0.5 * kWidestPinholeDeg, 3) + " deg off the rectified axis, which no pinhole holds";
        }
    }
    const Intrinsics K{f, f, principal.x(), principal.y(), 0.0};
    for (std::size_t k = 0; k < 2; ++k) {
        pair.cameras[k].rotation = rotations[k];
        pair.cameras[k].camera = rectified_camera(*sources[k], rotations[k], LensType::Pinhole, K, size);
    }
    // OpenCV's Q: [X Y Z W] = Q [u v d 1], Tx the second camera's x offset (-baseline).
    const double tx = -g.baseline;
    pair.Q << 1, 0, 0, -principal.x(),  //
        0, 1, 0, -principal.y(),        //
        0, 0, 0, f,                     //
        0, 0, -1.0 / tx, 0;
    pair.why += "PINHOLE " + std::to_string(size.width) + "x" + std::to_string(size.height) + ", f " +
                format_short(f, 6) + " px, principal point (" + format_short(principal.x(), 6) + ", " +
                format_short(principal.y(), 6) + ") as OpenCV places it: " + view + ".";
}

// ---- LATLON --------------------------------------------------------------------------------

// Pixels per radian of azimuth and of elevation of the first camera at the view's centre
// (azimuth az0, elevation 0): |dq/daz| and |dq/del| (mrcal's choice of resolution), by
// central differences of its projection along the two directions.
Vec2 resolution_at_centre(const PreparedCamera& first, const Mat3& to_first, double az0) {
    const auto direction = [](double az, double el) {
        return Vec3(std::sin(az), std::cos(az) * std::sin(el), std::cos(az) * std::cos(el));
    };
    const double h = 1e-5;
    const auto pixel = [&](double az, double el, const char* which) {
        const Projection p = first.project_camera_point(to_first * direction(az, el));
        if (!p.valid) {
            throw InvalidArgument(std::string("rectify: the first camera does not see the centre of the view (") +
                                  which + "): no resolution to match");
        }
        return p.pixel;
    };
    const double along = (pixel(az0 + h, 0, "azimuth") - pixel(az0 - h, 0, "azimuth")).norm() / (2 * h);
    const double across = (pixel(az0, h, "elevation") - pixel(az0, -h, "elevation")).norm() / (2 * h);
    return {along, across};
}

long side_for(double radians, double pixels_per_radian, const char* what) {
    const double pixels = std::ceil(radians * pixels_per_radian - 1e-9);
    if (!(pixels <= static_cast<double>(kLargestSide))) {
        throw InvalidArgument(std::string("rectify: the LATLON image would be ") + format_short(pixels, 6) +
                              " pixels " + what + " (more than " + std::to_string(kLargestSide) + ")");
    }
    return std::max(1L, static_cast<long>(pixels));
}

void rectify_to_latlon(RectifiedPair& pair, const std::array<const Camera*, 2>& sources,
                       const std::array<const PreparedCamera*, 2>& prepared, const std::array<const SourceRays*, 2>& rays,
                       const MrcalFrame& frame) {
    const AngleSpan span = span_of(rays, frame.rotations, frame.az0);
    const Vec2 resolution = resolution_at_centre(*prepared[0], frame.rotations[0].transpose(), frame.az0);
    const double half_el = span.el_off_centre();
    const ImageSize size{side_for(2 * span.az_off_centre, resolution.x(), "across"),
                         side_for(2 * half_el, resolution.y(), "down")};
    // mrcal's: (az0, 0) at the image's centre.
    const Intrinsics K{resolution.x(), resolution.y(), size.centre_x() - resolution.x() * frame.az0, size.centre_y(), 0.0};
    for (std::size_t k = 0; k < 2; ++k) {
        pair.cameras[k].rotation = frame.rotations[k];
        pair.cameras[k].camera = rectified_camera(*sources[k], frame.rotations[k], LensType::Latlon, K, size);
    }
    pair.why += "LATLON " + std::to_string(size.width) + "x" + std::to_string(size.height) + ", " +
                format_short(resolution.x() * kDegree, 6) + " px per degree of azimuth and " +
                format_short(resolution.y() * kDegree, 6) + " of elevation (the first camera's at the centre), " +
                "azimuth " + degrees(frame.az0) + " +- " + degrees(span.az_off_centre) + ", elevation 0 +- " +
                degrees(half_el) + ": every ray either camera sees (elevations within " +
                format_short(kNearPoleDeg, 3) + " deg of the baseline's line left out).";
}

}  // namespace

double kept_share(const PreparedCamera& source, const PreparedCamera& rectified, const Mat3& rotation, int threads) {
    return kept_of(rays_of(source, threads), rectified, rotation, threads);
}

RectifiedPair rectify_pair(const Camera& first, const Camera& second, const RectifyRequest& request) {
    if (request.model && *request.model != LensType::Pinhole && *request.model != LensType::Latlon) {
        throw InvalidArgument("rectify: the rectified model must be PINHOLE or LATLON, got " +
                              std::string(lens_info(*request.model).name));
    }
    if (request.size) request.size->validate("size");
    const std::array<const Camera*, 2> sources{&first, &second};
    std::vector<PreparedCamera> prepared_cameras;
    for (std::size_t k = 0; k < 2; ++k) {
        try {
            prepared_cameras.emplace_back(*sources[k]);
        } catch (const InvalidArgument& error) {
            throw InvalidArgument(std::string("rectify: the ") + kSide[k] + " camera: " + error.what());
        }
    }
    const std::array<const PreparedCamera*, 2> prepared{&prepared_cameras[0], &prepared_cameras[1]};
    const PairGeometry g = geometry_of(first, second);
    const SourceRays rays0 = rays_of(*prepared[0], request.threads), rays1 = rays_of(*prepared[1], request.threads);
    const std::array<const SourceRays*, 2> rays{&rays0, &rays1};
    for (std::size_t k = 0; k < 2; ++k) {
        if (std::none_of(rays[k]->has_ray.begin(), rays[k]->has_ray.end(), [](std::uint8_t v) { return v != 0; })) {
            throw InvalidArgument(std::string("rectify: no pixel of the ") + kSide[k] + " camera has a ray");
        }
    }
    const MrcalFrame frame = mrcal_rotations(g);

    RectifiedPair pair;
    pair.baseline = g.baseline;
    if (request.model) {
        pair.model = *request.model;
        pair.why = std::string(lens_info(pair.model).name) + " as asked. ";
    } else {
        const AngleSpan span = span_of(rays, frame.rotations, frame.az0);
        const double across = span.az_high - span.az_low, down = std::max(span.el_high - span.el_low, 0.0);
        const double limit = kWidestRectifiedPinholeDeg * kDegree;
        const std::string seen = "the cameras see " + degrees(across) + " along the baseline and " + degrees(down) +
                                 " across it";
        if (span.beside_or_behind) {
            pair.model = LensType::Latlon;
            pair.why = seen + ", and some pixels look beside or behind the rectified view, which no pinhole holds: "
                              "LATLON. ";
        } else if (across >= limit || down >= limit) {
            pair.model = LensType::Latlon;
            pair.why = seen + ", " + format_short(kWidestRectifiedPinholeDeg, 3) +
                       " deg or more, where a pinhole stretches its edges: LATLON. ";
        } else {
            pair.model = LensType::Pinhole;
            pair.why = seen + ", under " + format_short(kWidestRectifiedPinholeDeg, 3) + " deg: PINHOLE. ";
        }
    }
    if (pair.model == LensType::Pinhole) {
        rectify_to_pinhole(pair, sources, prepared, rays, g, request);
    } else {
        rectify_to_latlon(pair, sources, prepared, rays, frame);
    }
    for (std::size_t k = 0; k < 2; ++k) {
        RectifiedCamera& out = pair.cameras[k];
        out.kept = kept_of(*rays[k], PreparedCamera(out.camera), out.rotation, request.threads);
    }
    return pair;
}

Vec3 point_from_disparity(const RectifiedPair& pair, const Vec2& left_pixel, double disparity) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (!(disparity > 0)) return Vec3::Constant(nan);
    if (pair.model == LensType::Pinhole) {
        const Eigen::Vector4d h = pair.Q * Eigen::Vector4d(left_pixel.x(), left_pixel.y(), disparity, 1.0);
        return h.head<3>() / h.w();
    }
    // mrcal.stereo_range: the angles in the epipolar plane; range = b cos(az_right) / sin(az_left - az_right).
    const Intrinsics& K = pair.cameras[0].camera.intrinsics;
    const double az = (left_pixel.x() - K.cx) / K.fx, el = (left_pixel.y() - K.cy) / K.fy;
    const double angle = disparity / K.fx;
    const double range = pair.baseline * std::cos(az - angle) / std::sin(angle);
    return range * Vec3(std::sin(az), std::cos(az) * std::sin(el), std::cos(az) * std::cos(el));
}

double range_from_disparity(const RectifiedPair& pair, const Vec2& left_pixel, double disparity) {
    return point_from_disparity(pair, left_pixel, disparity).norm();
}

}  // namespace libcam
