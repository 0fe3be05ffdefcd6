"""pdesurf.batch (docs/batch.md) on a collection of 8 CGAL meshes and 3 broken files: a
LocalCluster of 2 workers, a rerun, a deleted model, and a scheduler with two dask-worker
processes started here on 127.0.0.1, one of them killed mid-run. Registered in ctest as
python_batch (python/CMakeLists.txt); every process it starts is killed at the end."""

import csv
import fcntl
import os
import shutil
import signal
import subprocess
import sys
import time

import pytest

from conftest import BUILD, CLI, ROOT

distributed = pytest.importorskip("distributed")
psutil = pytest.importorskip("psutil")

# Small, quick meshes (closed, open, with holes, one of quads) and where they go.
MESHES = {"closed/sphere.off": "sphere.off", "closed/ellipsoid.off": "ellipsoid.off",
          "closed/geosphere.off": "geosphere.off", "closed/icosahedron.off": "icosahedron.off",
          "closed/cube_quad.off": "cube_quad.off", "tripod.off": "tripod.off",
          "open/patch-23.off": "patch-23.off", "open/dragknob.off": "dragknob.off"}
# The broken files and a word the reason for each must hold.
BROKEN = {"broken/empty.off": "not an OFF file", "broken/truncated.off": "too short",
          "broken/nonmanifold.off": "manifold"}
# Fast fits: the test is about the batch, not the fit.
FIT = ["--frames", "12", "--iterations", "2", "--samples", "2000", "--resolution", "5"]
RUN_LIMIT_S = 120  # a run of the batch, however loaded the machine (a bound, not a target)
ENV = dict(os.environ, PYTHONPATH=os.pathsep.join(
    p for p in (str(BUILD / "python"), os.environ.get("PYTHONPATH")) if p))


@pytest.fixture(scope="module")
def collection(tmp_path_factory, cgal_mesh):
    root = tmp_path_factory.mktemp("collection")
    for rel, name in MESHES.items():
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(cgal_mesh(name), root / rel)
    (root / "broken").mkdir()
    (root / "broken/empty.off").write_bytes(b"")
    (root / "broken/truncated.off").write_bytes(
        open(cgal_mesh("sphere.off"), "rb").read()[:300])
    # Three triangles on the edge 0-1.
    (root / "broken/nonmanifold.off").write_text(
        "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n")
    return root


@pytest.fixture(scope="module")
def processes():
    """Processes the tests start (each its own process group), all killed at the end."""
    started = []
    yield started
    for p in started:
        if p.poll() is None:
            try:
                os.killpg(p.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            p.wait()


def batch(args, processes, on_start=None):
    """Runs python3 -m pdesurf.batch ARGS -> (exit status, stdout, stderr); on_start(process)
    is called while it runs."""
    p = subprocess.Popen([sys.executable, "-m", "pdesurf.batch", *map(str, args)], env=ENV,
                         cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True)
    processes.append(p)
    if on_start:
        on_start(p)
    out, err = p.communicate(timeout=RUN_LIMIT_S)
    return p.returncode, out, err


def rows(output):
    with open(output / "results.csv", newline="") as f:
        return list(csv.DictReader(f))


@pytest.fixture(scope="module")
def local_run(collection, tmp_path_factory, processes):
    output = tmp_path_factory.mktemp("local")
    code, out, err = batch([collection, "-o", output, "--workers", "2", "--peer", *FIT],
                           processes)
    return output, code, out, err


def test_local_cluster_fits_the_meshes_and_records_the_broken_files(local_run, tmp_path):
    output, code, out, err = local_run
    assert code == 1, f"some meshes failed: exit status 1\n{out}\n{err}"
    table = rows(output)
    assert sorted(r["path"] for r in table) == sorted([*MESHES, *BROKEN])
    by_path = {r["path"]: r for r in table}
    for rel, word in BROKEN.items():
        assert by_path[rel]["status"] == "failed" and word in by_path[rel]["error"], by_path[rel]
        assert not (output / f"{rel}.json").exists()
    builds = []
    for rel in MESHES:
        row = by_path[rel]
        assert row["status"] == "ok", row
        assert row["model"] == f"{rel}.json" and (output / row["model"]).is_file()
        assert int(row["storage_bytes"]) > 0 and int(row["frames"]) >= 1
        # The polygon peer reaches the model's accuracy, sqrt((a² + b²) / 2).
        accuracy = ((float(row["rms_model_to_mesh"]) ** 2
                     + float(row["rms_mesh_to_model"]) ** 2) / 2) ** 0.5
        assert int(row["peer_storage_bytes"]) > 0 and float(row["peer_rms"]) <= accuracy
        builds.append(subprocess.Popen([str(CLI), "build", str(output / row["model"]),
                                        "--resolution", "5", "-o",
                                        str(tmp_path / f"{len(builds)}.obj")],
                                       stdout=subprocess.PIPE, stderr=subprocess.PIPE))
    for rel, b in zip(MESHES, builds):
        _, err_build = b.communicate(timeout=RUN_LIMIT_S)
        assert b.returncode == 0, f"pdesurf build {rel}.json: {err_build.decode()}"
    summary = (output / "summary.md").read_text()
    assert "## Failed" in summary and all(f"`{rel}`" in summary for rel in BROKEN)
    assert (output / "rms-storage.png").stat().st_size > 1000
    assert not list(output.rglob("*.tmp-*")), "a temporary file left behind"


def test_a_rerun_does_nothing_and_a_deleted_model_is_redone_alone(local_run, collection,
                                                                   processes):
    output, *_ = local_run
    before = (output / "results.csv").read_bytes()

    def stamps():
        return {p: p.stat().st_mtime_ns for p in output.rglob("*")
                if p.is_file() and p.name != "results.csv"}
    written = stamps()
    # A row cut short (the client killed while appending it) is dropped by the next run.
    with open(output / "results.csv", "a") as f:
        f.write("closed/sphere.off,ok,,vertex-fr")
    code, out, err = batch([collection, "-o", output, "--workers", "2", "--peer", *FIT],
                           processes)
    assert code == 1 and out.startswith("nothing to do"), out + err
    assert (output / "results.csv").read_bytes() == before
    assert stamps() == written

    old = {r["path"]: r for r in rows(output)}
    (output / "closed/sphere.off.json").unlink()
    code, out, err = batch([collection, "-o", output, "--workers", "2", "--peer", *FIT],
                           processes)
    assert code == 1 and out.startswith("1 of 11 meshes to fit"), out + err
    fitted = [line for line in out.splitlines() if line.startswith(("ok ", "failed "))]
    assert fitted == [line for line in fitted if "closed/sphere.off" in line] and fitted
    new = {r["path"]: r for r in rows(output)}
    assert len(rows(output)) == len(new) == 11
    assert new["closed/sphere.off"]["model_sha256"] == old["closed/sphere.off"]["model_sha256"]
    for path, stamp in written.items():
        if path.suffix == ".json" and path.name != "sphere.off.json":
            assert path.stat().st_mtime_ns == stamp, f"{path} was written again"


@pytest.fixture(scope="module")
def scheduler(tmp_path_factory, processes):
    """A dask-scheduler on 127.0.0.1 and two dask-worker processes (each a nanny and its
    worker) -> (address, nanny processes)."""
    folder = tmp_path_factory.mktemp("dask")
    file = folder / "scheduler.json"
    common = dict(env=ENV, cwd=folder, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                  start_new_session=True)
    processes.append(subprocess.Popen(
        ["dask-scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
         "--scheduler-file", str(file)], **common))
    deadline = time.monotonic() + RUN_LIMIT_S
    while not file.exists() and time.monotonic() < deadline:
        time.sleep(0.1)
    nannies = []
    for i in range(2):
        nannies.append(subprocess.Popen(
            ["dask-worker", "--scheduler-file", str(file), "--nthreads", "1", "--host",
             "127.0.0.1", "--no-dashboard", "--local-directory", str(folder / f"w{i}")],
            **common))
        processes.append(nannies[-1])
    with distributed.Client(scheduler_file=str(file), timeout="60s") as client:
        client.wait_for_workers(2, timeout=RUN_LIMIT_S)
        address = client.scheduler.address
    return address, nannies


def test_a_scheduler_with_a_worker_killed_gives_the_local_results(local_run, collection,
                                                                  scheduler, processes,
                                                                  tmp_path):
    address, nannies = scheduler
    killed = {}

    def kill_a_worker_mid_fit(batch_process):
        """SIGKILL the first worker seen running a fit (its child pdesurf._batch_fit)."""
        deadline = time.monotonic() + RUN_LIMIT_S
        while not killed and batch_process.poll() is None and time.monotonic() < deadline:
            for nanny in nannies:
                for p in psutil.Process(nanny.pid).children(recursive=True):
                    try:
                        if "pdesurf._batch_fit" in " ".join(p.cmdline()):
                            killed.update(worker=p.ppid(), fit=p.pid)
                            os.kill(p.ppid(), signal.SIGKILL)
                            return
                    except psutil.Error:
                        continue
            time.sleep(0.02)

    # The collection as a list file this time (its paths relative to the list's folder).
    listing = collection / "meshes.txt"
    listing.write_text("# the collection\n" + "\n".join(sorted([*MESHES, *BROKEN])) + "\n")
    output = tmp_path / "out"
    code, out, err = batch([listing, "-o", output, "--scheduler", address, "--gather",
                            "--peer", *FIT], processes, on_start=kill_a_worker_mid_fit)
    listing.unlink()
    assert killed, f"no fit was seen running to kill its worker\n{out}\n{err}"
    assert code == 1, out + err
    table = rows(output)
    assert sorted(r["path"] for r in table) == sorted([*MESHES, *BROKEN]), "each mesh once"
    local = {r["path"]: r for r in rows(local_run[0])}
    for r in table:
        same = ("status", "model_sha256", "storage_bytes", "rms_model_to_mesh",
                "rms_mesh_to_model", "peer_storage_bytes")
        assert {k: r[k] for k in same} == {k: local[r["path"]][k] for k in same}, r["path"]
    # The killed worker's fit ended with it (pdesurf._batch_fit watches its parent).
    deadline = time.monotonic() + 5
    while psutil.pid_exists(killed["fit"]) and time.monotonic() < deadline:
        try:
            if psutil.Process(killed["fit"]).status() == psutil.STATUS_ZOMBIE:
                break
        except psutil.NoSuchProcess:
            break
        time.sleep(0.1)
    alive = psutil.pid_exists(killed["fit"])
    assert not alive or psutil.Process(killed["fit"]).status() == psutil.STATUS_ZOMBIE


def test_bad_options_exit_2_with_a_clear_error(collection, tmp_path, capsys):
    from pdesurf import batch as pdesurf_batch
    for args, words in ((["--workers", "0"], "--workers: must be at least 1"),
                        (["--grid", "4", "4", "--frames", "10"], "not with layout, grid or tube"),
                        (["--timeout", "0"], "--timeout"),
                        (["--target-rms", "2%", "--frames", "9"], "give one of them"),
                        (["--target-rms", "2%", "--max-normal-deviation", "-1"],
                         "max_normal_deviation -1"),
                        (["--as", "spheres"], "invalid choice")):
        try:
            code = pdesurf_batch.main([str(collection), "-o", str(tmp_path / "o"), *args])
        except SystemExit as e:  # argparse's own usage errors
            code = e.code
        assert code == 2 and words in capsys.readouterr().err, args
        assert not (tmp_path / "o").exists(), "no output for options that cannot run"
    assert pdesurf_batch.main([str(tmp_path / "none"), "-o", str(tmp_path / "o")]) == 1
    assert "no such folder or list file" in capsys.readouterr().err
    # Another client writing to OUTPUT (holding its lock): refused.
    (tmp_path / "o").mkdir()
    with open(tmp_path / "o/.batch.lock", "a") as held:
        fcntl.flock(held, fcntl.LOCK_EX)
        assert pdesurf_batch.main([str(collection), "-o", str(tmp_path / "o")]) == 1
    assert "another pdesurf.batch is writing to it" in capsys.readouterr().err


def test_a_fit_that_hangs_or_crashes_is_a_failed_row(tmp_path, monkeypatch):
    """fit_task, the Dask task, on its own: a fit past its timeout is killed; a fit process
    that dies of a signal (a stand-in for python that segfaults at once) is reported so."""
    from pdesurf import batch as pdesurf_batch
    job = {"path": str(ROOT / "examples/mug.json"), "options": {"frames": 12}, "threads": 1,
           "timeout": 0.05, "peer": False, "gather": True, "model_path": ""}
    hang = tmp_path / "hang"
    hang.write_text("#!/bin/sh\nexec sleep 60\n")
    crash = tmp_path / "crash"
    crash.write_text("#!/bin/sh\nkill -SEGV $$\n")
    for script in (hang, crash):
        script.chmod(0o755)
    monkeypatch.setattr(sys, "executable", str(hang))
    start = time.monotonic()
    result = pdesurf_batch.fit_task(job)
    assert result["status"] == "failed" and result["error"].startswith("timeout: the fit ran")
    assert time.monotonic() - start < 30, "the hanging fit was not killed at its timeout"
    monkeypatch.setattr(sys, "executable", str(crash))
    result = pdesurf_batch.fit_task(dict(job, timeout=RUN_LIMIT_S))
    assert result["status"] == "failed" and "killed by SIGSEGV" in result["error"], result
