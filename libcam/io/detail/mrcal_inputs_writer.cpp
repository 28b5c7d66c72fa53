// mrcal's optimization_inputs written from a board calibration's observations: the arrays
// mrcal.optimize() takes (mrcal 2.2's names and shapes, as its cameramodel.py stores them:
// None as the empty string), in an .npz archive, in base85, as a Python bytes literal.
// mrcal_observations.cpp reads the same back.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/io/detail/mrcal_observations.hpp"
#include "libcam/io/detail/npz_archive.hpp"
#include "libcam/io/observations.hpp"
#include "libcam/lens/lens_model.hpp"

namespace libcam {

namespace {

using detail::NpyArray;

NpyArray numbers(std::vector<std::size_t> shape, std::vector<double> values, const char* descr = "<f8") {
    return NpyArray{descr, std::move(shape), std::move(values), {}};
}
NpyArray flag(bool value) { return numbers({}, {value ? 1.0 : 0.0}, "|b1"); }
NpyArray text(std::string value) { return NpyArray{"<U1", {}, {}, std::move(value)}; }
NpyArray none() { return text(""); }  // mrcal stores None as ''

void append_rt(std::vector<double>& out, const Pose& pose) {
    const Vec3 r = pose.rvec();
    out.insert(out.end(), {r.x(), r.y(), r.z(), pose.t.x(), pose.t.y(), pose.t.z()});
}

[[noreturn]] void cannot(const std::string& why) {
    throw NotRepresentable("mrcal's optimization_inputs cannot hold these observations: " + why);
}

// The cameras' mrcal intrinsics (fx fy cx cy, then the coefficients its name does not
// hold), one lens model for all, as mrcal solves them.
std::pair<std::string, std::vector<double>> mrcal_intrinsics(const ObservationSet& set) {
    const Camera& first = set.cameras.front().camera;
    const std::string lensmodel = mrcal_model_name(first.lens.type, first.lens.coefficients);
    if (lensmodel.empty()) cannot("mrcal has no " + std::string(lens_info(first.lens.type).name) + " model");
    const LensInfo& info = lens_info(first.lens.type);
    std::vector<double> intrinsics;
    for (const ObservedCamera& observed : set.cameras) {
        const Camera& camera = observed.camera;
        if (mrcal_model_name(camera.lens.type, camera.lens.coefficients) != lensmodel) {
            cannot("mrcal solves cameras of one lens model; camera " + observed.name + " is " +
                   mrcal_model_name(camera.lens.type, camera.lens.coefficients) + ", camera " +
                   set.cameras.front().name + " " + lensmodel);
        }
        if (camera.intrinsics.skew != 0.0) cannot("camera " + observed.name + " has skew, which mrcal lacks");
        const Intrinsics& k = camera.intrinsics;
        intrinsics.insert(intrinsics.end(), {k.fx, k.fy, k.cx, k.cy});
        const auto& c = camera.lens.coefficients;
        intrinsics.insert(intrinsics.end(), c.begin() + info.mrcal_in_name.leading, c.end() - info.mrcal_in_name.trailing);
    }
    return {lensmodel, intrinsics};
}

}  // namespace

std::string mrcal_optimization_inputs(const ObservationSet& set, double observed_pixel_uncertainty) {
    if (!set.board) cannot("they are not of a board");
    if (set.cameras.empty() || set.views.empty()) cannot("no cameras or no views");
    const ObservedBoard& board = *set.board;
    const std::size_t corners = static_cast<std::size_t>(board.width) * static_cast<std::size_t>(board.height);
    if (set.points.size() != corners) {
        cannot(std::to_string(set.points.size()) + " points for a board of " + std::to_string(board.width) + " x " +
               std::to_string(board.height) + " corners");
    }
    // mrcal places corner (row i, column j) at (j, i) * spacing; points elsewhere would be
    // another board than the one mrcal would read.
    for (std::size_t k = 0; k < corners; ++k) {
        const Vec2 grid(double(k % std::size_t(board.width)) * board.spacing, double(k / std::size_t(board.width)) * board.spacing);
        if ((set.points[k].head<2>() - grid).norm() > 1e-9 * board.spacing * double(board.width + board.height)) {
            cannot("point " + std::to_string(k) + " is not where mrcal places that corner of the board");
        }
    }
    const auto [lensmodel, intrinsics] = mrcal_intrinsics(set);
    const std::size_t cameras = set.cameras.size();
    const bool shared_frames = !set.frames.empty();
    if (!shared_frames && cameras > 1) cannot("several cameras without the board poses they share");

    // The board poses (frames) and, for each camera but the first, its pose from the first:
    // mrcal's frames_rt_toref and extrinsics_rt_fromref.
    std::vector<Pose> frames = set.frames;
    if (!shared_frames) {
        for (const ObservedView& view : set.views) frames.push_back(view.pose);
    }
    std::vector<std::optional<Pose>> from_reference(cameras);
    from_reference[0] = Pose{};
    std::vector<std::size_t> order(set.views.size());  // the views by frame: mrcal wants them so
    for (std::size_t v = 0; v < order.size(); ++v) order[v] = v;
    const auto frame_of = [&](std::size_t v) { return shared_frames ? set.views[v].frame : static_cast<int>(v); };
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return std::pair(frame_of(a), set.views[a].camera) < std::pair(frame_of(b), set.views[b].camera);
    });
    for (std::size_t v = 0; v < set.views.size(); ++v) {
        const ObservedView& view = set.views[v];
        const int frame = frame_of(v);
        if (frame < 0 || static_cast<std::size_t>(frame) >= frames.size()) cannot("view " + view.name + " has no board pose");
        auto& pose = from_reference[static_cast<std::size_t>(view.camera)];
        if (!pose) pose = view.pose.after(frames[static_cast<std::size_t>(frame)].inverse());
    }
    std::vector<double> extrinsics;
    for (std::size_t c = 1; c < cameras; ++c) {
        if (!from_reference[c]) cannot("camera " + set.cameras[c].name + " has no view");
        append_rt(extrinsics, *from_reference[c]);
    }
    std::vector<double> frames_rt;
    for (const Pose& frame : frames) append_rt(frames_rt, frame);

    // Every corner of every view: (x, y, weight); a corner not seen, or an outlier, weighs -1.
    std::vector<std::size_t> row_of_view(set.views.size());
    for (std::size_t row = 0; row < order.size(); ++row) row_of_view[order[row]] = row;
    std::vector<double> observed(order.size() * corners * 3, 0.0);
    for (std::size_t i = 2; i < observed.size(); i += 3) observed[i] = -1.0;
    for (const Observation& o : set.observations) {
        if (o.view < 0 || std::size_t(o.view) >= set.views.size() || o.point < 0 || std::size_t(o.point) >= corners) {
            cannot("an observation of view " + std::to_string(o.view) + ", point " + std::to_string(o.point) +
                   ", which the set does not hold");
        }
        double* xyw = observed.data() + 3 * (row_of_view[static_cast<std::size_t>(o.view)] * corners +
                                             static_cast<std::size_t>(o.point));
        xyw[0] = o.pixel.x(), xyw[1] = o.pixel.y(), xyw[2] = o.inlier ? o.weight : -1.0;
    }
    std::vector<double> indices, sizes;
    for (const std::size_t v : order) {
        const int camera = set.views[v].camera;
        indices.insert(indices.end(), {double(frame_of(v)), double(camera), double(camera - 1)});
    }
    for (const ObservedCamera& c : set.cameras) sizes.insert(sizes.end(), {double(c.camera.size.width), double(c.camera.size.height)});

    const bool warped = board.warp != Vec2::Zero() || board.warp_solved;
    const std::vector<std::pair<std::string, NpyArray>> arrays{
        {"intrinsics", numbers({cameras, intrinsics.size() / cameras}, intrinsics)},
        {"extrinsics_rt_fromref", numbers({cameras - 1, 6}, extrinsics)},
        {"frames_rt_toref", numbers({frames.size(), 6}, frames_rt)},
        {"points", none()},
        {"observations_board", numbers({order.size(), std::size_t(board.height), std::size_t(board.width), 3}, observed)},
        {"indices_frame_camintrinsics_camextrinsics", numbers({order.size(), 3}, indices, "<i4")},
        {"observations_point", none()},
        {"indices_point_camintrinsics_camextrinsics", none()},
        {"lensmodel", text(lensmodel)},
        {"imagersizes", numbers({cameras, 2}, sizes, "<i4")},
        {"calobject_warp", warped ? numbers({2}, {board.warp.x(), board.warp.y()}) : none()},
        {"do_optimize_intrinsics_core", flag(true)},
        {"do_optimize_intrinsics_distortions", flag(true)},
        {"do_optimize_extrinsics", flag(true)},
        {"do_optimize_frames", flag(true)},
        {"do_optimize_calobject_warp", flag(board.warp_solved)},
        {"calibration_object_spacing", numbers({}, {board.spacing})},
        {"do_apply_outlier_rejection", flag(false)},
        {"observed_pixel_uncertainty", numbers({}, {observed_pixel_uncertainty})},
        {"do_apply_regularization", flag(false)},
        {"verbose", flag(false)},
    };
    return "b'" + detail::base85_encode(detail::write_npz(arrays)) + "'";
}

}  // namespace libcam
