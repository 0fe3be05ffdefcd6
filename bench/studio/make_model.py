#!/usr/bin/env python3
"""Writes the studio latency benchmark's model: a wavy ROWS x COLS sheet of vertex frames
over one shared lattice (docs/model-format.md), 25 x 40 = 1,000 frames by default.

Usage: make_model.py OUT.json [ROWS COLS]"""
import json
import math
import sys

# The 8 lattice points of the frame in cell (r, c), as offsets from (2r, 2c): corners and
# edge midpoints, in the order of scripts/make_examples.py (FRAME_LATTICE).
FRAME_LATTICE = [(0, 0), (0, 1), (0, 2), (1, 2), (2, 2), (2, 1), (2, 0), (1, 0)]


def main(argv):
    if any(a in ("-h", "--help") for a in argv):
        print(__doc__.strip())
        return 0
    if len(argv) not in (1, 3) or argv[0].startswith("-"):
        print("usage: make_model.py OUT.json [ROWS COLS]", file=sys.stderr)
        return 2
    out = argv[0]
    rows, cols = (int(argv[1]), int(argv[2])) if len(argv) == 3 else (25, 40)
    vertices, index = [], {}
    for i in range(2 * rows + 1):
        for j in range(2 * cols + 1):
            if i % 2 and j % 2:
                continue  # frame centres are not vertices
            x, y = 0.5 * j, 0.5 * i
            z = 0.4 * math.sin(0.35 * x) * math.cos(0.45 * y)
            index[i, j] = len(vertices)
            vertices.append([round(x, 6), round(y, 6), round(z, 6)])
    frames = [{"vertices": [index[2 * r + di, 2 * c + dj] for di, dj in FRAME_LATTICE]}
              for r in range(rows) for c in range(cols)]
    model = {"type": "vertex-frames", "name": f"latency sheet {rows}x{cols}",
             "description": "bench/studio: studio edit-to-frame latency",
             "vertices": vertices, "frames": frames}
    with open(out, "w") as f:
        json.dump(model, f, separators=(",", ":"))
    print(f"{out}: {len(frames)} frames, {len(vertices)} vertices")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
