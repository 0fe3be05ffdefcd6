#!/usr/bin/env python3
"""The Python package's call overhead and its no-copy meshes (docs/performance.md, "Python").

Usage: PYTHONPATH=build/python python3 bench/python_overhead.py [BUILD]   (BUILD: build)

1. Tessellating the mug at resolution 17 through Python against the same C++ call: the
   CLI's `build` prints the time of tessellate(solved, {17}) alone, the first call in a fresh
   process; the first surface.tessellate(17) of a fresh Python process is the same call
   through the binding. Minimum over RUNS fresh processes each, and their ratio; also the
   warm Python call (minimum of many in one process).
2. The 1,000-frame sheet (bench/studio/make_model.py) at resolution 33: the bytes numpy
   allocates (tracemalloc) and the time to get the mesh's positions, normals and triangles
   arrays (views of the library's buffers) against the mesh's size, and against `vertices`
   (the float32 -> float64 conversion, the one copy) and a plain copy of the positions.
"""

import pathlib
import re
import subprocess
import sys
import tempfile
import time
import tracemalloc

ROOT = pathlib.Path(__file__).resolve().parent.parent
RUNS = 20
WARM_CALLS = 2000
FRESH_CALL = """
import time, pdesurf
s = pdesurf.load({path!r}).solve()
t = time.perf_counter(); s.tessellate(17); print((time.perf_counter() - t) * 1e3)
"""


def cli_tessellate_ms(cli, model, out):
    text = subprocess.run([cli, "build", model, "-o", out], capture_output=True, text=True,
                          check=True).stdout
    return float(re.search(r"tessellate ([0-9.]+) ms", text).group(1))


def main(argv):
    build = pathlib.Path(argv[0] if argv else ROOT / "build")
    cli = str(build / "pdesurf")
    mug = str(ROOT / "examples/mug.json")
    import pdesurf

    with tempfile.TemporaryDirectory() as tmp:
        out = f"{tmp}/mug.ply"
        cpp = min(cli_tessellate_ms(cli, mug, out) for _ in range(RUNS))
        fresh = min(float(subprocess.run([sys.executable, "-c", FRESH_CALL.format(path=mug)],
                                         capture_output=True, text=True, check=True).stdout)
                    for _ in range(RUNS))
        surface = pdesurf.load(mug).solve()
        warm = []
        for _ in range(WARM_CALLS):
            t = time.perf_counter()
            surface.tessellate(17)
            warm.append((time.perf_counter() - t) * 1e3)
        print(f"mug, resolution 17, first call in a fresh process (min of {RUNS}): "
              f"C++ {cpp:.3f} ms, Python {fresh:.3f} ms, ratio {fresh / cpp:.2f}")
        print(f"mug, resolution 17, Python warm (min of {WARM_CALLS}): {min(warm):.3f} ms")

        sheet = f"{tmp}/sheet.json"
        subprocess.run([sys.executable, str(ROOT / "bench/studio/make_model.py"), sheet],
                       check=True, capture_output=True)
        mesh = pdesurf.load(sheet).solve().tessellate(33)
        size = sum(a.nbytes for a in (mesh.positions, mesh.normals, mesh.triangles))
        tracemalloc.start()
        t = time.perf_counter()
        views = (mesh.positions, mesh.normals, mesh.triangles, mesh.patch_ids)
        view_ms = (time.perf_counter() - t) * 1e3
        view_bytes = tracemalloc.get_traced_memory()[1]
        tracemalloc.reset_peak()
        t = time.perf_counter()
        wide = mesh.vertices
        wide_ms = (time.perf_counter() - t) * 1e3
        wide_bytes = tracemalloc.get_traced_memory()[1]
        tracemalloc.reset_peak()
        t = time.perf_counter()
        copy = mesh.positions.copy()
        copy_ms = (time.perf_counter() - t) * 1e3
        copy_bytes = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        print(f"sheet (1,000 frames), resolution 33: {mesh.vertex_count} vertices, "
              f"{mesh.triangle_count} triangles, {size / 1e6:.1f} MB of positions, normals, "
              f"triangles")
        print(f"  the four arrays (views): {view_ms:.3f} ms, {view_bytes} bytes allocated")
        print(f"  vertices (float64, converted): {wide_ms:.3f} ms, {wide_bytes / 1e6:.1f} MB")
        print(f"  positions.copy(): {copy_ms:.3f} ms, {copy_bytes / 1e6:.1f} MB")
        del views, wide, copy
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
