#!/usr/bin/python3
# mrcal's own projection uncertainty, for test_uncertainty.cpp: the expected values come
# from mrcal (python3-mrcal), never from libcam.
#
#   mrcal_uncertainty.py sigma MODEL DISTANCE X,Y [X,Y ...]
#       prints JSON: {"sigma_px": [...]}, mrcal.projection_uncertainty(what =
#       'worstdirection-stdev') of the point at DISTANCE ("inf": at infinity) along each
#       pixel's ray, and "noise_px", the observation noise mrcal infers from the residuals
#   mrcal_uncertainty.py write MODEL
#       writes a small solve of mrcal's own: an OPENCV4 camera (640x480) seeing a 10x8 board
#       in 14 poses (mrcal.synthesize_board_observations), 0.3 px of noise on the corners,
#       solved by mrcal.optimize from a start off the truth. The board is held flat and
#       there is no regularization or outlier rejection, so the problem is libcam's.
#   mrcal_uncertainty.py write-bowed MODEL
#       the same with a bowed board (calobject_warp 2 mm and -1.5 mm), whose bow mrcal
#       solves for beside the rest (do_optimize_calobject_warp).
#   mrcal_uncertainty.py write-rig MODEL0 MODEL1
#       a solve of two OPENCV4 cameras 12 cm apart seeing a 10x8 board in 12 poses together
#       (each board pose shared, camera 1's pose from camera 0 solved), written as mrcal
#       writes each camera's model: the whole solve in both, icam_intrinsics 0 and 1.

import json
import sys

import numpy as np
import mrcal


def sigma(path, distance, pixels):
    model = mrcal.cameramodel(path)
    q = np.array([[float(v) for v in p.split(",")] for p in pixels])
    at_infinity = distance == "inf"
    v = mrcal.unproject(q, *model.intrinsics(), normalize=True)
    p = v if at_infinity else v * float(distance)
    s = mrcal.projection_uncertainty(p, model, atinfinity=at_infinity, what="worstdirection-stdev")
    inputs = model.optimization_inputs()
    x = mrcal.optimizer_callback(**inputs, no_jacobian=True, no_factorization=True)[1]
    noise = np.std(mrcal.residuals_chessboard(inputs, residuals=x).ravel())
    print(json.dumps({"sigma_px": np.atleast_1d(s).tolist(), "noise_px": float(noise)}))


def write(path, bowed=False):
    rng = np.random.default_rng(5)
    lensmodel = "LENSMODEL_OPENCV4"
    truth = np.array([600.0, 605.0, 319.5, 239.5, -0.25, 0.08, 0.001, -0.0005])
    width, height = 640, 480
    model = mrcal.cameramodel(intrinsics=(lensmodel, truth), imagersize=(width, height))
    columns, rows, spacing = 10, 8, 0.03
    np.random.seed(5)  # synthesize_board_observations draws from numpy's global generator
    q, Rt_ref_board = mrcal.synthesize_board_observations(
        [model], object_width_n=columns, object_height_n=rows, object_spacing=spacing,
        calobject_warp=np.array([0.002, -0.0015]) if bowed else None,
        rt_ref_boardcenter=np.array([0.0, 0.0, 0.0, 0.0, 0.0, 0.45]),
        rt_ref_boardcenter__noiseradius=np.array([np.pi / 180.0 * 35.0] * 3 + [0.12, 0.08, 0.1]),
        Nframes=14)
    q = q[:, 0] + rng.normal(scale=0.3, size=q[:, 0].shape)
    observations = np.concatenate([q, np.ones(q.shape[:-1] + (1,))], axis=-1)
    frames = mrcal.rt_from_Rt(Rt_ref_board)
    start = truth * np.array([1.02, 0.98, 1.0, 1.0, 0.5, 0.5, 0.0, 0.0]) + np.array([0, 0, 3.0, -2.0, 0, 0, 0, 0])
    inputs = dict(
        intrinsics=start[None, :].copy(), extrinsics_rt_fromref=np.zeros((0, 6)),
        frames_rt_toref=frames + rng.normal(scale=0.01, size=frames.shape), points=None,
        observations_board=observations,
        indices_frame_camintrinsics_camextrinsics=np.array([[i, 0, -1] for i in range(len(frames))], dtype=np.int32),
        observations_point=None, indices_point_camintrinsics_camextrinsics=None, lensmodel=lensmodel,
        imagersizes=np.array([[width, height]], dtype=np.int32), calobject_warp=np.zeros(2) if bowed else None,
        do_optimize_intrinsics_core=True, do_optimize_intrinsics_distortions=True, do_optimize_extrinsics=True,
        do_optimize_frames=True, do_optimize_calobject_warp=bowed, calibration_object_spacing=spacing,
        do_apply_outlier_rejection=False, do_apply_regularization=False, verbose=False)
    mrcal.optimize(**inputs)
    mrcal.cameramodel(optimization_inputs=inputs, icam_intrinsics=0).write(path)


def write_rig(paths):
    rng = np.random.default_rng(5)
    lensmodel = "LENSMODEL_OPENCV4"
    truth = [np.array([600.0, 605.0, 319.5, 239.5, -0.25, 0.08, 0.001, -0.0005]),
             np.array([590.0, 592.0, 322.5, 241.5, -0.22, 0.07, -0.001, 0.0005])]
    width, height = 640, 480
    rt_cam1_ref = np.array([0.01, -0.05, 0.003, -0.12, 0.002, 0.001])
    models = [mrcal.cameramodel(intrinsics=(lensmodel, truth[0]), imagersize=(width, height)),
              mrcal.cameramodel(intrinsics=(lensmodel, truth[1]), imagersize=(width, height),
                                extrinsics_rt_fromref=rt_cam1_ref)]
    columns, rows, spacing = 10, 8, 0.03
    np.random.seed(5)  # synthesize_board_observations draws from numpy's global generator
    q, Rt_ref_board = mrcal.synthesize_board_observations(
        models, object_width_n=columns, object_height_n=rows, object_spacing=spacing, calobject_warp=None,
        rt_ref_boardcenter=np.array([0.0, 0.0, 0.0, -0.06, 0.0, 0.5]),
        rt_ref_boardcenter__noiseradius=np.array([np.pi / 180.0 * 30.0] * 3 + [0.1, 0.08, 0.1]), Nframes=12)
    frames_count = q.shape[0]
    q = q + rng.normal(scale=0.3, size=q.shape)
    observations = np.concatenate([q, np.ones(q.shape[:-1] + (1,))], axis=-1)
    observations = observations.reshape((frames_count * 2,) + observations.shape[2:])
    indices = np.array([[f, c, c - 1] for f in range(frames_count) for c in range(2)], dtype=np.int32)
    frames = mrcal.rt_from_Rt(Rt_ref_board)
    inputs = dict(
        intrinsics=np.array([t * np.array([1.02, 0.98, 1, 1, 0.5, 0.5, 0, 0]) for t in truth]),
        extrinsics_rt_fromref=(rt_cam1_ref + 0.01)[None, :],
        frames_rt_toref=frames + rng.normal(scale=0.01, size=frames.shape), points=None,
        observations_board=observations, indices_frame_camintrinsics_camextrinsics=indices,
        observations_point=None, indices_point_camintrinsics_camextrinsics=None, lensmodel=lensmodel,
        imagersizes=np.array([[width, height]] * 2, dtype=np.int32), calobject_warp=None,
        do_optimize_intrinsics_core=True, do_optimize_intrinsics_distortions=True, do_optimize_extrinsics=True,
        do_optimize_frames=True, do_optimize_calobject_warp=False, calibration_object_spacing=spacing,
        do_apply_outlier_rejection=False, do_apply_regularization=False, verbose=False)
    mrcal.optimize(**inputs)
    for camera, path in enumerate(paths):
        mrcal.cameramodel(optimization_inputs=inputs, icam_intrinsics=camera).write(path)


if __name__ == "__main__":
    if sys.argv[1] == "sigma":
        sigma(sys.argv[2], sys.argv[3], sys.argv[4:])
    elif sys.argv[1] == "write":
        write(sys.argv[2])
    elif sys.argv[1] == "write-bowed":
        write(sys.argv[2], bowed=True)
    elif sys.argv[1] == "write-rig":
        write_rig(sys.argv[2:4])
    else:
        sys.exit("usage: mrcal_uncertainty.py sigma MODEL DISTANCE X,Y ... | write MODEL | write-bowed MODEL | "
                 "write-rig MODEL0 MODEL1")
