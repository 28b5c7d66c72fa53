"""`libcam dataset` from Python: a COLMAP model or a transforms.json into pinhole cameras,
in this process (run) or spread over many (plan, then each task's run() anywhere).

    import libcam.dataset
    summary = libcam.dataset.run("scene/sparse/0", "out")          # the CLI's job, in-process

    plan = libcam.dataset.plan("scene/sparse/0", "out", masks=True)  # the model and stamp written
    for task in plan.tasks:                                          # one per image still to do
        task.run()                                                   # here, or in another process

A task is picklable (its state is one line of JSON), so Dask sends it to its workers:

    from dask.distributed import Client
    client = Client("tcp://scheduler:8786")
    client.gather(client.map(libcam.dataset.run_task, plan.tasks))

Each process keeps the maps of the cameras it used last (map_cache), so a worker builds a
camera's map once for all of its images. The tasks name absolute paths: every worker must
see the source images and the output folder at the same paths (a shared filesystem). A
stopped job is resumed by planning again with the same options: the images already
written are not in the new plan's tasks.
"""

from __future__ import annotations

from typing import Any, Optional, Sequence

from ._libcam import DatasetPlan, ImageTask, dataset_map_cache, dataset_plan, dataset_run

__all__ = ["DatasetPlan", "ImageTask", "map_cache", "plan", "run", "run_task"]


def plan(
    src: str,
    output: str,
    images: Optional[str] = None,
    camera: str = "valid",
    size: Optional[Sequence[int]] = None,
    to: str = "colmap",
    masks: bool = False,
    interpolation: str = "cubic",
    jpeg_quality: int = 95,
    text: bool = False,
    threads: int = 0,
) -> DatasetPlan:
    """Everything `libcam dataset SRC -o OUTPUT` does but the images: the new cameras chosen,
    the observations moved, the model written (OUTPUT/sparse/0, or OUTPUT/transforms.json
    with to="nerf") and the stamp OUTPUT/.libcam-dataset; returns the tasks of the images
    still to write (those of an earlier run with the same options are kept and not listed).

    src: a COLMAP model folder or a transforms.json. images: the source images (default:
    X/images for X/sparse/0; a transforms.json's own folder or its images/). camera:
    "valid", "all", "fov:DEG" or "views"; size: (width, height) of every new camera (not
    with "views"). to: "colmap" or "nerf". masks: also write OUTPUT/masks/<name>.png.
    interpolation: "nearest", "linear", "cubic" or "lanczos". jpeg_quality: 1 to 100.
    text: the COLMAP model as text. threads: for choosing the cameras (0: one per core).
    Releases the GIL. Raises libcam.FileError or libcam.Error naming the file or field.
    """
    return dataset_plan(src, output, images, camera, size, to, masks, interpolation, jpeg_quality, text, threads)


def run(
    src: str,
    output: str,
    images: Optional[str] = None,
    camera: str = "valid",
    size: Optional[Sequence[int]] = None,
    to: str = "colmap",
    masks: bool = False,
    interpolation: str = "cubic",
    jpeg_quality: int = 95,
    text: bool = False,
    threads: int = 0,
) -> dict[str, Any]:
    """The whole job in this process, as `libcam dataset` runs it: plan(...) and every task
    on `threads` workers (0: one per core). Returns the summary (the dict `libcam dataset
    --json` prints, without time_s) with "errors": one line for each image that could not
    be read or written (the others are written). Releases the GIL."""
    return dataset_run(src, output, images, camera, size, to, masks, interpolation, jpeg_quality, text, threads)


def run_task(task: ImageTask) -> str:
    """task.run(), returning the path written: a module-level function for client.map."""
    task.run()
    return task.target_path


def map_cache(capacity: Optional[int] = None, threads: Optional[int] = None) -> dict[str, int]:
    """This process's cache of maps, which every task.run() uses: {"capacity", "threads",
    "maps", "builds"} (maps held now, maps built so far). Given capacity (maps kept, default
    4: each is 6 bytes per output pixel) or threads (threads each map is built with, default
    1; 0: one per core), starts a new, empty cache with those."""
    return dataset_map_cache(capacity, threads)
