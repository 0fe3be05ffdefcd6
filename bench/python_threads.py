#!/usr/bin/env python3
"""Two Python threads tessellating at once against the same two calls in sequence.

Usage: PYTHONPATH=build/python python3 bench/python_threads.py [--rounds N]

The package releases the GIL around tessellation (python/tests/test_robustness.py checks
that a second thread runs during the call). This measures what that buys on a machine with
two or more cores: the vase at resolution 257, the library's own threads set to 1 so that
each call uses one core, a warm-up call, then ROUNDS rounds alternating sequential and
concurrent; the medians, their ratio (target: concurrent <= 0.7x sequential,
docs/performance.md "Python") and whether the results are byte-identical (compared after the
clock stops: the copy holds the GIL).
"""

import argparse
import os
import pathlib
import statistics
import sys
import threading
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
RESOLUTION = 257


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    parser.add_argument("--rounds", type=int, default=9, help="rounds of each kind (default 9)")
    args = parser.parse_args(argv)
    if args.rounds < 1:
        parser.error("--rounds must be at least 1")
    import pdesurf

    pdesurf.set_threads(1)
    surface = pdesurf.load(ROOT / "examples/vase.json").solve()
    expected = surface.tessellate(RESOLUTION).positions.tobytes()
    results = [None, None]
    surface.tessellate(RESOLUTION)  # a warm-up call: the allocator's first pages

    def run(i):
        results[i] = surface.tessellate(RESOLUTION)  # compared after the clock stops

    def sequential():
        t = time.perf_counter()
        run(0)
        run(1)
        return time.perf_counter() - t

    def concurrent():
        threads = [threading.Thread(target=run, args=(i,)) for i in range(2)]
        t = time.perf_counter()
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        return time.perf_counter() - t

    seq, con, identical = [], [], True
    for _ in range(args.rounds):
        seq.append(sequential())
        con.append(concurrent())
        identical = identical and all(r.positions.tobytes() == expected for r in results)
    s, c = statistics.median(seq), statistics.median(con)
    print(f"vase, resolution {RESOLUTION}, {os.cpu_count()} cores, library threads 1, "
          f"median of {args.rounds} rounds: sequential {s * 1e3:.1f} ms, "
          f"two threads {c * 1e3:.1f} ms, ratio {c / s:.3f}; results identical: {identical}")
    print(f"  sequential {sorted(round(x * 1e3, 1) for x in seq)}")
    print(f"  two threads {sorted(round(x * 1e3, 1) for x in con)}")
    return 0 if identical else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
