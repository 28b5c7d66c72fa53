"""`libcam dataset` from Python: a COLMAP model or a transforms.json into pinhole cameras,
in this process (run) or spread over many (plan, then each task's run() anywhere).

    import libcam.dataset
    summary = libcam.dataset.run("scene/sparse/0", "out")          # the CLI's job, in-process

    plan = libcam.dataset.plan("scene/sparse/0", "out", masks=True)  # the model and stamp staged
    for task in plan.tasks:                                          # one per image still to do
        task.run()                                                   # here, or in another process
    libcam.dataset.finish(plan)                                      # everything moved into place

A task is picklable (its state is one line of JSON), so Dask sends it to its workers:

    from dask.distributed import Client
    client = Client("tcp://scheduler:8786")
    client.gather(client.map(libcam.dataset.run_task, plan.tasks))
    libcam.dataset.finish(plan)

Nothing is in place in the output folder until finish: the plan writes the model, the stamp
and (its tasks) the images into OUTPUT/.libcam-dataset-partial, and finish moves them into
OUTPUT once every image is there, so a job that fails or stops leaves OUTPUT as it was. A
task writes only into that folder (a task line that names another place is refused).

Each process keeps the maps of the cameras it used last (map_cache), so a worker builds a
camera's map once for all of its images. The tasks name absolute paths: every worker must
see the source images and the output folder at the same paths (a shared filesystem). A
stopped job is resumed by planning again with the same options: the images already
written are not in the new plan's tasks; then its tasks and finish.
"""

from __future__ import annotations

from typing import Any, Optional, Sequence

from ._libcam import DatasetPlan, ImageTask, dataset_finish, dataset_map_cache, dataset_plan, dataset_run

__all__ = ["DatasetPlan", "ImageTask", "finish", "map_cache", "plan", "run", "run_task"]


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
    """Everything `libcam dataset SRC -o OUTPUT` does but the images: every check (each image's
    name inside its folder, every source image there), the new cameras chosen, the
    observations moved, the model (sparse/0, or transforms.json with to="nerf") and the stamp
    written to OUTPUT/.libcam-dataset-partial; returns the tasks of the images still to
    write (those of an earlier run with the same options are kept and not listed). Nothing
    is in OUTPUT itself until finish(plan). The plan holds OUTPUT until finish(plan) or until
    it is deleted: meanwhile a run on OUTPUT in another process (`libcam dataset`, another
    Python) is refused. Plans made again in this process share the hold.

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
    """The whole job in this process, as `libcam dataset` runs it: plan(...), every task on
    `threads` workers (0: one per core) and finish. Returns the summary (the dict `libcam
    dataset --json` prints, without time_s) with "errors": one line for each image that
    could not be read or written. With any, "finished" is False: OUTPUT is as it was, the
    other images are kept in OUTPUT/.libcam-dataset-partial, and the same call again makes
    the rest and finishes. Releases the GIL."""
    return dataset_run(src, output, images, camera, size, to, masks, interpolation, jpeg_quality, text, threads)


def finish(plan: DatasetPlan) -> dict[str, Any]:
    """Once every task of `plan` has run (anywhere): moves the images, masks, model and stamp
    from OUTPUT/.libcam-dataset-partial into OUTPUT (the images first, the model last) and
    removes that folder. Returns the plan's summary with "finished" True and
    "images_written" the images its tasks made. Raises libcam.FileError, moving nothing,
    when an image is not there yet (naming the first and how many). Releases the GIL."""
    return dataset_finish(plan)


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
