"""Bad calls raise the documented exceptions, memory stays flat, the GIL is released."""

import random
import sys
import threading
import time

import numpy as np
import pytest

import pdesurf
from conftest import ROOT

MUG = ROOT / "examples/mug.json"

# Resident memory after 1,000 load/solve/tessellate cycles, against after the warm-up: a leak
# of one mesh a cycle (the mug at resolution 17: about 60 kB) would add 60 MB, several times
# the process' size; 10 % leaves room for the allocator's own fluctuation.
RSS_GROWTH_LIMIT = 1.10


def bad_calls(surface, mesh):
    """(description, callable, the exception it must raise) for calls that are wrong."""
    v, t = mesh.vertices, mesh.triangles.astype(np.int64)
    n = len(v)
    frame = np.arange(8)[None, :]
    square = np.array([[0, 0, 0], [.5, 0, 0], [1, 0, 0], [1, .5, 0], [1, 1, 0], [.5, 1, 0],
                       [0, 1, 0], [0, .5, 0]], float)
    nan = v.copy()
    nan[3, 1] = np.nan
    return [
        ("vertices of shape (n, 2)", lambda: pdesurf.Mesh(v[:, :2], t), ValueError),
        ("vertices of strings", lambda: pdesurf.Mesh(v.astype(str), t), ValueError),
        ("vertices with NaN", lambda: pdesurf.Mesh(nan, t), ValueError),
        ("vertices None", lambda: pdesurf.Mesh(None, t), ValueError),
        ("ragged vertices", lambda: pdesurf.Mesh([[0, 0, 0], [1, 1]], t), ValueError),
        ("triangles as floats", lambda: pdesurf.Mesh(v, t.astype(float)), ValueError),
        ("a triangle index too large", lambda: pdesurf.Mesh(v, t + n), ValueError),
        ("a negative triangle index", lambda: pdesurf.Mesh(v, t - n), ValueError),
        ("triangles of shape (m, 4)", lambda: pdesurf.Mesh(v, np.c_[t, t[:, :1]]), ValueError),
        ("normals of the wrong count", lambda: pdesurf.Mesh(v, t, v[:-1]), ValueError),
        ("resolution 1", lambda: surface.tessellate(1), ValueError),
        ("resolution 5000", lambda: surface.tessellate(5000), ValueError),
        ("resolution -3", lambda: surface.tessellate(-3), TypeError),
        ("sample grid 1", lambda: surface.sample(1), ValueError),
        ("evaluate a patch out of range", lambda: surface.evaluate(10 ** 6, 0.5, 0.5),
         ValueError),
        ("evaluate at NaN", lambda: surface.evaluate(0, np.nan, 0.5), ValueError),
        ("evaluate a float patch", lambda: surface.evaluate(0.5, 0.5, 0.5), ValueError),
        ("evaluate shapes that do not broadcast",
         lambda: surface.evaluate([0, 1], [0.1, 0.2, 0.3], 0.5), ValueError),
        ("a frame index out of range", lambda: pdesurf.vertex_frames(square, frame + 1),
         ValueError),
        ("frames of shape (1, 7)", lambda: pdesurf.vertex_frames(square, frame[:, :7]),
         ValueError),
        ("ragged frames", lambda: pdesurf.vertex_frames(square, [[0, 1], [2]]), ValueError),
        ("a1 with NaN", lambda: pdesurf.vertex_frames(square, frame, a1=np.nan), ValueError),
        ("a1 of two rows for one frame",
         lambda: pdesurf.vertex_frames(square, frame, a1=np.ones((2, 3))), ValueError),
        ("a force on a frame out of range",
         lambda: pdesurf.vertex_frames(square, frame, forces=[{"frame": 3, "f0": [0, 0, 1]}]),
         ValueError),
        ("a force whose PDE has no solution",
         lambda: pdesurf.vertex_frames(square, frame, a1=0, a2=0,
                                       forces=[{"frame": 0, "f0": [0, 0, 1]}]),
         pdesurf.ModelError),
        ("an unknown solver", lambda: pdesurf.load(MUG).solve(solver="fast"), ValueError),
        ("a seed frame out of range",
         lambda: pdesurf.load(MUG).solve(solver="local", seed_frame=10 ** 6), ValueError),
        ("JSON that is not a model", lambda: pdesurf.parse('{"type": "teapot"}'),
         pdesurf.ModelError),
        ("text that is not JSON", lambda: pdesurf.parse("{"), pdesurf.ModelError),
        ("a model that is a number", lambda: pdesurf.parse(3), ValueError),
        ("a missing model file", lambda: pdesurf.load("/nonexistent/m.json"), pdesurf.Error),
        ("a missing mesh file", lambda: pdesurf.read_mesh("/nonexistent/m.off"),
         pdesurf.MeshIOError),
        ("saving to an unknown mesh format", lambda: mesh.save("/tmp/m.xyz"),
         pdesurf.MeshIOError),
        ("an unknown rebuild kind", lambda: pdesurf.rebuild(v, t, kind="nurbs"), ValueError),
        ("frames and target_rms together",
         lambda: pdesurf.rebuild(v, t, frames=10, target_rms=0.01), ValueError),
        ("a target_rms that is no fraction",
         lambda: pdesurf.rebuild(v, t, target_rms="2%x"), ValueError),
        ("a target_rms of the whole diagonal",
         lambda: pdesurf.rebuild(v, t, target_rms="100%"), ValueError),
        ("an automatic layout's option with a grid",
         lambda: pdesurf.rebuild(v, t, grid=(2, 2), frames=10), ValueError),
        ("an unknown quad construction", lambda: pdesurf.rebuild(v, t, quads="hex"), ValueError),
        ("a crease angle above 180°",
         lambda: pdesurf.rebuild(v, t, crease_angle=200), ValueError),
        ("a negative max_normal_deviation",
         lambda: pdesurf.rebuild(v, t, target_rms=0.01, max_normal_deviation=-1), ValueError),
        ("a max_normal_deviation that is not a number",
         lambda: pdesurf.rebuild(v, t, target_rms=0.01, max_normal_deviation=float("nan")),
         ValueError),
        ("a max_normal_deviation without target_rms",
         lambda: pdesurf.rebuild(v, t, max_normal_deviation=5), ValueError),
        ("rebuild with two layouts",
         lambda: pdesurf.rebuild(v, t, grid=(2, 2), tube=(2, 4)), ValueError),
        ("a grid of 0 frames", lambda: pdesurf.rebuild(v, t, grid=(0, 2)), ValueError),
        ("a grid on a closed mesh", lambda: pdesurf.rebuild(v, t, grid=(2, 2)),
         pdesurf.LayoutError),
        ("a tube of 2 sectors", lambda: pdesurf.rebuild(v, t, tube=(2, 2)), ValueError),
        ("fit_samples 2", lambda: pdesurf.rebuild(v, t, grid=(2, 2), fit_samples=2),
         ValueError),
        ("cross sections with too few points",
         lambda: pdesurf.rebuild(v, t, kind="cross-sections", modes=8, points=10), ValueError),
        ("a negative iteration count",
         lambda: pdesurf.rebuild(v, t, grid=(2, 2), iterations=-1), ValueError),
        ("cross sections with fit_shape",
         lambda: pdesurf.rebuild(v, t, kind="cross-sections", fit_shape=True), ValueError),
        ("a chain of one section",
         lambda: pdesurf.rebuild(v, t, kind="cross-sections", count=1), ValueError),
        ("cross sections with ends 'open'",
         lambda: pdesurf.rebuild(v, t, kind="cross-sections", ends="open"), ValueError),
        ("slicing along w", lambda: pdesurf.slice(mesh, axis="w"), ValueError),
        ("slicing with a reversed range", lambda: pdesurf.slice(mesh, range=(1, 0), count=3),
         ValueError),
        ("slicing beside the mesh", lambda: pdesurf.slice(mesh, range=(100, 101), count=2),
         pdesurf.SliceError),
        ("slicing near NaN", lambda: pdesurf.slice(mesh, near=(0, np.nan, 0)), ValueError),
        ("compare with no samples", lambda: pdesurf.compare(mesh, mesh, samples=0), ValueError),
        ("compare with a mesh of no triangles",
         lambda: pdesurf.compare(mesh, (v, np.zeros((0, 3), int))), pdesurf.MeshIOError),
        ("export to .dxf", lambda: pdesurf.export(surface, "/tmp/m.dxf"), pdesurf.CadError),
        ("export with a negative tolerance",
         lambda: pdesurf.export(surface, "/tmp/m.step", tolerance=-1), ValueError),
        ("an edit that is no edit", lambda: pdesurf.Session(pdesurf.load(MUG)).apply({"op": "x"}),
         pdesurf.ModelError),
        ("an edit that is a list", lambda: pdesurf.Session(pdesurf.load(MUG)).apply([1]),
         ValueError),
        ("set_threads(-1)", lambda: pdesurf.set_threads(-1), TypeError),
        ("a1 of a spectral model", lambda: pdesurf.load(ROOT / "examples/membrane.json").a1,
         TypeError),
    ]


def test_random_bad_calls_raise_the_documented_exceptions():
    surface = pdesurf.load(MUG).solve()
    mesh = surface.tessellate(9)
    calls = bad_calls(surface, mesh)
    rng = random.Random(28)
    # Every bad call once, then random ones up to 100.
    order = list(range(len(calls))) + [rng.randrange(len(calls)) for _ in range(100 - len(calls))]
    for index in order:
        what, call, expected = calls[index]
        with pytest.raises(expected) as raised:
            call()
        assert str(raised.value), what
    # The interpreter and the library still work.
    assert surface.tessellate(9).positions.tobytes() == mesh.positions.tobytes()


def resident_bytes():
    with open("/proc/self/statm") as statm:
        return int(statm.read().split()[1]) * 4096


def cycle():
    return pdesurf.load(MUG).solve().tessellate(17).vertex_count


def test_a_thousand_cycles_hold_memory_flat():
    count = cycle()
    for _ in range(100):  # warm-up: allocator pools, caches
        assert cycle() == count
    before = resident_bytes()
    for _ in range(1000):
        assert cycle() == count
    assert resident_bytes() <= RSS_GROWTH_LIMIT * before


def test_the_gil_is_released_while_tessellating():
    """While the main thread is inside tessellate, a second Python thread runs.

    With a switch interval far longer than the call, a thread that holds the GIL through
    the call lets no other Python thread run from before it to after it: the counter would
    not move. It moves only if the call released the GIL.
    """
    surface = pdesurf.load(ROOT / "examples/vase.json").solve()
    big = surface.tessellate(129)
    counter = [0]
    started, stop = threading.Event(), threading.Event()

    def count():
        started.set()
        while not stop.is_set():
            counter[0] += 1
            time.sleep(0.001)  # releases the GIL: the main thread takes it back at once

    interval = sys.getswitchinterval()
    worker = threading.Thread(target=count)
    worker.start()
    started.wait()
    sys.setswitchinterval(30.0)
    try:
        moved, held = [], []
        for _ in range(5):
            before = counter[0]
            surface.tessellate(129)  # a million vertices: milliseconds or more
            moved.append(counter[0] - before)
            # The control: a call that holds the GIL (the float64 copy of a million vertices,
            # also milliseconds) lets the counter stand still.
            before = counter[0]
            big.vertices
            held.append(counter[0] - before)
    finally:
        sys.setswitchinterval(interval)
        stop.set()
        worker.join()
    assert max(moved) > 0 and held == [0] * 5, (moved, held)


def test_two_threads_tessellate_the_same_meshes():
    surface = pdesurf.load(ROOT / "examples/vase.json").solve()
    expected = surface.tessellate(129).positions.tobytes()
    results = [None, None]

    def run(i):
        results[i] = surface.tessellate(129).positions.tobytes()

    threads = [threading.Thread(target=run, args=(i,)) for i in range(2)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert results == [expected, expected]
