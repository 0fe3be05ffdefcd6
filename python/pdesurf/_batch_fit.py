"""One fit of pdesurf.batch, in a process of its own (docs/batch.md): the Dask task
(pdesurf.batch.fit_task) starts `python3 -m pdesurf._batch_fit PARENT_PID`, writes the job as
JSON on its standard input and reads the result, one JSON object, from its standard output.

A crash of the library (a signal) or a hang ends this process alone: the task records the
mesh as failed and its Dask worker goes on. The process ends itself when its parent (the
worker) is gone, so that a worker killed mid-fit leaves no fit running.
"""

import hashlib
import json
import math
import os
import sys
import threading
import time


def _exit_with_parent(parent):
    """Ends this process (os._exit) soon after the process `parent` is gone: a killed parent's
    children are given to another parent, so getppid() changes."""
    def watch():
        while os.getppid() == parent:
            time.sleep(0.2)
        os._exit(3)
    threading.Thread(target=watch, daemon=True).start()


def write_atomically(path, text):
    """Writes `text` to `path` whole or not at all: a temporary file beside it, flushed to the
    disk, renamed over it (a rename within a folder is atomic on POSIX file systems)."""
    folder = os.path.dirname(path) or "."
    os.makedirs(folder, exist_ok=True)
    temporary = f"{path}.tmp-{os.getpid()}-{threading.get_ident()}"
    try:
        with open(temporary, "w", encoding="utf-8") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.unlink(temporary)
        raise


def sha256(text):
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def layout_text(options):
    """How the frames or sections were laid out, for the results' `layout` column."""
    if options.get("kind") == "cross-sections":
        return f"sections {options.get('count', 25)} along {options.get('axis', 'z')}"
    if options.get("grid") is not None:
        return "grid {}x{}".format(*options["grid"])
    if options.get("tube") is not None:
        return "tube {}x{}".format(*options["tube"])
    if options.get("layout") is not None:
        return f"quads {os.path.basename(options['layout'])}"
    if options.get("target_rms") is not None:
        return f"automatic, target {options['target_rms']}"
    return f"automatic, {options.get('frames') or 200} frames"


def fit(job):
    """Rebuilds job["path"] with job["options"] -> the result row's values (status "ok"), and
    the model written to job["model_path"] (or its text under "model_json" with
    job["gather"])."""
    import pdesurf
    pdesurf.set_threads(job["threads"])
    options = job["options"]
    start = time.process_time()
    model, report = pdesurf.rebuild(job["path"], **options)
    cpu = time.process_time() - start
    text = model.to_json()
    kind = options.get("kind", "vertex-frames")
    rms, largest = report["rms"], report["max"]
    reference = report.get("part")
    truth_bytes = (pdesurf._core.storage_bytes(reference) if reference is not None
                   else report.get("mesh_storage_bytes"))
    if truth_bytes is None:
        truth_bytes = pdesurf._core.storage_bytes(pdesurf.read_mesh(job["path"]))
    result = {
        "status": "ok", "method": kind, "layout": layout_text(options),
        "frames": len(model.frames) if kind == "vertex-frames" else "",
        "sections": len(report["sections"]) if kind == "cross-sections" else "",
        "rms_model_to_mesh": rms[0], "rms_mesh_to_model": rms[1],
        "max_model_to_mesh": largest[0], "max_mesh_to_model": largest[1],
        "storage_bytes": report["storage_bytes"], "mesh_storage_bytes": truth_bytes,
        "fit_cpu_s": round(cpu, 3), "model_sha256": sha256(text),
    }
    if job["peer"]:
        # The protocol of docs/accuracy-storage.md: the polygon peer at the model's accuracy,
        # sqrt((a² + b²) / 2) of its two one-way RMS distances.
        target = math.sqrt(0.5 * (rms[0] ** 2 + rms[1] ** 2))
        truth = reference if reference is not None else pdesurf.read_mesh(job["path"])
        peer = pdesurf.polygon_peer(truth, target, samples=options.get("samples", 100000))
        result.update(peer_storage_bytes=peer["bytes"], peer_rms=peer["rms"])
    if job["gather"]:
        result["model_json"] = text
    else:
        write_atomically(job["model_path"], text)
    return result


def main():
    _exit_with_parent(int(sys.argv[1]))
    job = json.load(sys.stdin)
    try:
        result = fit(job)
    except Exception as e:  # noqa: BLE001 -- every error of one mesh is that mesh's row
        message = " ".join(str(e).split()) or type(e).__name__
        result = {"status": "failed", "error": f"{type(e).__name__}: {message}"}
    sys.stdout.write(json.dumps(result) + "\n")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
