#!/usr/bin/env python3
"""Throughput of pdesurf.batch (docs/batch.md) with 1 and 2 LocalCluster workers on a
collection of CGAL's meshes, and the overheads per mesh: Dask's (the scheduler's, a task that
does nothing) and the fit process's start (a mesh that fails at once). Results:
docs/performance.md, "The Dask batch".

    PYTHONPATH=build/python python3 bench/batch_scaling.py [--json out/batch-scaling.json]
"""

import argparse
import json
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
# Meshes whose fits take a second of CPU or more with FIT (a few seconds on an idle core).
MESHES = ("elephant.off", "three_peaks.off", "lion-head.off", "dragknob.off", "part.off",
          "double-torus-3-holes.off", "pipe.off", "u.off")
FIT = {"frames": 100, "iterations": 20, "samples": 20000}
NO_OP_TASKS = 200


def no_op(i):
    return i


def scheduler_overhead(tasks):
    """Seconds per task of Dask alone: `tasks` tasks that do nothing, submitted and gathered as
    the batch does (client.submit, as_completed) on a LocalCluster of one worker."""
    import logging
    from distributed import Client, LocalCluster, as_completed
    with LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=":0",
                      silence_logs=logging.ERROR) as cluster, Client(cluster) as client:
        client.submit(no_op, -1).result()  # the worker is up
        start = time.monotonic()
        futures = [client.submit(no_op, i, pure=False) for i in range(tasks)]
        for _ in as_completed(futures):
            pass
        return (time.monotonic() - start) / tasks


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--json", help="also write the results here")
    parser.add_argument("--meshes", nargs="+", default=MESHES)
    args = parser.parse_args()
    from pdesurf import batch
    work = pathlib.Path(tempfile.mkdtemp(prefix="batch-scaling-"))
    try:
        collection = work / "meshes"
        collection.mkdir()
        for name in args.meshes:
            path = subprocess.run([str(ROOT / "scripts/cgal_data"), name], check=True,
                                  capture_output=True, text=True).stdout.strip()
            shutil.copy(path, collection / name)
        quiet = open(os.devnull, "w")
        runs = {}
        for workers in (1, 2):
            result = batch.run(collection, work / f"out-{workers}", FIT, workers=workers,
                               threads=1, progress=False, out=quiet)
            rows = result["rows"]
            assert all(r["status"] == "ok" for r in rows), [r["error"] for r in rows]
            runs[workers] = {
                "meshes": len(rows), "fitting_s": round(result["fitting_s"], 2),
                "meshes_per_minute": round(60 * len(rows) / result["fitting_s"], 2),
                "fit_cpu_s": [float(r["fit_cpu_s"]) for r in rows],
                "task_wall_s": [float(r["wall_s"]) for r in rows]}
            print(f"{workers} worker(s): {len(rows)} meshes in {result['fitting_s']:.1f} s, "
                  f"fits of {min(runs[workers]['fit_cpu_s']):.2f} to "
                  f"{max(runs[workers]['fit_cpu_s']):.2f} s CPU", flush=True)
        ratio = runs[1]["fitting_s"] / runs[2]["fitting_s"]
        # The fit process's start: meshes that fail at once (empty files).
        empty = work / "empty"
        empty.mkdir()
        for i in range(8):
            (empty / f"{i}.off").write_bytes(b"")
        failing = batch.run(empty, work / "out-empty", FIT, workers=1, progress=False,
                            out=quiet)
        child_s = sum(float(r["wall_s"]) for r in failing["rows"]) / len(failing["rows"])
        dask_s = scheduler_overhead(NO_OP_TASKS)
        results = {"load_average": os.getloadavg(), "cores": os.cpu_count(), "fit": FIT,
                   "runs": runs, "throughput_ratio_2_to_1": round(ratio, 3),
                   "dask_overhead_per_task_ms": round(1000 * dask_s, 2),
                   "fit_process_start_ms": round(1000 * child_s, 1)}
        print(f"2 workers / 1 worker throughput: {ratio:.2f}x")
        print(f"Dask's overhead per task: {1000 * dask_s:.1f} ms ({NO_OP_TASKS} no-op tasks)")
        print(f"the fit process's start per mesh: {1000 * child_s:.0f} ms")
        print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
        if args.json:
            pathlib.Path(args.json).write_text(json.dumps(results, indent=1) + "\n")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
