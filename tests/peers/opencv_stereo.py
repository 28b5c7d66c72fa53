"""OpenCV's stereo calibration as its stereo_calib sample makes and writes it, shared by the
rectify test (rectify_vs_peers.py), bench/rectify_vs_cv2.py and
docs/images/make-rectify-picture.py."""

import os


def calibrate_sample_pairs(cv2, np, folder):
    """OpenCV's sample pairs (leftNN.jpg, rightNN.jpg, a 9x6 chessboard) calibrated as
    stereo_calib does: each camera by cv2.calibrateCamera, then cv2.stereoCalibrate.
    Returns (K1, D1, K2, D2, R, T, size, rms, corners): corners = (objects, left, right)."""
    pattern = (9, 6)
    board = np.zeros((pattern[0] * pattern[1], 3), np.float32)
    board[:, :2] = np.mgrid[0:pattern[0], 0:pattern[1]].T.reshape(-1, 2)
    criteria = (cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 30, 0.01)
    objects, left, right = [], [], []
    size = None
    for i in range(1, 15):
        names = [os.path.join(folder, f"{side}{i:02d}.jpg") for side in ("left", "right")]
        if not all(os.path.isfile(n) for n in names):
            continue
        found = []
        for name in names:
            gray = cv2.imread(name, cv2.IMREAD_GRAYSCALE)
            size = gray.shape[::-1]
            ok, corners = cv2.findChessboardCorners(gray, pattern)
            found.append(cv2.cornerSubPix(gray, corners, (11, 11), (-1, -1), criteria) if ok else None)
        if found[0] is not None and found[1] is not None:
            objects.append(board)
            left.append(found[0])
            right.append(found[1])
    _, K1, D1, _, _ = cv2.calibrateCamera(objects, left, size, None, None)
    _, K2, D2, _, _ = cv2.calibrateCamera(objects, right, size, None, None)
    rms, K1, D1, K2, D2, R, T, _, _ = cv2.stereoCalibrate(objects, left, right, K1, D1, K2, D2, size,
                                                          flags=cv2.CALIB_FIX_INTRINSIC)
    return K1, D1, K2, D2, R, T, size, rms, (objects, left, right)


def write_stereo_files(cv2, folder, name, K1, D1, K2, D2, R, T, size=None):
    """stereo_calib's two files, NAME-intrinsics.yml (M1 D1 M2 D2, and the image size when
    given) and NAME-extrinsics.yml (R T), in `folder`; returns their paths."""
    intrinsics = os.path.join(folder, f"{name}-intrinsics.yml")
    extrinsics = os.path.join(folder, f"{name}-extrinsics.yml")
    fs = cv2.FileStorage(intrinsics, cv2.FILE_STORAGE_WRITE)
    if size is not None:
        fs.write("image_width", size[0])
        fs.write("image_height", size[1])
    for key, value in (("M1", K1), ("D1", D1), ("M2", K2), ("D2", D2)):
        fs.write(key, value)
    fs.release()
    fs = cv2.FileStorage(extrinsics, cv2.FILE_STORAGE_WRITE)
    fs.write("R", R)
    fs.write("T", T)
    fs.release()
    return intrinsics, extrinsics
