"""Rebuilds a collection of meshes on Dask, resumably: `python3 -m pdesurf.batch INPUT -o
OUTPUT [options]`, or pdesurf.batch.run(INPUT, OUTPUT, ...) from Python (docs/batch.md).

INPUT is a folder (its .off .obj .ply .stl files, recursively) or a text file listing mesh
paths. Each mesh is rebuilt as pdesurf.rebuild does with the options given; its model goes to
OUTPUT/<relative path>.json and its row to OUTPUT/results.csv, after the model. A rerun skips
the meshes that have both. At the end OUTPUT/summary.md and OUTPUT/rms-storage.png sum up.
"""

import argparse
import csv
import hashlib
import io
import json
import math
import os
import pathlib
import signal
import subprocess
import sys
import threading
import time

from . import _batch_fit
from . import _check_rebuild_options

MESH_SUFFIXES = (".off", ".obj", ".ply", ".stl")
RESULTS = "results.csv"
COLUMNS = ("path", "status", "error", "method", "layout", "frames", "sections",
           "rms_model_to_mesh", "rms_mesh_to_model", "max_model_to_mesh", "max_mesh_to_model",
           "storage_bytes", "mesh_storage_bytes", "peer_storage_bytes", "peer_rms", "fit_cpu_s",
           "wall_s", "model", "model_sha256", "options", "worker")

# rebuild's keywords that the batch passes on (every `pdesurf rebuild` option but those that
# name one mesh's outputs: -o, --part, --name, --json, --quiet, --loft).
REBUILD_OPTIONS = ("kind", "grid", "layout", "tube", "iterations", "tolerance", "smoothness",
                   "fit_samples", "prevent_folds", "fold_weight", "normal_weight", "fit_shape",
                   "frames", "target_rms", "max_normal_deviation", "quads", "crease_angle",
                   "resolution", "samples", "axis", "count", "range", "near", "track", "modes",
                   "points", "a", "ends", "exact")


class UsageError(ValueError):
    """Options that cannot run (exit status 2)."""


class InputError(ValueError):
    """An INPUT or OUTPUT that cannot be used (exit status 1)."""


# ------------------------------------------------------------------------------------------
# The collection and the results file.

def collect(source, output=None):
    """The meshes of INPUT -> [(path, relative path)], sorted by relative path: a folder's
    mesh files (recursively, OUTPUT left out where it lies inside) relative to the folder, or
    a list file's paths (one a line; blank lines and lines starting with # skipped; relative
    ones from the list's folder) relative to the folder all of them share."""
    source = pathlib.Path(source)
    if source.is_dir():
        skip = pathlib.Path(output).resolve() if output is not None else None
        paths = [p for p in source.rglob("*") if p.suffix.lower() in MESH_SUFFIXES
                 and p.is_file() and (skip is None or skip not in p.resolve().parents)]
        meshes = [(str(p), p.relative_to(source).as_posix()) for p in paths]
    elif source.is_file():
        try:
            lines = source.read_text(encoding="utf-8").splitlines()
        except (OSError, UnicodeDecodeError) as e:
            raise InputError(f"{source}: cannot read the list of meshes: {e}") from None
        listed = [line.strip() for line in lines]
        listed = [os.path.normpath(source.parent / p) for p in listed if p and p[0] != "#"]
        if not listed:
            raise InputError(f"{source}: the list names no mesh")
        root = os.path.commonpath([os.path.dirname(os.path.abspath(p)) for p in listed])
        meshes = [(p, os.path.relpath(os.path.abspath(p), root).replace(os.sep, "/"))
                  for p in listed]
        seen = {}
        for path, rel in meshes:
            if rel in seen:
                raise InputError(f"{source}: lists {rel} twice ({seen[rel]} and {path})")
            seen[rel] = path
    else:
        raise InputError(f"{source}: no such folder or list file")
    if not meshes:
        raise InputError(f"{source}: no .off .obj .ply .stl file in it")
    return sorted(meshes, key=lambda m: m[1])


def read_rows(path):
    """The rows of results.csv by mesh path. A last line without its newline is a row whose
    write was cut short (the client was killed while appending): it is dropped (the caller
    rewrites the file without it, and that mesh is done again)."""
    try:
        text = pathlib.Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        return {}
    if text and not text.endswith("\n"):
        text = text[:text.rfind("\n") + 1]
    rows = {}
    for row in csv.DictReader(io.StringIO(text)):
        if row.get("path") and set(COLUMNS) <= set(row):
            rows[row["path"]] = row
    return rows


def row_line(row):
    """One row of results.csv as text, newline included."""
    out = io.StringIO()
    csv.DictWriter(out, COLUMNS, extrasaction="ignore", lineterminator="\n").writerow(row)
    return out.getvalue()


def write_rows(path, rows):
    """results.csv with these rows (the header first), written whole or not at all."""
    header = ",".join(COLUMNS) + "\n"
    _batch_fit.write_atomically(str(path), header + "".join(row_line(r) for r in rows))


def append_row(path, row):
    """Appends one row with a single write() to the file opened for appending, flushed to the
    disk: a row is there whole, or (the client killed in the write) as a last line without its
    newline, which read_rows drops."""
    fd = os.open(path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
    try:
        os.write(fd, row_line(row).encode("utf-8"))
        os.fsync(fd)
    finally:
        os.close(fd)


def options_key(options):
    """A short fingerprint of the rebuild options, stored in each row: a rerun with other
    options redoes the mesh."""
    text = json.dumps(options, sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:12]


def is_complete(row, output, key, retry_failed):
    """A row that a rerun keeps: made with the same options, and either failed (unless
    retry_failed) or ok with its model in OUTPUT, whole (its SHA-256 is the row's)."""
    if row.get("options") != key:
        return False
    if row["status"] != "ok":
        return not retry_failed
    try:
        text = (pathlib.Path(output) / row["model"]).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return False
    return _batch_fit.sha256(text) == row["model_sha256"]


# ------------------------------------------------------------------------------------------
# The task a Dask worker runs.

def fit_task(job):
    """Fits one mesh in a child process (pdesurf._batch_fit) and returns its row's values.
    Runs on a Dask worker. A child that crashes (a signal, an abort), exits without a result
    or runs past job["timeout"] seconds (then killed) makes a "failed" row with the reason;
    the worker itself goes on."""
    package = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (package, env.get("PYTHONPATH")) if p)
    start = time.monotonic()
    child = subprocess.Popen([sys.executable, "-m", "pdesurf._batch_fit", str(os.getpid())],
                             stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, env=env, start_new_session=True)
    try:
        out, err = child.communicate(json.dumps(job).encode(), timeout=job["timeout"])
    except subprocess.TimeoutExpired:
        child.kill()
        child.communicate()
        result = {"status": "failed",
                  "error": f"timeout: the fit ran past {job['timeout']:g} s and was killed"}
    except BaseException:
        child.kill()
        child.wait()
        raise
    else:
        last = (err.decode("utf-8", "replace").strip().splitlines() or [""])[-1][:300]
        if child.returncode < 0:
            try:
                name = signal.Signals(-child.returncode).name
            except ValueError:
                name = f"signal {-child.returncode}"
            result = {"status": "failed", "error": f"crashed: the fit process was killed by "
                      f"{name}" + (f" ({last})" if last else "")}
        elif child.returncode != 0 or not out.strip():
            result = {"status": "failed", "error": f"the fit process exited with status "
                      f"{child.returncode} and no result" + (f": {last}" if last else "")}
        else:
            result = json.loads(out)
    try:
        from distributed import get_worker
        result["worker"] = get_worker().address
    except (ImportError, ValueError):
        result["worker"] = f"pid {os.getpid()}"
    result["wall_s"] = round(time.monotonic() - start, 3)
    return result


# ------------------------------------------------------------------------------------------
# Progress and summary.

def _duration(seconds):
    seconds = int(round(seconds))
    if seconds >= 3600:
        return f"{seconds // 3600}h{seconds % 3600 // 60:02d}m"
    return f"{seconds // 60}m{seconds % 60:02d}s" if seconds >= 60 else f"{seconds}s"


class Progress:
    """Meshes done, failed and running, and the time left, on one line redrawn on a terminal
    (stderr); one line a mesh either way (stdout)."""

    def __init__(self, total, terminal, out=sys.stdout, err=sys.stderr):
        self.total, self.terminal, self.out, self.err = total, terminal, out, err
        self.done = self.failed = self.running = 0
        self.start = time.monotonic()
        self.lock = threading.Lock()

    def line(self):
        elapsed = time.monotonic() - self.start
        running = min(self.running, self.total - self.done)
        left = ""
        if self.done:
            left = f", about {_duration(elapsed / self.done * (self.total - self.done))} left"
        width = 24
        filled = width * self.done // max(self.total, 1)
        return (f"[{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total} done, "
                f"{self.failed} failed, {running} running, {_duration(elapsed)}{left}")

    def draw(self):
        if self.terminal:
            with self.lock:
                self.err.write("\r\033[K" + self.line())
                self.err.flush()

    def finished(self, row):
        with self.lock:
            self.done += 1
            self.failed += row["status"] != "ok"
            if self.terminal:
                self.err.write("\r\033[K")
                self.err.flush()
            if row["status"] == "ok":
                peer = (f", polygon peer {row['peer_storage_bytes']} bytes"
                        if row.get("peer_storage_bytes") not in (None, "") else "")
                text = (f"ok      {row['path']}: RMS {row['rms_model_to_mesh']:.3%} / "
                        f"{row['rms_mesh_to_model']:.3%}, {row['storage_bytes']} bytes{peer}, "
                        f"{row['wall_s']:.1f} s")
            else:
                text = f"failed  {row['path']}: {row['error']}"
            print(text, file=self.out, flush=True)
        self.draw()

    def close(self):
        if self.terminal:
            self.err.write("\r\033[K" + self.line() + "\n")
            self.err.flush()


def _number(value):
    try:
        return float(value)
    except (TypeError, ValueError):
        return None


def summarize(output, rows, write=True):
    """OUTPUT/summary.md (the totals, the failures, a table of the meshes) and
    OUTPUT/rms-storage.png (each model's RMS against its storage, with the polygon peer's
    where measured), unless not `write` -> the totals table's text."""
    ok = [r for r in rows if r["status"] == "ok"]
    failed = [r for r in rows if r["status"] != "ok"]

    def total(column, subset=ok):
        return sum(_number(r[column]) or 0 for r in subset)

    def median(column):
        values = sorted(v for v in (_number(r[column]) for r in ok) if v is not None)
        return values[len(values) // 2] if values else math.nan

    models, meshes = total("storage_bytes"), total("mesh_storage_bytes")
    peers = [r for r in ok if _number(r["peer_storage_bytes"]) is not None]
    table = ["| meshes | ok | failed | models' storage | meshes' storage | polygon peers' storage "
             "| median RMS model → mesh | median RMS mesh → model | fit CPU |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
             f"| {len(rows)} | {len(ok)} | {len(failed)} | {models / 1000:.1f} KB | "
             f"{meshes / 1000:.1f} KB | "
             + (f"{total('peer_storage_bytes', peers) / 1000:.1f} KB ({len(peers)}) | "
                if peers else "not measured | ")
             + f"{median('rms_model_to_mesh'):.3%} | {median('rms_mesh_to_model'):.3%} | "
             f"{total('fit_cpu_s', rows):.1f} s |"]
    if not write:
        return "\n".join(table)
    lines = ["# pdesurf.batch: summary", "", *table, ""]
    if failed:
        lines += ["## Failed", ""] + [f"- `{r['path']}`: {r['error']}" for r in failed] + [""]
    shown = rows[:1000]
    lines += ["## Meshes" + (" (the first 1000; results.csv has all)" if len(rows) > 1000
                             else ""), "",
              "| mesh | status | layout | frames / sections | RMS model → mesh | "
              "RMS mesh → model | storage | polygon peer | fit CPU |",
              "|---|---|---|---:|---:|---:|---:|---:|---:|"]
    for r in shown:
        if r["status"] != "ok":
            lines.append(f"| {r['path']} | failed | | | | | | | |")
            continue
        lines.append(f"| {r['path']} | ok | {r['layout']} | {r['frames'] or r['sections']} | "
                     f"{float(r['rms_model_to_mesh']):.3%} | {float(r['rms_mesh_to_model']):.3%} "
                     f"| {r['storage_bytes']} | {r['peer_storage_bytes'] or ''} | "
                     f"{float(r['fit_cpu_s']):.1f} s |")
    _batch_fit.write_atomically(str(pathlib.Path(output) / "summary.md"), "\n".join(lines) + "\n")
    plot(output, ok)
    return "\n".join(table)


def plot(output, ok):
    """OUTPUT/rms-storage.png: accuracy (sqrt((a² + b²) / 2) of the RMS both ways, % of the
    diagonal) against storage (KB), log-log, one point a mesh; the polygon peer at the same
    RMS beside it where measured, joined to its model."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    def accuracy(r):
        return 100 * math.sqrt(0.5 * (float(r["rms_model_to_mesh"]) ** 2
                                      + float(r["rms_mesh_to_model"]) ** 2))
    exact = [r for r in ok if accuracy(r) == 0.0]  # no place on a log scale
    ok = [r for r in ok if accuracy(r) > 0.0]
    figure, axes = plt.subplots(figsize=(7, 5))
    rms = [accuracy(r) for r in ok]
    axes.loglog([float(r["storage_bytes"]) / 1000 for r in ok], rms, "o", color="tab:blue",
                label="PDE models")
    axes.loglog([float(r["mesh_storage_bytes"]) / 1000 for r in ok], rms, "x",
                color="tab:gray", label="meshes (exact; drawn at the model's RMS)")
    peers = [(r, a) for r, a in zip(ok, rms)
             if _number(r["peer_storage_bytes"]) is not None and float(r["peer_rms"]) > 0]
    if peers:
        axes.loglog([float(r["peer_storage_bytes"]) / 1000 for r, _ in peers],
                    [100 * float(r["peer_rms"]) for r, _ in peers], "s", color="tab:orange",
                    label="polygon peers (GH simplified, same RMS)")
        for r, a in peers:
            axes.plot([float(r["storage_bytes"]) / 1000, float(r["peer_storage_bytes"]) / 1000],
                      [a, 100 * float(r["peer_rms"])], "-", color="tab:gray", lw=0.5)
    axes.set_xlabel("storage KB")
    axes.set_ylabel("RMS % of diagonal")
    axes.set_title(f"{len(ok)} meshes" + (f" ({len(exact)} fitted exactly, RMS 0, not drawn)"
                                          if exact else ""))
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=8)
    figure.tight_layout()
    temporary = pathlib.Path(output) / f".rms-storage.{os.getpid()}.png"
    figure.savefig(temporary, dpi=100)
    plt.close(figure)
    os.replace(temporary, pathlib.Path(output) / "rms-storage.png")


def write_parquet(output):
    """OUTPUT/results.parquet beside results.csv, where pyarrow is installed."""
    try:
        import pyarrow.csv
        import pyarrow.parquet
    except ImportError:
        return False
    table = pyarrow.csv.read_csv(str(pathlib.Path(output) / RESULTS))
    temporary = pathlib.Path(output) / f".results.{os.getpid()}.parquet"
    pyarrow.parquet.write_table(table, str(temporary))
    os.replace(temporary, pathlib.Path(output) / "results.parquet")
    return True


# ------------------------------------------------------------------------------------------
# The run.

def check_options(options, workers, threads, timeout):
    """The options of a run checked before any work -> rebuild's keywords. Raises UsageError
    naming the option."""
    unknown = set(options) - set(REBUILD_OPTIONS)
    if unknown:
        raise UsageError(f"unknown rebuild option(s): {', '.join(sorted(unknown))}")
    if workers is not None and workers < 1:
        raise UsageError(f"--workers: must be at least 1, got {workers}")
    if threads < 0:
        raise UsageError(f"--threads: must be 0 (every core) or more, got {threads}")
    if timeout is not None and not timeout > 0:
        raise UsageError(f"--timeout: must be more than 0 seconds, got {timeout}")
    kind = options.get("kind", "vertex-frames")
    if kind not in ("vertex-frames", "cross-sections"):
        raise UsageError(f"--as: '{kind}' is neither vertex-frames nor cross-sections")
    try:
        _check_rebuild_options(options)
    except ValueError as e:
        raise UsageError(str(e)) from None
    if options.get("layout") is not None:
        if not os.path.isfile(options["layout"]):
            raise InputError(f"--layout: {options['layout']}: no such file")
        options = dict(options, layout=os.path.abspath(options["layout"]))
    return options


def _start(scheduler, workers):
    """(client, cluster or None): a Client of the scheduler at `scheduler`, else of a
    LocalCluster of `workers` processes (default: one a core), one thread each."""
    import logging
    from distributed import Client, LocalCluster
    if scheduler:
        try:
            return Client(scheduler, timeout="20s"), None
        except OSError as e:
            raise InputError(f"--scheduler {scheduler}: cannot connect: {e}") from None
    cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                           processes=True, dashboard_address=":0",
                           silence_logs=logging.ERROR)
    return Client(cluster), cluster


def run(source, output, options=None, workers=None, threads=1, scheduler=None, gather=False,
        timeout=None, peer=False, retry_failed=False, progress=None, out=sys.stdout,
        err=sys.stderr):
    """Rebuilds every mesh of `source` (a folder or a list file) into `output`, as
    `python3 -m pdesurf.batch` does -> dict: "meshes", "todo" (the meshes fitted in this run),
    "ok", "failed" (over the whole collection), "rows" (results.csv's rows of the
    collection), "summary" (the totals table), "wall_s", "fitting_s" (from the first task
    submitted to the last row written).

    options: pdesurf.rebuild's keywords (kind, grid, frames, target_rms, iterations, ...).
    workers: LocalCluster processes (default: one a core); threads: each fit's threads
    (pdesurf.set_threads; 0: every core); scheduler: "tcp://HOST:PORT" of a running Dask
    scheduler instead (its workers must import pdesurf and, unless gather, write to
    `output`); gather: workers return the models and this process writes them; timeout:
    seconds a fit may run; peer: measure the polygon peer's storage at each model's RMS;
    retry_failed: fit again the meshes that failed before; progress: draw a progress line on
    `err` (default: when err is a terminal). Raises UsageError, InputError.
    """
    options = check_options(dict(options or {}), workers, threads, timeout)
    meshes = collect(source, output)
    output = pathlib.Path(output)
    try:
        output.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise InputError(f"{output}: cannot make the output folder: {e}") from None
    lock = _lock(output)
    try:
        return _run_locked(source, output, options, meshes, threads, scheduler, workers,
                           gather, timeout, peer, retry_failed, progress, out, err)
    finally:
        lock.close()


def _lock(output):
    """An exclusive lock on OUTPUT/.batch.lock, held for the run: one client writes OUTPUT at
    a time (the single writer of results.csv)."""
    import fcntl
    lock = open(output / ".batch.lock", "a")
    try:
        fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        lock.close()
        raise InputError(f"{output}: another pdesurf.batch is writing to it (it holds "
                         f"{output / '.batch.lock'})") from None
    return lock


def _run_locked(source, output, options, meshes, threads, scheduler, workers, gather, timeout,
                peer, retry_failed, progress, out, err):
    results = output / RESULTS
    key = options_key(options)
    rows = read_rows(results)
    names = {rel for _, rel in meshes}
    todo = [(path, rel) for path, rel in meshes
            if rel not in rows or not is_complete(rows[rel], output, key, retry_failed)]
    start = time.monotonic()
    redo = {rel for _, rel in todo}
    kept = [r for rel, r in rows.items() if rel not in redo]
    # Rows to redo (and a torn last line) leave the file: one row a mesh at any time.
    if todo or not results.exists() or not results.read_bytes().endswith(b"\n"):
        write_rows(results, kept)

    fitting = 0.0
    if not todo:
        print(f"nothing to do: all {len(meshes)} meshes of {source} have their model and row "
              f"in {results}" + (" (--retry-failed fits the failed ones again)"
                                 if any(rows[r]["status"] != "ok" for r in names) else ""),
              file=out, flush=True)
    else:
        print(f"{len(todo)} of {len(meshes)} meshes to fit ({len(meshes) - len(todo)} done "
              f"before) into {output}", file=out, flush=True)
        fitting = _fit_all(todo, output, options, key, threads, scheduler, workers, gather,
                           timeout, peer, progress, out, err)
    rows = read_rows(results)
    collection = [rows[rel] for _, rel in meshes if rel in rows]
    # A run that fitted nothing writes nothing, unless the summary is missing.
    stale = todo or not all((output / f).exists() for f in ("summary.md", "rms-storage.png"))
    summary = summarize(output, collection, write=stale)
    if stale:
        write_parquet(output)
    if todo:
        print(summary, file=out, flush=True)
        print(f"wrote {results}, {output / 'summary.md'}, {output / 'rms-storage.png'}",
              file=out, flush=True)
    return {"meshes": len(meshes), "todo": len(todo),
            "ok": sum(r["status"] == "ok" for r in collection),
            "failed": sum(r["status"] != "ok" for r in collection), "rows": collection,
            "summary": summary, "wall_s": time.monotonic() - start, "fitting_s": fitting}


def _fit_all(todo, output, options, key, threads, scheduler, workers, gather, timeout, peer,
             progress, out, err):
    """Submits one task a mesh and writes each result as it comes: the model (with gather),
    then the row. This process is the only writer of results.csv, and each mesh's future
    gives one result however often Dask ran it, so no row is written twice. -> the seconds
    from the first task submitted to the last row written."""
    from distributed import as_completed

    from pdesurf.batch import fit_task  # by name, also when this module runs as __main__
    client, cluster = _start(scheduler, workers)
    terminal = err.isatty() if progress is None else progress
    bar = Progress(len(todo), terminal, out, err)
    stop = threading.Event()
    try:
        if client.dashboard_link and _has_dashboard(client):
            print(f"Dask dashboard: {client.dashboard_link}", file=out, flush=True)
        _check_workers(client, scheduler, out)
        futures = {}
        submitted = time.monotonic()
        for path, rel in todo:
            job = {"path": os.path.abspath(path), "options": options, "threads": threads,
                   "timeout": timeout, "peer": peer, "gather": gather,
                   "model_path": str((output / f"{rel}.json").resolve())}
            # Keys unique to this output, options and mesh: another client of the same
            # scheduler fitting the same mesh elsewhere gets a task of its own.
            name = f"{output.resolve()}\0{key}\0{rel}"
            task = "pdesurf-fit-" + hashlib.sha1(name.encode()).hexdigest()[:20]
            futures[client.submit(fit_task, job, key=task, pure=False)] = rel
        ours = {f.key for f in futures}

        def watch():  # the running count, from the scheduler, once a second
            while not stop.wait(1.0):
                try:
                    # A worker's "processing" includes tasks queued on it: at most its
                    # threads run.
                    processing, threads_of = client.processing(), client.nthreads()
                    bar.running = sum(min(threads_of.get(w, 1), sum(k in ours for k in keys))
                                      for w, keys in processing.items())
                except Exception:  # noqa: BLE001 -- a progress line is not worth failing for
                    pass
                bar.draw()
        if terminal:
            threading.Thread(target=watch, daemon=True).start()
        bar.draw()
        for future in as_completed(futures):
            rel = futures[future]
            try:
                result = future.result()
            except Exception as e:  # noqa: BLE001 -- e.g. KilledWorker: its workers all died
                result = {"status": "failed", "error": f"{type(e).__name__}: {e}"[:500]}
            row = {c: "" for c in COLUMNS}
            row.update(result, path=rel, options=key)
            if row["status"] == "ok":
                row["model"] = f"{rel}.json"
                if gather:
                    _batch_fit.write_atomically(str(output / row["model"]), row.pop("model_json"))
                elif not is_complete(row, output, key, False):
                    row.update(status="failed", model="", error=(
                        f"the worker wrote {row['model']}, but this client does not find it "
                        f"whole in {output}: is OUTPUT a folder the workers share? (else "
                        "--gather)"))
            append_row(output / RESULTS, row)
            bar.finished(row)
            future.release()
        return time.monotonic() - submitted
    finally:
        stop.set()
        bar.close()
        client.close()
        if cluster is not None:
            cluster.close()


def _probe():
    import pdesurf.batch  # noqa: F401 -- what every task needs
    return True


def _check_workers(client, scheduler, out):
    """Waits for a worker (saying so when none is there yet) and checks that it imports
    pdesurf: a cluster whose workers cannot is an InputError, not a row of failures a mesh."""
    if not client.scheduler_info().get("workers"):
        print(f"waiting for a worker to connect to {scheduler}", file=out, flush=True)
    try:
        client.submit(_probe, pure=False).result()
    except Exception as e:  # noqa: BLE001 -- whatever the worker raised, it cannot fit
        raise InputError(f"the workers cannot import pdesurf ({type(e).__name__}: {e}): give "
                         "them its folder on PYTHONPATH (docs/batch.md)") from None


def _has_dashboard(client):
    """Whether the scheduler serves the dashboard (it needs bokeh, on the scheduler's host:
    this process's bokeh stands for it)."""
    try:
        import bokeh  # noqa: F401
        return "dashboard" in client.scheduler_info().get("services", {})
    except Exception:  # noqa: BLE001 -- no bokeh, or no answer: no link to print
        return False


# ------------------------------------------------------------------------------------------
# The command.

def parser():
    p = argparse.ArgumentParser(
        prog="python3 -m pdesurf.batch",
        description="Rebuild a collection of meshes as PDE models on Dask (docs/batch.md): "
                    "OUTPUT/<relative path>.json a mesh, OUTPUT/results.csv a row a mesh, "
                    "OUTPUT/summary.md and rms-storage.png at the end. A rerun fits only the "
                    "meshes without a complete model and row.")
    p.add_argument("input", metavar="INPUT",
                   help="a folder (its .off .obj .ply .stl files, recursively) or a text file "
                        "listing mesh paths, one a line")
    p.add_argument("-o", "--output", required=True, metavar="OUTPUT", help="the output folder")
    run_ = p.add_argument_group("the run")
    run_.add_argument("--workers", type=int, metavar="N",
                      help="LocalCluster worker processes, one thread each (default: one a "
                           "core)")
    run_.add_argument("--threads", type=int, default=1, metavar="T",
                      help="threads of each fit (0: every core; default 1)")
    run_.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                      help="a running Dask scheduler to send the fits to (instead of a "
                           "LocalCluster)")
    run_.add_argument("--gather", action="store_true",
                      help="workers return the models and this process writes them (default: "
                           "workers write them to OUTPUT, which they must share)")
    run_.add_argument("--timeout", type=float, metavar="SECONDS",
                      help="a fit running longer is killed and its mesh recorded as failed")
    run_.add_argument("--peer", action="store_true",
                      help="also measure the polygon peer's storage at each model's RMS")
    run_.add_argument("--retry-failed", action="store_true",
                      help="fit again the meshes whose rows say failed")
    run_.add_argument("--no-progress", action="store_true",
                      help="no progress line, even on a terminal")
    r = p.add_argument_group("rebuild options (as pdesurf rebuild's; docs/rebuild.md)")
    r.add_argument("--as", dest="kind", choices=("vertex-frames", "cross-sections"),
                   default="vertex-frames")
    r.add_argument("--grid", type=int, nargs=2, metavar=("U", "V"))
    r.add_argument("--layout", metavar="QUADS_FILE")
    r.add_argument("--tube", type=int, nargs=2, metavar=("RINGS", "SECTORS"))
    r.add_argument("--frames", type=int, metavar="N")
    r.add_argument("--target-rms", metavar="X")
    r.add_argument("--max-normal-deviation", type=float, metavar="DEGREES")
    r.add_argument("--quads", choices=("pair", "split"))
    r.add_argument("--crease-angle", type=float, metavar="DEGREES")
    r.add_argument("--iterations", type=int, default=30)
    r.add_argument("--tolerance", type=float, default=1e-3)
    r.add_argument("--smoothness", type=float, default=1e-5)
    r.add_argument("--fit-samples", type=int, default=9)
    r.add_argument("--prevent-folds", action="store_true")
    r.add_argument("--fold-weight", type=float, default=1e-5)
    r.add_argument("--normal-weight", type=float, metavar="W")
    r.add_argument("--fit-shape", action="store_true")
    r.add_argument("--resolution", type=int, default=17)
    r.add_argument("--samples", type=int, default=100000)
    r.add_argument("--axis", choices=("x", "y", "z"), default="z")
    r.add_argument("--count", type=int, default=25)
    r.add_argument("--range", type=float, nargs=2, metavar=("A", "B"))
    r.add_argument("--near", type=float, nargs=3, metavar=("X", "Y", "Z"))
    r.add_argument("--track", action="store_true")
    r.add_argument("--modes", type=int, default=8)
    r.add_argument("--points", type=int, default=128)
    r.add_argument("--a", type=float, default=1.0)
    r.add_argument("--ends", choices=("natural", "estimated"), default="natural")
    r.add_argument("--exact", action="store_true")
    return p


def main(argv=None):
    p = parser()
    args = p.parse_args(argv)
    options = {name: getattr(args, name) for name in REBUILD_OPTIONS}
    defaults = {name: p.get_default(name) for name in REBUILD_OPTIONS}
    # Only what differs from rebuild's defaults: the row's options fingerprint then stays
    # the same for the same fit however it was asked for.
    options = {k: v for k, v in options.items() if v != defaults[k] or k == "kind"}
    try:
        result = run(args.input, args.output, options, workers=args.workers,
                     threads=args.threads, scheduler=args.scheduler, gather=args.gather,
                     timeout=args.timeout, peer=args.peer, retry_failed=args.retry_failed,
                     progress=False if args.no_progress else None)
    except UsageError as e:
        p.print_usage(sys.stderr)
        print(f"{p.prog}: error: {e}", file=sys.stderr)
        return 2
    except InputError as e:
        print(f"{p.prog}: error: {e}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print(f"\n{p.prog}: interrupted; rerun the same command to go on", file=sys.stderr)
        return 130
    return 1 if result["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
