#!/usr/bin/env python3
"""The speed record: libcam's time over OpenCV's or mrcal's, now and as recorded.

Runs the `libcam bench` commands of docs/speed-record.json, each several times and in
turn, and prints for each ratio it records (libcam's time per point over a peer's, both
from the same run) the median of this run's values beside the recorded one, flagging any
more than the record's tolerance (25 %) worse. Exit status 1 when one is flagged.

    scripts/bench-check.py                 # compare with the record (about 3 minutes)
    scripts/bench-check.py --record        # and add this run to the record

Run it before and after a change to the batch engine (libcam/camera/), the lens models
(libcam/lens/) or the remap maps (libcam/remap/), on a build of scripts/build.sh, and
record a run when a change is meant to move the figures. It is not a test: times depend on
the machine and on what else runs on it. A ratio carries over between machines better
than a time, not perfectly; each recorded run says on what machine it ran and how busy the
machine was (load average), and this script prints both beside the run being compared.
"""

import argparse
import datetime
import json
import os
import platform
import shlex
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def cpu_model():
    try:
        with open("/proc/cpuinfo") as cpuinfo:
            for line in cpuinfo:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def load_average():
    return [round(value, 2) for value in os.getloadavg()]


def commit():
    def git(*args):
        return subprocess.run(["git", "-C", ROOT, *args], capture_output=True, text=True).stdout.strip()

    head = git("rev-parse", "--short", "HEAD")
    return head + ("+changes" if git("status", "--porcelain", "--untracked-files=no") else "")


def matches(row, selector):
    return all(row.get(key) == value for key, value in selector.items())


def the_row(rows, selector, command, name):
    found = [row for row in rows if matches(row, selector)]
    if len(found) != 1:
        sys.exit(f"bench-check: '{name}': {len(found)} rows of `{command}` match {json.dumps(selector)}, expected 1")
    return found[0]


def run_bench(program, arguments):
    command = [program, "bench", *arguments, "--json"]
    result = subprocess.run(command, cwd=ROOT, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"bench-check: `{' '.join(command)}` failed: {result.stderr.strip()}")
    return json.loads(result.stdout)


def measure(record, program, runs):
    """Each ratio's value in each run: {name: [value, ...]}, and the instruction set used."""
    values = {ratio["name"]: [] for ratio in record["ratios"]}
    simd = None
    for run in range(runs):
        for command, arguments in record["commands"].items():
            print(f"run {run + 1}/{runs}: libcam bench {arguments}", file=sys.stderr, flush=True)
            output = run_bench(program, shlex.split(arguments))
            simd = output["simd"]["in_use"]
            for ratio in (r for r in record["ratios"] if r["command"] == command):
                row = the_row(output["rows"], ratio["row"], command, ratio["name"])
                reference = the_row(output["rows"], ratio["reference"], command, ratio["name"])
                values[ratio["name"]].append(row["ns_per_point"] / reference["ns_per_point"])
    return values, simd


def machine_text(run):
    load = run["load_average"]
    return (f"{run['machine']['cpu']}, {run['machine']['cores']} cores, {run['machine']['simd']}; "
            f"load average {load['before'][0]} before, {load['after'][0]} after; {run['date']}, commit {run['commit']}")


def report(record, values, last, tolerance):
    """Prints the table; returns the names of the ratios more than `tolerance` worse."""
    recorded = last["ratios"] if last else {}
    worse = []
    width = max(len(name) for name in values)
    print(f"{'ratio (libcam / peer, same run)':<{width}}  {'now':>7}  {'range':>15}  {'recorded':>8}  change")
    for name, samples in values.items():
        now = statistics.median(samples)
        spread = f"{min(samples):.3g}-{max(samples):.3g}"
        before = recorded.get(name)
        if before is None:
            print(f"{name:<{width}}  {now:>7.3g}  {spread:>15}  {'-':>8}")
            continue
        change = now / before - 1
        flag = ""
        if change > tolerance:
            flag = f"  WORSE by more than {tolerance:.0%}"
            worse.append(name)
        print(f"{name:<{width}}  {now:>7.3g}  {spread:>15}  {before:>8.3g}  {change:+.0%}{flag}")
    return worse


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"), help="build folder (default: build)")
    parser.add_argument("--runs", type=int, default=3, help="runs of each command; the median ratio is compared (default 3)")
    parser.add_argument("--record", action="store_true", help="add this run to the record file")
    parser.add_argument("--file", default=os.path.join(ROOT, "docs", "speed-record.json"), help="the record file")
    args = parser.parse_args()
    if args.runs < 1:
        parser.error(f"--runs: at least 1, got {args.runs}")
    program = os.path.join(args.build, "tools", "libcam")
    if not os.path.exists(program):
        sys.exit(f"bench-check: no program {program}: build it first (scripts/build.sh)")
    with open(args.file) as file:
        record = json.load(file)

    before = load_average()
    values, simd = measure(record, program, args.runs)
    this_run = {
        "date": datetime.date.today().isoformat(),
        "commit": commit(),
        "machine": {"cpu": cpu_model(), "cores": os.cpu_count(), "simd": simd},
        "load_average": {"before": before, "after": load_average()},
        "runs": args.runs,
        "ratios": {name: round(statistics.median(samples), 4) for name, samples in values.items()},
    }
    last = record["recorded_runs"][-1] if record["recorded_runs"] else None
    print(f"this run:      {machine_text(this_run)}")
    if last:
        print(f"recorded run:  {machine_text(last)}")
        if last["machine"]["cpu"] != this_run["machine"]["cpu"] or last["machine"]["simd"] != simd:
            print("(another CPU or instruction set than the recorded run's: the ratios move with the machine)")
    if max(before[0], this_run["load_average"]["after"][0]) > this_run["machine"]["cores"]:
        print("(the machine was busy, more runnable threads than cores: the ratios are noisier than usual)")
    worse = report(record, values, last, record["tolerance"])
    if args.record:
        record["recorded_runs"].append(this_run)
        with open(args.file, "w") as file:
            json.dump(record, file, indent=2)
            file.write("\n")
        print(f"recorded in {os.path.relpath(args.file, ROOT)}")
        return 0
    return 1 if worse else 0


if __name__ == "__main__":
    sys.exit(main())
