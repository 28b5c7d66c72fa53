#!/usr/bin/env python3
"""`libcam dataset` with its images spread over a Dask cluster.

    python3 dataset_dask.py SRC -o OUT [--images DIR] [--camera valid|all|fov:DEG|views]
                            [--masks] [--to colmap|nerf] [--scheduler tcp://HOST:8786 | --workers N]

1. plans here: the new cameras chosen, the model and the stamp written to OUT's staging
   folder (OUT/.libcam-dataset-partial), one task per image still to write (a run stopped
   earlier leaves fewer);
2. sends the tasks to the cluster's workers (a task is picklable: one line of JSON), each
   worker reading its image, remapping it through its camera's map (built once per worker
   and camera) and writing it into the staging folder;
3. prints how many images each worker wrote and how many maps it built;
4. when every image is there, finishes here: the images, masks and model moved into OUT.

With --scheduler, the cluster is the one running there (`dask-scheduler` on one machine,
`dask-worker tcp://HOST:8786` on each of the others); every worker must see SRC's images
and OUT at the same paths (a shared filesystem). Without it, a cluster of --workers
processes on this machine. Exits with 1 when an image fails: OUT is left as it was, the
other images are kept in its staging folder, and running again makes the rest and finishes.
"""

import argparse
import collections
import sys

from dask.distributed import Client, LocalCluster, as_completed, get_worker

import libcam.dataset


def run_task(task):
    """One image, on a worker: returns the worker's address and the path written."""
    task.run()
    return get_worker().address, task.target_path


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("src", help="a COLMAP model folder or a transforms.json")
    parser.add_argument("-o", "--output", required=True)
    parser.add_argument("--images", help="the source images (default: beside the model, as libcam dataset finds them)")
    parser.add_argument("--camera", default="valid")
    parser.add_argument("--masks", action="store_true")
    parser.add_argument("--to", default="colmap")
    parser.add_argument("--interpolation", default="cubic")
    parser.add_argument("--jpeg-quality", type=int, default=95)
    parser.add_argument("--scheduler", help="a running cluster's scheduler, tcp://HOST:8786")
    parser.add_argument("--workers", type=int, default=2, help="without --scheduler: worker processes on this machine")
    args = parser.parse_args()

    plan = libcam.dataset.plan(args.src, args.output, images=args.images, camera=args.camera, to=args.to,
                               masks=args.masks, interpolation=args.interpolation, jpeg_quality=args.jpeg_quality)
    print(f"model: {plan.summary['model']}")
    print(f"images: {len(plan.tasks)} to write, {plan.summary['images_kept']} already there")
    if plan.tasks:
        failed = run_on_cluster(args, plan.tasks)
        if failed:
            print(f"error: {failed} images failed: {args.output} is as it was; the other images are kept in its "
                  "staging folder, and running this again makes the rest and finishes", file=sys.stderr)
            return 1
    summary = libcam.dataset.finish(plan)
    print(f"finished: {summary['images_out']} images in {args.output}")
    return 0


def run_on_cluster(args, tasks):
    """Every task on the cluster's workers; returns how many failed."""
    if args.scheduler:
        cluster = None
        client = Client(args.scheduler)
    else:
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
    try:
        written = collections.Counter()
        failed = 0
        for future in as_completed(client.map(run_task, tasks, pure=False)):
            try:
                worker, _ = future.result()
                written[worker] += 1
            except libcam.Error as error:  # the image is named; the others go on
                print(f"error: {error}", file=sys.stderr)
                failed += 1
        maps = client.run(libcam.dataset.map_cache)
        for worker in sorted(maps):
            print(f"worker {worker}: {written[worker]} images, {maps[worker]['builds']} maps built")
        print(f"images: {sum(written.values())} written, {failed} failed")
        return failed
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


if __name__ == "__main__":
    sys.exit(main())
