#!/usr/bin/env python3
"""The Python package's call overhead and its no-copy meshes (docs/performance.md, "Python").

Usage: PYTHONPATH=build/python python3 bench/python_overhead.py [BUILD]   (BUILD: build)

1. Tessellating the mug at resolution 17 through Python against the same C++ call
   (tessellate(solved, {17}) of the model layer, bench/bench_model_tessellate.cpp): each
   side in ROUNDS rounds, alternating, each round the mean over CALLS calls (Google
   Benchmark's own count in C++); the medians and their ratio.
2. The 1,000-frame sheet (bench/studio/make_model.py) at resolution 33: the bytes numpy
   allocates (tracemalloc) and the time to get the mesh's positions, normals, triangles and
   patch ids (views of the library's buffers), against `vertices` (the float32 -> float64
   conversion, the one copy) and a plain copy of the positions.
"""

import json
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time
import tracemalloc

ROOT = pathlib.Path(__file__).resolve().parent.parent
ROUNDS = 7
CALLS = 500


def cpp_ms(build):
    """One round of the C++ call: Google Benchmark's mean time a call, in ms."""
    out = subprocess.run([str(build / "bench/bench_model_tessellate"),
                          "--benchmark_format=json", "--benchmark_min_time=0.5"],
                         capture_output=True, text=True, check=True).stdout
    return json.loads(out)["benchmarks"][0]["real_time"]


def python_ms(surface):
    """One round of the Python call: the mean over CALLS calls, in ms."""
    t = time.perf_counter()
    for _ in range(CALLS):
        surface.tessellate(17)
    return (time.perf_counter() - t) * 1e3 / CALLS


def main(argv):
    if any(a in ("-h", "--help") for a in argv):
        print(__doc__.strip())
        return 0
    if len(argv) > 1 or (argv and argv[0].startswith("-")):
        print("usage: python3 bench/python_overhead.py [BUILD]", file=sys.stderr)
        return 2
    build = pathlib.Path(argv[0] if argv else ROOT / "build")
    mug = str(ROOT / "examples/mug.json")
    import pdesurf

    with tempfile.TemporaryDirectory() as tmp:
        surface = pdesurf.load(mug).solve()
        cpp, python = [], []
        for _ in range(ROUNDS):
            cpp.append(cpp_ms(build))
            python.append(python_ms(surface))
        c, p = statistics.median(cpp), statistics.median(python)
        print(f"mug, resolution 17 ({surface.tessellate(17).vertex_count} vertices), median of "
              f"{ROUNDS} rounds: C++ {c:.3f} ms, Python {p:.3f} ms, ratio {p / c:.3f}")
        print(f"  C++ rounds {sorted(round(x, 3) for x in cpp)}, "
              f"Python rounds {sorted(round(x, 3) for x in python)}")

        sheet = f"{tmp}/sheet.json"
        subprocess.run([sys.executable, str(ROOT / "bench/studio/make_model.py"), sheet],
                       check=True, capture_output=True)
        mesh = pdesurf.load(sheet).solve().tessellate(33)
        size = sum(a.nbytes for a in (mesh.positions, mesh.normals, mesh.triangles))
        tracemalloc.start()

        def measured(make):
            """(the result, ms, bytes numpy allocated for it) of make()."""
            before = tracemalloc.get_traced_memory()[0]
            t = time.perf_counter()
            result = make()
            ms = (time.perf_counter() - t) * 1e3
            return result, ms, tracemalloc.get_traced_memory()[0] - before

        views, view_ms, view_bytes = measured(
            lambda: (mesh.positions, mesh.normals, mesh.triangles, mesh.patch_ids))
        wide, wide_ms, wide_bytes = measured(lambda: mesh.vertices)
        copy, copy_ms, copy_bytes = measured(lambda: mesh.positions.copy())
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
