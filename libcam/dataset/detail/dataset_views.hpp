#pragma once
// `libcam dataset --camera views`: a lens wider than one pinhole holds well, split into
// several pinhole views turned away from its axis (colmap_dataset.hpp's make_pinhole_dataset
// calls these; they are here so that the rest of the dataset code stays one view per camera).
//
// The choice (choose_views): the rays the lens has (the pixel centres of its image that
// unproject, every step-th row and column for at most about 250000 of them, and the last
// row and column) and every observation's ray. A lens whose rays all lie within
// kViewHalfAngleDeg of its axis stays one view. A wider one is tried against a fixed list of layouts, each a set of view axes
// given by a yaw (about the source's y, towards +x) and a pitch (towards +y): each ray goes
// to the view whose axis is nearest, and a layout holds the lens when every ray is within
// kViewHalfAngleDeg of its view's axis. Each view is then the smallest pinhole (the
// source's pixels per radian at its centre, square pixels) whose image holds every ray
// given to it, so a view is cropped to what the lens sees. Of the layouts that hold the
// lens, the one with the fewest views wins, then the one with the fewest pixels; its views
// are then sized over the ray of every pixel, so every pixel that has a ray lands on one.
//
// Each view's turn Q is its axes relative to the source's (d_view = Q d_source, as
// RemapOptions::rotation): its pose is R_view = Q R_source, t_view = Q t_source.

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/dataset/colmap_dataset.hpp"
#include "libcam/io/detail/colmap_format.hpp"

namespace libcam {

// A view's rays keep within this angle of its axis: a pinhole stretches a ray at angle a
// off its axis by 1/cos^2(a) radially, 4x at 60 degrees.
inline constexpr double kViewHalfAngleDeg = 60.0;

struct LensView {
    Camera camera;            // the pinhole (pose: the source's turned by `turn`)
    Mat3 turn = Mat3::Identity();
    double yaw_deg = 0, pitch_deg = 0;
};

struct LensViews {
    std::vector<LensView> views;
    std::string why;  // how many views and why, in a sentence
};

// `extra_rays`: directions in the source camera's frame that must land in a view too (the
// observations' rays). Throws InvalidArgument when the lens has no ray or no layout holds
// it (a lens that sees all around: the message says how far off the axis it sees).
LensViews choose_views(const PreparedCamera& source, std::span<const Vec3> extra_rays, int threads = 1);

// The image name of view k of a source image: "<stem>_view<k><extension>" in the same
// folder ("sub/a.png", 2 -> "sub/a_view2.png").
std::string view_image_name(const std::string& source_name, std::size_t view);

// A model with each source camera replaced by its views: what make_pinhole_dataset then
// carries as it carries a model of one view per camera.
struct ViewSplit {
    std::vector<DatasetCamera> cameras;       // one per source camera and view, ids 1, 2, ...
    std::vector<ColmapCameraRecord> records;  // the same, as the output's cameras
    // One per source image and view of its camera (ids 1, 2, ...): the view's name (the
    // source's with one view) and turned pose, and the source's POINTS2D as they are.
    std::vector<ColmapImage> images;
    std::vector<std::size_t> camera_of;       // each image's camera, an index into `cameras`
    std::vector<std::size_t> source_of;       // each image's source image, an index
    ColmapPoints3D points;                    // each track element repeated for every view of its image
};

// `kept_as_is[c]`: source camera c's one view when it is already a pinhole kept as it is.
// `where` names the model in messages. Throws FileError for a track naming no image, and
// InvalidArgument (naming the camera) when no layout of views holds a lens.
ViewSplit split_into_views(const std::vector<ColmapCameraRecord>& cameras, const std::vector<ColmapImage>& images,
                           const ColmapPoints3D& points, const std::vector<std::size_t>& camera_of,
                           const std::vector<std::optional<DatasetCamera>>& kept_as_is, const std::string& where,
                           int threads);

}  // namespace libcam
