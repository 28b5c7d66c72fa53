#pragma once
// Rectifying a calibrated pair: two new cameras, at the two cameras' centres and sharing one
// orientation whose x axis runs from the first centre to the second, in which a point seen
// by both lands on the same row of both images. A stereo matcher then searches along rows.
//
//   const RectifiedPair pair = rectify_pair(left, right, RectifyRequest{});
//   pair.cameras[0].camera   // the rectified left camera (libcam Camera: remap makes its map)
//   pair.cameras[0].rotation // R1: a direction in the left camera's frame into the rectified frame
//
// Two kinds of rectified camera:
//   PINHOLE  OpenCV's (cv::stereoRectify's rotations: each camera turned half the relative
//            rotation, then both turned so that the baseline is the x axis; one K for both,
//            square pixels, the same principal point: disparity 0 at infinity). Its view keeps
//            no black border (Keep::Valid, OpenCV's alpha 0) or every pixel either camera sees
//            (Keep::All, alpha 1), worked out from the exact rays of the images' pixels (every
//            lens model), not from a few undistorted points.
//   LATLON   mrcal's (mrcal.rectified_system): z the cameras' mean optical axis without its
//            part along the baseline; columns azimuth and rows elevation, both uniform in angle
//            (LatlonLens: azimuth asin(x / |p|), elevation atan2(y, z)), so a lens of any width,
//            past 180 degrees too, keeps its view. Its resolution is the first camera's at the
//            centre of the view (mrcal's), its azimuth and elevation ranges symmetric about the
//            centre (mrcal's az0 and el0 = 0) and wide enough for every ray of both cameras.
// Auto: PINHOLE while both cameras see under kWidestRectifiedPinholeDeg across, in azimuth and
// in elevation, LATLON otherwise; RectifiedPair::why says which and why.
//
// Disparity: d = u_left - u_right (pixels). PINHOLE: depth f b / d, OpenCV's Q. LATLON: the
// range is mrcal.stereo_range's, b cos(az_right) / sin(az_left - az_right).

#include <array>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "libcam/camera/camera.hpp"
#include "libcam/remap/new_camera.hpp"

namespace libcam {

// Auto rectifies to a pinhole while every ray of both cameras is within this many degrees
// across, in azimuth and in elevation: a pinhole's edges stretch as tan, by 1.7 at 50 degrees
// off its axis and without bound towards 90.
inline constexpr double kWidestRectifiedPinholeDeg = 100.0;

struct RectifyRequest {
    // LensType::Pinhole or LensType::Latlon; nullopt: chosen (see above).
    std::optional<LensType> model;
    // PINHOLE: Keep::Valid (no black border) or Keep::All (everything seen). LATLON always
    // keeps everything seen.
    Keep keep = Keep::Valid;
    // PINHOLE: the rectified images' size (default: the first camera's).
    std::optional<ImageSize> size;
    int threads = 1;
};

struct RectifiedCamera {
    Camera camera;   // the rectified camera, in the sources' world
    Mat3 rotation;   // the source camera's frame into the rectified frame (OpenCV's R1, R2)
    double kept = 0; // share of the source's pixels looking in front of it whose rays land in the image
};

struct RectifiedPair {
    LensType model = LensType::Pinhole;
    std::array<RectifiedCamera, 2> cameras;
    double baseline = 0;       // distance between the centres, in the poses' units
    Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();  // PINHOLE: OpenCV's disparity-to-depth matrix; LATLON: zero
    std::string why;           // the model and the view chosen, and why, in sentences
};

// Throws InvalidArgument, naming the camera and the value, for a camera that is not valid,
// two cameras with the same centre (no baseline), or a request that cannot be met.
RectifiedPair rectify_pair(const Camera& first, const Camera& second, const RectifyRequest& request = {});

// The share of `source`'s pixels whose ray (exact unprojection) looks in front of it (z > 0 in
// its frame) that land on `rectified`'s image (within its pixels' area) once turned by
// `rotation` (source frame to rectified frame). 0 when no pixel looks in front.
double kept_share(const PreparedCamera& source, const PreparedCamera& rectified, const Mat3& rotation, int threads = 1);

// The point seen at `left_pixel` of the first rectified image with disparity `disparity`
// (u_left - u_right, pixels), in the first rectified camera's frame. Not finite where the
// disparity gives no point (d <= 0).
Vec3 point_from_disparity(const RectifiedPair& pair, const Vec2& left_pixel, double disparity);
// Its distance from the first camera's centre (mrcal.stereo_range's range).
double range_from_disparity(const RectifiedPair& pair, const Vec2& left_pixel, double disparity);

}  // namespace libcam
