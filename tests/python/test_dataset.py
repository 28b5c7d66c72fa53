"""libcam.dataset: `libcam dataset` planned in Python, its image tasks pickled and run in
this process or on a Dask cluster of worker processes, compared file by file (the same
bytes) with the program's own run of the same options."""

import importlib.util
import os
import pathlib
import pickle
import subprocess
import sys

import cv2
import numpy as np
import pytest

import libcam
from conftest import SOURCE_DIR

EXAMPLE = SOURCE_DIR / "examples" / "python" / "dataset_dask.py"

# A wide fisheye (144 degrees off the axis at its corners: split into views), an OPENCV lens
# and a pinhole (kept: its image copied), five small images, two in a subfolder.
CAMERAS = """1 OPENCV_FISHEYE 80 60 20 20 39.5 29.5 0.01 0 0 0
2 OPENCV 64 48 60 58 32.5 24.2 -0.2 0.04 0 0
3 PINHOLE 40 30 35 35 20 15
"""
IMAGES = """1 1 0 0 0 0 0 0 1 f1.png

2 1 0 0 0 1 0 0 1 sub/f2.jpg

3 1 0 0 0 0 0 1 2 o1.png

4 0 1 0 0 0 1 0 2 sub/o2.jpg

5 0 0 1 0 0 0 2 3 p1.png

"""
OPTIONS = {"camera": "views", "masks": True}


@pytest.fixture
def scene(tmp_path):
    model = tmp_path / "model"
    model.mkdir()
    (model / "cameras.txt").write_text(CAMERAS)
    (model / "images.txt").write_text(IMAGES)
    (model / "points3D.txt").write_text("")
    rng = np.random.default_rng(7)
    (tmp_path / "images" / "sub").mkdir(parents=True)
    for name, (width, height) in {"f1.png": (80, 60), "sub/f2.jpg": (80, 60), "o1.png": (64, 48),
                                  "sub/o2.jpg": (64, 48)}.items():
        assert cv2.imwrite(str(tmp_path / "images" / name), (rng.random((height, width, 3)) * 255).astype(np.uint8))
    assert cv2.imwrite(str(tmp_path / "images" / "p1.png"), (rng.random((30, 40)) * 65535).astype(np.uint16))
    return tmp_path


def cli_dataset(scene, output):
    """The program's own run: `libcam dataset` with OPTIONS."""
    program = os.environ.get("LIBCAM_EXE")
    if not program:
        pytest.fail("LIBCAM_EXE is not set: run these tests through ctest")
    subprocess.run([program, "dataset", str(scene / "model"), "--images", str(scene / "images"), "-o", str(output),
                    "--camera", "views", "--masks"], check=True, capture_output=True)


def files_under(folder):
    return {path.relative_to(folder).as_posix(): path.read_bytes()
            for path in sorted(pathlib.Path(folder).rglob("*")) if path.is_file()}


def assert_same_files(expected_folder, folder):
    expected = files_under(expected_folder)
    written = files_under(folder)
    assert sorted(written) == sorted(expected)
    different = [name for name in expected if written[name] != expected[name]]
    assert not different, f"not the same bytes: {different}"


def test_plan_tasks_pickled_and_run_here_give_the_programs_files_and_a_new_plan_resumes(scene):
    cli_dataset(scene, scene / "cli")
    libcam.dataset.map_cache(capacity=4)  # a new, empty cache for this process
    plan = libcam.dataset.plan(str(scene / "model"), str(scene / "tasks"), images=str(scene / "images"), **OPTIONS)
    assert plan.summary["images_kept"] == 0 and plan.summary["images_written"] == 0
    assert len(plan.tasks) == plan.summary["model_images_out"] > 5  # the fisheye's images in views
    assert sum(task.copy for task in plan.tasks) == 1  # the pinhole's image
    assert any(not np.array_equal(task.turn, np.eye(3)) for task in plan.tasks)
    assert all(task.mask_path.endswith(".png") and os.path.isabs(task.target_path) for task in plan.tasks)
    staging = scene / "tasks" / ".libcam-dataset-partial"
    assert all(pathlib.Path(task.target_path).is_relative_to(staging) for task in plan.tasks)
    # While the plan holds its output folder, another process's run does not write there.
    with pytest.raises(subprocess.CalledProcessError) as refused:
        cli_dataset(scene, scene / "tasks")
    assert b"another libcam dataset run is writing this folder" in refused.value.stderr
    assert sorted(os.listdir(scene / "tasks")) == [".libcam-dataset-partial"]
    for task in plan.tasks[:-1]:
        back = pickle.loads(pickle.dumps(task))
        assert back.to_json() == task.to_json()
        back.run()
    # Not every image there: finish moves nothing, and the output holds nothing but the staging folder.
    with pytest.raises(libcam.FileError, match="2 of the run's .* image files are not written yet"):
        libcam.dataset.finish(plan)
    assert sorted(os.listdir(scene / "tasks")) == [".libcam-dataset-partial"]
    plan.tasks[-1].run()
    summary = libcam.dataset.finish(plan)
    assert summary["finished"] and summary["images_written"] == len(plan.tasks)
    assert_same_files(scene / "cli", scene / "tasks")
    # The maps of this process: one per camera that is not copied, each built once.
    assert libcam.dataset.map_cache()["builds"] <= len(plan.summary["cameras"]) - 1

    # One image lost from the output: the new plan has that image alone.
    lost = plan.tasks[2]
    os.remove(scene / "tasks" / pathlib.Path(lost.target_path).relative_to(staging))
    again = libcam.dataset.plan(str(scene / "model"), str(scene / "tasks"), images=str(scene / "images"), **OPTIONS)
    assert [task.target_path for task in again.tasks] == [lost.target_path]
    assert again.summary["images_kept"] == len(plan.tasks) - 1
    again.tasks[0].run()
    libcam.dataset.finish(again)
    assert_same_files(scene / "cli", scene / "tasks")
    with pytest.raises(libcam.FileError, match="no unfinished dataset here"):
        libcam.dataset.finish(again)

    summary = libcam.dataset.run(str(scene / "model"), str(scene / "whole"), images=str(scene / "images"), **OPTIONS)
    assert summary["images_written"] == len(plan.tasks) and summary["errors"] == [] and summary["finished"]
    assert_same_files(scene / "cli", scene / "whole")


def test_a_run_with_an_unreadable_image_leaves_the_output_as_it_was_and_finishes_when_mended(scene):
    cli_dataset(scene, scene / "out")
    before = files_under(scene / "out")
    good = (scene / "images" / "o1.png").read_bytes()
    (scene / "images" / "o1.png").write_bytes(b"not a picture")
    summary = libcam.dataset.run(str(scene / "model"), str(scene / "out"), images=str(scene / "images"),
                                 interpolation="linear", **OPTIONS)
    assert not summary["finished"] and summary["images_failed"] == 1
    assert len(summary["errors"]) == 1 and "o1.png: not an image OpenCV can read" in summary["errors"][0]
    staged = scene / "out" / ".libcam-dataset-partial"
    after = files_under(scene / "out")
    assert {name: data for name, data in after.items() if not name.startswith(staged.name + "/")} == before
    assert any(name.startswith(staged.name + "/images/") for name in after)
    (scene / "images" / "o1.png").write_bytes(good)
    again = libcam.dataset.run(str(scene / "model"), str(scene / "out"), images=str(scene / "images"),
                               interpolation="linear", **OPTIONS)
    assert again["finished"] and again["images_written"] == 1
    assert again["images_kept"] == summary["model_images_out"] - 1
    assert not staged.exists()



def test_a_task_that_cannot_run_names_its_image(scene):
    plan = libcam.dataset.plan(str(scene / "model"), str(scene / "out"), images=str(scene / "images"))
    os.remove(plan.tasks[0].source_path)
    with pytest.raises(libcam.FileError, match="no such image file"):
        plan.tasks[0].run()
    crafted = plan.tasks[1].to_json().replace(".libcam-dataset-partial/images/", "")
    with pytest.raises(libcam.FileError, match="target_path: not in a staging folder a plan made"):
        libcam.dataset.ImageTask.from_json(crafted).run()
    with pytest.raises(libcam.FileError, match="no such image file .*nothing was written"):
        libcam.dataset.plan(str(scene / "model"), str(scene / "other"), images=str(scene / "images"))
    assert not (scene / "other").exists()
    with pytest.raises(libcam.FileError, match="jpeg_quality"):
        libcam.dataset.ImageTask.from_json(plan.tasks[1].to_json().replace('"jpeg_quality": 95', '"jpeg_quality": 0'))
    with pytest.raises(libcam.Error, match="camera: expected valid"):
        libcam.dataset.plan(str(scene / "model"), str(scene / "out"), camera="wide")


def test_a_dask_cluster_of_two_worker_processes_writes_the_programs_files(scene):
    """examples/python/dataset_dask.py: LocalCluster(n_workers=2, threads_per_worker=1,
    processes=True), client.map over the plan's tasks."""
    if importlib.util.find_spec("distributed") is None:
        pytest.skip("skipped: Dask is absent (apt-get install python3-distributed)")
    cli_dataset(scene, scene / "cli")
    # No deadline of its own: a cluster starts slowly on a busy machine, and ctest's
    # timeout ends a run that hangs.
    result = subprocess.run([sys.executable, str(EXAMPLE), str(scene / "model"), "--images", str(scene / "images"),
                             "-o", str(scene / "dask"), "--camera", "views", "--masks", "--workers", "2"],
                            capture_output=True, text=True, env=os.environ)
    assert result.returncode == 0, result.stdout + result.stderr
    assert_same_files(scene / "cli", scene / "dask")
    workers = [line for line in result.stdout.splitlines() if line.startswith("worker ")]
    assert len(workers) == 2, result.stdout
    cameras = len(libcam.dataset.plan(str(scene / "model"), str(scene / "dask"), images=str(scene / "images"),
                                      **OPTIONS).summary["cameras"])
    for line in workers:  # "worker tcp://...: N images, M maps built": each camera's map once at most
        built = int(line.split(", ")[1].split()[0])
        assert built <= cameras - 1, line
    assert ", 0 failed" in result.stdout
