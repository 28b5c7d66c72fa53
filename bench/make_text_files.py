#!/usr/bin/env python3
"""Writes the camera files docs/speed.md times `libcam info`, `convert` and `reproject` on.

    python3 bench/make_text_files.py OUT_FOLDER

For reading text (each large, one kind of document):
  transforms.json     instant-ngp's layout, 20,000 frames of one calibration (12.7 MB)
  opencv.yaml         OpenCV's YAML calibration with a 1 x 150,000 matrix beside it (3.2 MB)
  opencv.xml          the same in OpenCV's XML (3.1 MB)
  metashape-long.xml  a Metashape document with one attribute of 40 MB
  colmap/             a COLMAP text model: 200 images of 3,000 points each, 60,000 points (22 MB)
For `info` (many cameras):
  metashape-94.xml       94 cameras, each with a calibration of its own (Metashape's f, b1,
                         b2, k1, k2, p1, p2), as a zoom lens shot at every focal length gives
  metashape-94-wild.xml  the same with wild coefficients (k1 up to 50, k2 up to 500, p1 and
                         p2 up to 5): lenses whose unprojection fails over much of the image
  transforms-67.json     67 frames sharing one calibration (instant-ngp's example's size)
Pseudo-random with a fixed seed: the same files every run.
"""
import json
import math
import os
import random
import sys


def rotation(rng):
    """A random rotation matrix (rows), from a random unit quaternion."""
    q = [rng.gauss(0, 1) for _ in range(4)]
    n = math.sqrt(sum(v * v for v in q))
    w, x, y, z = (v / n for v in q)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def transforms(rng, frames):
    out = {"fl_x": 1375.52, "fl_y": 1374.49, "k1": 0.0578421, "k2": -0.0805099, "p1": -0.000980296,
           "p2": 0.00015575, "cx": 554.558, "cy": 965.268, "w": 1080.0, "h": 1920.0, "frames": []}
    for i in range(frames):
        r = rotation(rng)
        matrix = [r[k] + [rng.uniform(-5, 5)] for k in range(3)] + [[0.0, 0.0, 0.0, 1.0]]
        out["frames"].append({"file_path": "images/%05d.jpg" % i, "transform_matrix": matrix})
    return json.dumps(out, indent=2)


def opencv_matrix_values(rng, count):
    return ["%.17g" % rng.uniform(-1, 1) for _ in range(count)]


def opencv_yaml(values):
    return ("%%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\n"
            "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
            "   data: [ 500., 0., 319.5, 0., 500., 239.5, 0., 0., 1. ]\n"
            "distortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 5\n   dt: d\n"
            "   data: [ -0.1, 0.01, 0., 0., 0. ]\n"
            "extra: !!opencv-matrix\n   rows: 1\n   cols: %d\n   dt: d\n   data: [ %s ]\n"
            % (len(values), ", ".join(values)))


def opencv_xml(values):
    def matrix(name, rows, cols, data):
        return ('<%s type_id="opencv-matrix">\n  <rows>%d</rows>\n  <cols>%d</cols>\n  <dt>d</dt>\n'
                '  <data>\n    %s</data></%s>\n' % (name, rows, cols, data, name))
    return ('<?xml version="1.0"?>\n<opencv_storage>\n<image_width>640</image_width>\n'
            '<image_height>480</image_height>\n' + matrix("camera_matrix", 3, 3, "500. 0. 319.5 0. 500. 239.5 0. 0. 1.") +
            matrix("distortion_coefficients", 1, 5, "-0.1 0.01 0. 0. 0.") +
            matrix("extra", 1, len(values), " ".join(values)) + "</opencv_storage>\n")


def metashape(rng, cameras, wild, note=""):
    """Metashape's cameras.xml: one sensor per camera, each with its adjusted calibration."""
    sensors, views = [], []
    for i in range(cameras):
        terms = {"f": rng.uniform(8000, 8500), "b1": rng.uniform(-1, 1), "b2": rng.uniform(-25, -20)}
        if wild:
            terms.update(k1=rng.uniform(-50, 50), k2=rng.uniform(-500, 500), p1=rng.uniform(-5, 5), p2=rng.uniform(-5, 5))
        else:
            terms.update(k1=rng.uniform(-0.07, -0.05), k2=rng.uniform(0.15, 0.2), p1=rng.uniform(-2e-3, 2e-3),
                         p2=rng.uniform(-2e-3, 2e-3))
        values = "".join("          <%s>%.15g</%s>\n" % (k, v, k) for k, v in terms.items())
        sensors.append('      <sensor id="%d" label="lens %d" type="frame">\n'
                       '        <resolution width="5184" height="3456"/>\n'
                       '        <calibration type="frame" class="adjusted">\n'
                       '          <resolution width="5184" height="3456"/>\n%s        </calibration>\n'
                       '      </sensor>\n' % (i, i, values))
        r = rotation(rng)
        t = [rng.uniform(-1, 1) for _ in range(3)]
        numbers = [v for k in range(3) for v in r[k] + [t[k]]] + [0, 0, 0, 1]
        views.append('      <camera id="%d" sensor_id="%d" label="%03d">\n        <transform>%s</transform>\n'
                     '      </camera>\n' % (i, i, i + 1, " ".join("%.17g" % v for v in numbers)))
    attribute = ' note="%s"' % note if note else ""
    return ('<?xml version="1.0" encoding="UTF-8"?>\n<document version="1.5.0"%s>\n  <chunk label="Chunk 1" enabled="true">\n'
            '    <sensors next_id="%d">\n%s    </sensors>\n    <cameras next_id="%d" next_group_id="0">\n%s'
            '    </cameras>\n  </chunk>\n</document>\n'
            % (attribute, cameras, "".join(sensors), cameras, "".join(views)))


def colmap_model(rng, folder, images=200, points=60000, per_image=3000):
    """A COLMAP text model: one SIMPLE_RADIAL camera, identity rotations, points in front."""
    os.makedirs(folder, exist_ok=True)
    width, height, f, k = 1600, 1200, 1200.0, 0.01
    xyz = [(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(4, 6)) for _ in range(points)]
    tracks = [[] for _ in range(points)]
    with open(os.path.join(folder, "cameras.txt"), "w") as out:
        out.write("1 SIMPLE_RADIAL %d %d %g %g %g %g\n" % (width, height, f, width / 2, height / 2, k))
    with open(os.path.join(folder, "images.txt"), "w") as out:
        for i in range(images):
            tx, ty = rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)
            out.write("%d 1 0 0 0 %.6f %.6f 0 1 img%04d.jpg\n" % (i + 1, tx, ty, i))
            seen = []
            for j, p in enumerate(rng.sample(range(points), per_image)):
                x, y, z = xyz[p]
                u, v = (x + tx) / z, (y + ty) / z
                radial = 1 + k * (u * u + v * v)
                seen.append("%.4f %.4f %d" % (f * u * radial + width / 2, f * v * radial + height / 2, p + 1))
                tracks[p].append("%d %d" % (i + 1, j))
            out.write(" ".join(seen) + "\n")
    with open(os.path.join(folder, "points3D.txt"), "w") as out:
        for p, (x, y, z) in enumerate(xyz):
            out.write("%d %.6f %.6f %.6f 128 128 128 0.5 %s\n" % (p + 1, x, y, z, " ".join(tracks[p])))


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    folder = sys.argv[1]
    os.makedirs(folder, exist_ok=True)
    rng = random.Random(48)

    def write(name, text):
        with open(os.path.join(folder, name), "w") as out:
            out.write(text)

    write("transforms.json", transforms(rng, 20000))
    values = opencv_matrix_values(rng, 150000)
    write("opencv.yaml", opencv_yaml(values))
    write("opencv.xml", opencv_xml(values))
    write("metashape-long.xml", metashape(rng, 94, False, "abcdefghij" * 4000000))
    colmap_model(rng, os.path.join(folder, "colmap"))
    write("metashape-94.xml", metashape(rng, 94, False))
    write("metashape-94-wild.xml", metashape(rng, 94, True))
    write("transforms-67.json", transforms(rng, 67))


if __name__ == "__main__":
    main()
