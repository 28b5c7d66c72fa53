#!/usr/bin/python3
# mrcal's own view of a .cameramodel's optimization_inputs, for test_mrcal_observations.cpp:
# the expected values come from mrcal (python3-mrcal), never from libcam.
#
#   mrcal_optimization_inputs.py summary FILE   prints JSON: counts, the board's measurements
#                                               x (mrcal.optimizer_callback) and RMS values
#   mrcal_optimization_inputs.py write FILE [VARIANT]
#       writes a small .cameramodel through mrcal's API: a 3x2 board seen in 2 frames by an
#       OPENCV4 camera (one outlier, one half weight) and 3 discrete points. VARIANT spoils
#       one array: float32-intrinsics, mismatched-imagersizes, frame-out-of-range; or
#       no-observations leaves out the board's and the points' observations (None, as
#       mrcal stores an array it does not have); or
#       inflated-member: the npz archive's first member said (in its central directory) to
#       inflate to 50 MB from its 110 compressed bytes, as a zip bomb claims; or
#       many-views: the same camera over 558 views of a 10x10 board, a file of 1.07 MiB
#       (the size of a real calibration that libcam's former 1 MiB bound refused).

import base64
import json
import struct
import sys

import numpy as np
import mrcal

# _serialize_optimization_inputs: the module, not the class mrcal exports by the same name.
cameramodel_module = sys.modules["mrcal.cameramodel"]


def summary(path):
    inputs = mrcal.cameramodel(path).optimization_inputs()
    x = mrcal.optimizer_callback(**inputs, no_jacobian=True, no_factorization=True)[1]
    observed = inputs["observations_board"]
    weights = observed[..., 2].ravel()
    board = x[: weights.size * 2].reshape(-1, 2)
    inliers = weights > 0
    # Each point observation has 3 measurements: x, y and the penalty on its range.
    points = inputs.get("observations_point")
    point_count = 0 if points is None else points.shape[0]
    point_x = x[weights.size * 2: weights.size * 2 + 3 * point_count].reshape(-1, 3)[:, :2]
    unweighted = board[inliers] / weights[inliers, None]
    print(json.dumps({
        "views": int(observed.shape[0]),
        "height": int(observed.shape[1]),
        "width": int(observed.shape[2]),
        "corners": int(weights.size),
        "outliers": int((~inliers).sum()),
        "board_x": board.ravel().tolist(),
        "point_x": point_x.ravel().tolist(),
        # over the inliers' x and y, weighted: what mrcal.residuals_chessboard gives
        "rms_weighted_inliers": float(np.sqrt(np.mean(board[inliers] ** 2))),
        "rms_unweighted_inliers": float(np.sqrt(np.mean(unweighted ** 2))),
        # mrcal_optimize's rms_reproj_error__pixels: every measurement, outliers as 0,
        # regularization included
        "rms_reproj_error__pixels": float(np.sqrt(np.mean(x ** 2))),
    }))


def small_inputs():
    width, height, spacing = 3, 2, 0.1
    lensmodel = "LENSMODEL_OPENCV4"
    intrinsics = np.array([[800.0, 810.0, 320.0, 240.0, -0.1, 0.02, 0.001, -0.002]])
    frames = np.array([[0.1, -0.2, 0.05, -0.05, 0.02, 1.0], [-0.1, 0.15, 0.0, 0.0, -0.03, 1.2]])
    warp = np.array([0.002, -0.001])
    board = mrcal.ref_calibration_object(width, height, spacing, calobject_warp=warp)
    observed = []
    for frame in frames:
        q = mrcal.project(mrcal.transform_point_rt(frame, board), lensmodel, intrinsics[0])
        noise = 0.3 * np.sin(np.arange(q.size).reshape(q.shape))
        observed.append(np.concatenate([q + noise, np.ones(q.shape[:-1] + (1,))], axis=-1))
    observed = np.array(observed)
    observed[0, 1, 2, 2] = -1.0  # an outlier
    observed[1, 0, 0, 2] = 0.5   # a weighted corner
    points = np.array([[0.1, 0.2, 3.0], [-0.3, 0.1, 2.5], [0.2, -0.2, 4.0]])
    q_points = mrcal.project(points, lensmodel, intrinsics[0]) + np.array([0.25, -0.5])
    observations_point = np.concatenate([q_points, np.array([[1.0], [0.25], [1.0]])], axis=-1)
    return dict(
        intrinsics=intrinsics, extrinsics_rt_fromref=np.zeros((0, 6)), frames_rt_toref=frames, points=points,
        observations_board=observed,
        indices_frame_camintrinsics_camextrinsics=np.array([[0, 0, -1], [1, 0, -1]], dtype=np.int32),
        observations_point=observations_point,
        indices_point_camintrinsics_camextrinsics=np.array([[0, 0, -1], [1, 0, -1], [2, 0, -1]], dtype=np.int32),
        lensmodel=lensmodel, imagersizes=np.array([[640, 480]], dtype=np.int32), calobject_warp=warp,
        do_optimize_intrinsics_core=True, do_optimize_intrinsics_distortions=True, do_optimize_extrinsics=True,
        do_optimize_frames=True, do_optimize_calobject_warp=True, calibration_object_spacing=spacing,
        do_apply_outlier_rejection=False, do_apply_regularization=True, verbose=False,
        point_min_range=0.1, point_max_range=100.0)


def many_view_inputs():
    """The small solve's camera over 558 views of a 10x10 board, each a little apart."""
    inputs = small_inputs()
    width, height, spacing, views = 10, 10, 0.03, 558
    board = mrcal.ref_calibration_object(width, height, spacing)
    angle = np.arange(views) * 0.37
    frames = np.stack([0.2 * np.sin(angle), 0.2 * np.cos(1.3 * angle), 0.1 * np.sin(0.7 * angle),
                       -0.135 + 0.05 * np.cos(angle), -0.135 + 0.05 * np.sin(angle), 1.0 + 0.3 * np.sin(0.5 * angle)],
                      axis=-1)
    q = mrcal.project(mrcal.transform_point_rt(frames[:, None, None, :], board), inputs["lensmodel"],
                      inputs["intrinsics"][0])
    noise = 0.3 * np.sin(np.arange(q.size).reshape(q.shape))
    observed = np.concatenate([q + noise, np.ones(q.shape[:-1] + (1,))], axis=-1)
    indices = np.stack([np.arange(views), np.zeros(views), -np.ones(views)], axis=-1).astype(np.int32)
    inputs.update(frames_rt_toref=frames, observations_board=observed,
                  indices_frame_camintrinsics_camextrinsics=indices, calibration_object_spacing=spacing,
                  calobject_warp=np.zeros(2))
    return inputs


def write(path, variant):
    if variant == "many-views":
        mrcal.cameramodel(optimization_inputs=many_view_inputs(), icam_intrinsics=0).write(path)
        return
    inputs = small_inputs()
    mrcal.cameramodel(optimization_inputs=inputs, icam_intrinsics=0).write(path)
    if variant == "good":
        return
    if variant == "float32-intrinsics":
        inputs["intrinsics"] = inputs["intrinsics"].astype(np.float32)
    elif variant == "mismatched-imagersizes":
        inputs["imagersizes"] = np.array([[640, 480], [640, 480]], dtype=np.int32)
    elif variant == "frame-out-of-range":
        inputs["indices_frame_camintrinsics_camextrinsics"][1, 0] = 7
    elif variant == "no-observations":
        for key in ("observations_board", "indices_frame_camintrinsics_camextrinsics", "observations_point",
                    "indices_point_camintrinsics_camextrinsics"):
            inputs[key] = None
    elif variant != "inflated-member":
        raise SystemExit(f"unknown variant {variant}")
    # The model's text with its optimization_inputs swapped for the spoiled ones: mrcal's
    # own writer would refuse them.
    text = open(path).read()
    good = repr(cameramodel_module._serialize_optimization_inputs(small_inputs()))
    spoiled = repr(cameramodel_module._serialize_optimization_inputs(inputs))
    if variant == "inflated-member":
        archive = bytearray(base64.b85decode(cameramodel_module._serialize_optimization_inputs(inputs)))
        # The first member's uncompressed size, in its central directory entry and in its
        # local header (and that header's zip64 field, where numpy wrote one) alike.
        struct.pack_into("<I", archive, archive.find(b"PK\x01\x02") + 24, 50 * 2**20)
        local = archive.find(b"PK\x03\x04")
        struct.pack_into("<I", archive, local + 22, 50 * 2**20)
        name_length, extra_length = struct.unpack_from("<HH", archive, local + 26)
        extra = local + 30 + name_length
        if extra_length >= 12 and struct.unpack_from("<H", archive, extra)[0] == 1:
            struct.pack_into("<Q", archive, extra + 4, 50 * 2**20)
        spoiled = repr(base64.b85encode(bytes(archive)))
    assert good in text
    open(path, "w").write(text.replace(good, spoiled))


if __name__ == "__main__":
    if sys.argv[1] == "summary":
        summary(sys.argv[2])
    else:
        write(sys.argv[2], sys.argv[3] if len(sys.argv) > 3 else "good")
