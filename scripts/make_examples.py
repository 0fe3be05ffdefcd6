#!/usr/bin/env python3
"""Generates the example vertex-frame models in examples/*.json.

Usage, from the repository root:  python3 scripts/make_examples.py [--check]

Standard library only and deterministic: the same files come out every run. Numbers
are rounded to 6 significant digits and each vertex, frame and force takes one line,
so a change to a model reads as a small diff. Every model is checked before it is
written (see `check`): indices in range, shared edges share their middle vertex, no
duplicate vertices, no edge on more than two frames, every vertex used, orientable.
With --check nothing is written; the files on disk are compared with what would be.

Conventions (docs/vertex-frames.md): a frame lists 8 vertex indices P1..P8
counter-clockwise around the unit square, P1 (0,0), P2 (½,0), P3 (1,0), P4 (1,½),
P5 (1,1), P6 (½,1), P7 (0,1), P8 (0,½). Each side is a curve through its corner,
middle and corner vertex, so middles sit at the midpoint of the intended curve.
"""

import math
import os
import sys

SIGNIFICANT = 6
DUPLICATE_TOLERANCE = 1e-9  # two vertices closer than this are the same point
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLES = os.path.join(ROOT, "examples")

# Lattice offsets (row = v, column = u) of P1..P8 inside a frame spanning 2×2 lattice steps.
FRAME_LATTICE = [(0, 0), (0, 1), (0, 2), (1, 2), (2, 2), (2, 1), (2, 0), (1, 0)]
# The four sides as slots (start, middle, end), each in its own parameter direction.
SIDES = {"alpha": (0, 1, 2), "delta": (2, 3, 4), "beta": (6, 5, 4), "gamma": (0, 7, 6)}


def rounded(x):
    """x rounded to SIGNIFICANT digits, without negative zero."""
    if abs(x) < 1e-12:
        return 0.0
    value = float(format(x, ".%dg" % SIGNIFICANT))
    return 0.0 if value == 0 else value


def number(x):
    """JSON text of a number: integers without a decimal point, others with 6 digits."""
    x = rounded(x)
    if x == int(x) and abs(x) < 1e15:
        return str(int(x))
    return format(x, ".%dg" % SIGNIFICANT)


def vector(values):
    return "[" + ", ".join(number(v) for v in values) + "]"


def lerp(a, b, t):
    return tuple(x + (y - x) * t for x, y in zip(a, b))


def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def scale(a, s):
    return tuple(x * s for x in a)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalized(a):
    n = math.sqrt(sum(x * x for x in a))
    return tuple(x / n for x in a)


def catmull_rom(points, samples_per_span=64):
    """A dense polyline through `points` (tuples) along a uniform Catmull-Rom spline."""
    ext = [points[0]] + list(points) + [points[-1]]
    out = []
    for i in range(1, len(ext) - 2):
        p0, p1, p2, p3 = ext[i - 1], ext[i], ext[i + 1], ext[i + 2]
        for s in range(samples_per_span):
            t = s / samples_per_span
            t2, t3 = t * t, t * t * t
            out.append(tuple(
                0.5 * (2 * b + (c - a) * t + (2 * a - 5 * b + 4 * c - d) * t2 +
                       (3 * b - a - 3 * c + d) * t3)
                for a, b, c, d in zip(p0, p1, p2, p3)))
    out.append(tuple(points[-1]))
    return out


def resample(points, count, weights=None):
    """`count`+1 points along the spline through `points`, equally spaced in arc length
    (or at the cumulative fractions given by `weights`, one weight per step)."""
    dense = catmull_rom(points)
    lengths = [0.0]
    for a, b in zip(dense, dense[1:]):
        lengths.append(lengths[-1] + math.dist(a, b))
    total = lengths[-1]
    if weights is None:
        weights = [1.0] * count
    assert len(weights) == count
    targets, acc = [0.0], 0.0
    for w in weights:
        acc += w
        targets.append(acc / sum(weights) * total)
    out, k = [], 0
    for target in targets:
        while k < len(lengths) - 2 and lengths[k + 1] < target:
            k += 1
        span = lengths[k + 1] - lengths[k]
        t = 0.0 if span == 0 else min(1.0, max(0.0, (target - lengths[k]) / span))
        out.append(lerp(dense[k], dense[k + 1], t))
    out[0], out[-1] = tuple(points[0]), tuple(points[-1])
    return out


def profile(pieces):
    """Lattice points of a profile made of smooth pieces joined at corners (creases).
    Each piece is (control points, rows[, row weights]); a piece of n rows gives 2n
    lattice steps, so its middles fall halfway (in arc length) along each row."""
    out = []
    for piece in pieces:
        points, rows = piece[0], piece[1]
        weights = None
        if len(piece) > 2:
            weights = [w for w in piece[2] for _ in range(2)]
        pts = resample(points, 2 * rows, weights)
        if out:
            assert math.dist(out[-1], pts[0]) < 1e-12, "profile pieces must join"
            pts = pts[1:]
        out.extend(pts)
    return out


class Model:
    """A vertex-frame model under construction."""

    def __init__(self, name, description, shared_edges_allowed=2):
        self.name = name
        self.description = description
        self.vertices = []
        self.frames = []
        self.forces = []
        self.shared_edges_allowed = shared_edges_allowed

    def vertex(self, p):
        self.vertices.append(tuple(rounded(c) for c in p))
        return len(self.vertices) - 1

    def frame(self, indices, a1=None, a2=None, forces=None):
        assert len(indices) == 8
        frame = {"vertices": list(indices)}
        if a1 is not None:
            frame["a1"] = list(a1)
        if a2 is not None:
            frame["a2"] = list(a2)
        if forces:
            frame["forces"] = forces
        self.frames.append(frame)
        return len(self.frames) - 1

    def lattice(self, rows, cols, position, periodic=True):
        """Vertex indices of a (2·rows+1) × (2·cols[+1]) lattice; point (i, j) is at
        `position(i, j)`, which returns a point or the index of an existing vertex.
        Points with both i and j odd (frame centres) are not vertices."""
        width = 2 * cols if periodic else 2 * cols + 1
        grid = {}
        for i in range(2 * rows + 1):
            for j in range(width):
                if i % 2 and j % 2:
                    continue
                p = position(i, j)
                grid[i, j] = p if isinstance(p, int) else self.vertex(p)
        return Lattice(grid, width if periodic else None)

    def grid_frames(self, lattice, rows, cols, skip=(), **frame_args):
        """One frame per lattice cell (row r, column c) not in `skip`: u runs along j,
        v along i. Returns {(r, c): frame index}."""
        out = {}
        for r in range(rows):
            for c in range(cols):
                if (r, c) in skip:
                    continue
                out[r, c] = self.frame(lattice.frame(r, c), **frame_args)
        return out

    def json_text(self):
        lines = ["{", '  "type": "vertex-frames",',
                 '  "name": "%s",' % self.name,
                 '  "description": "%s",' % self.description.replace('"', '\\"'),
                 '  "vertices": [']
        lines += ["    %s%s" % (vector(v), "," if k + 1 < len(self.vertices) else "")
                  for k, v in enumerate(self.vertices)]
        lines += ["  ],", '  "frames": [']
        for k, f in enumerate(self.frames):
            parts = ['"vertices": [%s]' % ", ".join(str(i) for i in f["vertices"])]
            for key in ("a1", "a2"):
                if key in f:
                    parts.append('"%s": %s' % (key, vector(f[key])))
            if "forces" in f:
                forces = ", ".join('{"f0": %s, "region": %s}' % (vector(g["f0"]), vector(g["region"]))
                                   for g in f["forces"])
                parts.append('"forces": [%s]' % forces)
            lines.append("    {%s}%s" % (", ".join(parts), "," if k + 1 < len(self.frames) else ""))
        lines.append("  ],")
        if self.forces:
            lines.append('  "forces": [')
            lines += ['    {"f0": %s, "frames": [%s]}%s' % (
                vector(g["f0"]), ", ".join(str(i) for i in g["frames"]),
                "," if k + 1 < len(self.forces) else "") for k, g in enumerate(self.forces)]
            lines.append("  ]")
        else:
            lines.append('  "forces": []')
        lines.append("}")
        return "\n".join(lines) + "\n"


class Lattice:
    def __init__(self, grid, period):
        self.grid = grid
        self.period = period

    def __getitem__(self, ij):
        i, j = ij
        if self.period:
            j %= self.period
        return self.grid[i, j]

    def frame(self, r, c):
        return [self[2 * r + di, 2 * c + dj] for di, dj in FRAME_LATTICE]


# ---------------------------------------------------------------------------------------
# Checks


class ModelError(Exception):
    pass


def check(model):
    """Asserts the rules of a vertex-frame model; returns a one-line summary."""
    n = len(model.vertices)
    problems = []

    def fail(message):
        problems.append(message)

    for k, f in enumerate(model.frames):
        v = f["vertices"]
        if len(v) != 8 or any(not (0 <= i < n) for i in v):
            fail("frame %d: indices out of range or not 8: %s" % (k, v))
            continue
        collapsed = 0
        for side, (s, m, e) in SIDES.items():
            a, b, c = v[s], v[m], v[e]
            if a == b == c:
                collapsed += 1
            elif a == c or b in (a, c):
                fail("frame %d: side %s %s is neither a curve nor a point" % (k, side, (a, b, c)))
        if collapsed > 1:
            fail("frame %d: %d collapsed sides" % (k, collapsed))
        if len(set(v)) != 8 - 2 * collapsed:
            fail("frame %d: repeated vertex %s" % (k, v))
        for key in ("a1", "a2"):
            if key in f and (len(f[key]) != 3 or not all(math.isfinite(x) for x in f[key])):
                fail("frame %d: bad %s" % (k, key))
        for g in f.get("forces", []):
            u0, u1, v0, v1 = g["region"]
            if not (0 <= u0 < u1 <= 1 and 0 <= v0 < v1 <= 1) or len(g["f0"]) != 3:
                fail("frame %d: bad force %s" % (k, g))
    for g in model.forces:
        if not g["frames"] or any(not (0 <= i < len(model.frames)) for i in g["frames"]):
            fail("force over frames %s: index out of range" % g["frames"])
    if problems:
        raise ModelError("%s: %s" % (model.name, "; ".join(problems)))

    # Edges: sides keyed by their two corners must agree on the middle.
    edges = {}
    for k, f in enumerate(model.frames):
        v = f["vertices"]
        for side, (s, m, e) in SIDES.items():
            if v[s] == v[m] == v[e]:
                continue
            key = (min(v[s], v[e]), max(v[s], v[e]))
            edges.setdefault(key, []).append((k, side, v[m], v[s] < v[e]))
    for key, sides in edges.items():
        middles = {m for _, _, m, _ in sides}
        if len(middles) > 1:
            fail("edge %s: frames %s disagree on the middle vertex %s"
                 % (key, [s[0] for s in sides], sorted(middles)))
        if len(sides) > model.shared_edges_allowed:
            fail("edge %s is on %d frames %s" % (key, len(sides), [s[0] for s in sides]))

    # No duplicate vertices, none unused.
    order = sorted(range(n), key=lambda i: model.vertices[i])
    for a in range(n):
        for b in range(a + 1, n):
            pa, pb = model.vertices[order[a]], model.vertices[order[b]]
            if pb[0] - pa[0] > DUPLICATE_TOLERANCE:
                break
            if math.dist(pa, pb) <= DUPLICATE_TOLERANCE:
                fail("vertices %d and %d coincide at %s" % (order[a], order[b], pa))
    used = {i for f in model.frames for i in f["vertices"]}
    if len(used) != n:
        fail("unused vertices %s" % sorted(set(range(n)) - used))

    # Orientation: frames sharing an edge, once flipped as needed, must run it in opposite
    # directions around their boundaries (P1→P3→P5→P7). A conflict is a Möbius band.
    parent = list(range(len(model.frames)))
    parity = [0] * len(model.frames)

    def find(x):
        if parent[x] == x:
            return x, 0
        root, p = find(parent[x])
        parent[x], parity[x] = root, parity[x] ^ p
        return root, parity[x]

    forward = {"alpha": True, "delta": True, "beta": False, "gamma": False}
    orientable = True
    for key, sides in edges.items():
        for (k0, s0, _, d0), (k1, s1, _, d1) in zip(sides, sides[1:]):
            # Same traversal direction around both boundaries means one frame is flipped.
            same = (d0 == forward[s0]) == (d1 == forward[s1])
            (r0, p0), (r1, p1) = find(k0), find(k1)
            want = 1 if same else 0
            if r0 != r1:
                parent[r1], parity[r1] = r0, p0 ^ p1 ^ want
            elif p0 ^ p1 != want:
                orientable = False
    if not orientable:
        fail("not orientable")
    parts = len({find(k)[0] for k in range(len(model.frames))})
    if parts != 1:
        fail("%d disconnected parts" % parts)
    if problems:
        raise ModelError("%s: %s" % (model.name, "; ".join(problems)))
    boundary = sum(1 for sides in edges.values() if len(sides) == 1)
    flipped = sum(find(k)[1] for k in range(len(model.frames)))
    return "%-12s %3d frames %4d vertices %3d boundary edges %2d mirrored frames" % (
        model.name, len(model.frames), n, boundary, flipped)


# ---------------------------------------------------------------------------------------
# Models


def column_angles(widths):
    """Lattice angles (corners and middles) of columns `widths` degrees wide, counter-
    clockwise from the first column, which is centred on +x."""
    angles = [-math.radians(widths[0]) / 2]
    for w in widths:
        angles += [angles[-1] + math.radians(w) / 2, angles[-1] + math.radians(w)]
    return angles[:-1]  # the last corner is the first


def revolution(model, rings, cols=8, angles=None):
    """Lattice of a surface of revolution about z: `rings[i]` is (radius, z) of lattice row
    i; a ring of radius 0 is one vertex (a pole). Column lattice j sits at angle
    angles[j], by default (j - 1)·π/cols: column 0 is centred on +x."""
    pole = {}
    if angles is None:
        angles = [(j - 1) * math.pi / cols for j in range(2 * cols)]

    def position(i, j):
        r, z = rings[i]
        if r == 0:
            if i not in pole:
                pole[i] = model.vertex((0.0, 0.0, z))
            return pole[i]
        return (r * math.cos(angles[j]), r * math.sin(angles[j]), z)

    return model.lattice(len(rings) // 2, cols, position)


def mug():
    m = Model("mug", "A mug: a closed flat bottom, a slightly flared wall of 5 rows by 8 "
              "columns with an open rim, and a C-shaped handle: a tube of 4 frames around "
              "whose end rings replace two wall frames (a branch).")
    radius, flare, height = 1.0, 0.05, 2.5
    row_heights = [0.5, 0.45, 0.65, 0.45, 0.45]  # rows 1 and 3 hold the handle's ends
    zs = [0.0]
    for h in row_heights:
        zs += [zs[-1] + h / 2, zs[-1] + h]
    wall = [(radius + flare * z / height, z) for z in zs]
    rings = [(0.0, 0.0), (wall[0][0] / 2, 0.0)] + wall  # the bottom collapses to its centre
    # Column 0, where the handle attaches, is narrower than the other seven.
    handle_angle = math.radians(26.0)
    lat = revolution(m, rings, angles=column_angles([26.0] + [(360.0 - 26.0) / 7] * 7))
    rows = len(rings) // 2
    # Frame row 0 is the base, so wall row k is frame row k + 1; the handle replaces the
    # column-0 frames of wall rows 3 (upper end) and 1 (lower end).
    upper, lower = 3, 1
    m.grid_frames(lat, rows, 8, skip=((upper + 1, 0), (lower + 1, 0)))

    # The handle: a swept tube on a half ellipse in the xz-plane, from the upper hole out,
    # down and back into the lower hole. Cross-section coordinates (y, up) per ring slot
    # b = 0..7 follow the hole frame's P1..P8; at the lower end the path has turned half
    # a circle, so slot b meets the lower hole's P(7-b) (0-based (6-b) mod 8).
    hole_top = lat.frame(upper + 1, 0)
    hole_bottom = lat.frame(lower + 1, 0)
    z_top = (zs[2 * upper] + zs[2 * upper + 2]) / 2
    z_bottom = (zs[2 * lower] + zs[2 * lower + 2]) / 2
    zc, half = (z_top + z_bottom) / 2, (z_top - z_bottom) / 2
    reach = 0.75
    x0 = radius * (1 + math.cos(handle_angle / 2)) / 2 + flare * zc / height  # the holes' centres
    segments = 4
    w_end, h_end = radius * math.sin(handle_angle / 2), row_heights[upper] / 2
    w_mid, h_mid = 0.15, 0.1
    slots = [(-1, -1), (0, -1), (1, -1), (1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0)]

    def path(phi):
        point = (x0 + reach * math.sin(phi), 0.0, zc + half * math.cos(phi))
        tangent = normalized((reach * math.cos(phi), 0.0, -half * math.sin(phi)))
        return point, cross(tangent, (0.0, 1.0, 0.0))

    def section(phi, b):
        g = abs(math.cos(phi)) ** 1.5  # 1 at the ends, 0 halfway
        w = w_mid + (w_end - w_mid) * g
        h = h_mid + (h_end - h_mid) * g
        bulge = 1.0 + 0.35 * (1 - g)  # middles pushed out: a rounder tube midway
        sy, su = slots[b]
        k = bulge if (sy == 0 or su == 0) else 1.0
        point, up = path(phi)
        return add(point, add((0.0, sy * w * k, 0.0), scale(up, su * h * k)))

    end_offsets = {}
    for b in range(8):
        end_offsets[0, b] = tuple(x - y for x, y in zip(m.vertices[hole_top[b]], section(0.0, b)))
        end_offsets[1, b] = tuple(x - y for x, y in zip(m.vertices[hole_bottom[(6 - b) % 8]],
                                                        section(math.pi, b)))

    def tube(i, j):
        if i == 0:
            return hole_top[j]
        if i == 2 * segments:
            return hole_bottom[(6 - j) % 8]
        phi = math.pi * i / (2 * segments)
        p = section(phi, j)
        step = math.pi / segments
        for end, distance in ((0, phi), (1, math.pi - phi)):
            weight = max(0.0, 1.0 - distance / step) ** 2  # the holes are not planar: blend
            p = add(p, scale(end_offsets[end, j], weight))
        return p

    # Tube lattice: row i along the tube (ring i/2), column j around it (slot j); a tube
    # frame's first side (P1 P2 P3) at ring 0 is the upper hole's side through slots
    # 2k, 2k+1, 2k+2, so the tube's end edges are exactly the removed frame's edges.
    tube_lat = m.lattice(segments, 4, tube)
    m.grid_frames(tube_lat, segments, 4)
    return m


def basket():
    m = Model("basket", "A basket (seed Figs. 3 and 11): a bowl with a closed bottom and an "
              "open rim, and a strap arching from one side of the rim to the other; the "
              "strap's u runs along the strap where the bowl's runs around the rim, and the "
              "two joint frames set a1.")
    rim_radius, rim_height = 1.25, 1.0
    base = 0.85
    wall = [(base + (rim_radius - base) * t + 0.08 * math.sin(math.pi * t), rim_height * t)
            for t in (k / 6 for k in range(7))]
    rings = [(0.0, -0.04), (base / 2, -0.025)] + wall  # a slightly domed-in base
    # Columns 0 and 4, where the strap meets the rim, are narrower than the others.
    strap_angle = 24.0
    side = (360.0 - 2 * strap_angle) / 6
    lat = revolution(m, rings, angles=column_angles([strap_angle] + [side] * 3 +
                                                    [strap_angle] + [side] * 3))
    rows = len(rings) // 2
    m.grid_frames(lat, rows, 8)
    top = len(rings) - 1

    # The strap: lattice (a along the strap, b across); b = 0, 1, 2 at the first end are
    # the rim vertices of column 0 (at -12°, 0°, 12°) and at the far end those of column 4
    # (192°, 180°, 168°), so the strap's first and last cross edges are rim edges.
    n = 6
    arch = 1.45
    corner_x = rim_radius * math.cos(math.radians(strap_angle / 2))
    corner_y = rim_radius * math.sin(math.radians(strap_angle / 2))

    def strap(b, a):
        if a == 0:
            return lat[top, b]
        if a == 2 * n:
            return lat[top, 10 - b]
        phi = math.pi * a / (2 * n)
        narrow = 1.0 - 0.2 * math.sin(phi) ** 2  # narrower over the top
        x = (rim_radius if b == 1 else corner_x) * math.cos(phi)
        y = (b - 1) * corner_y * narrow
        z = rim_height + arch * math.sin(phi)
        return (x, y, z)

    # Lattice row i = b runs across, column j = a along: the strap frames' u runs along
    # the strap while the bowl's u runs around it, so at each joint the shared rim edge
    # is a u-side of the bowl's frame and a v-side of the strap's.
    strap_lat = m.lattice(1, n, strap, periodic=False)
    for k in range(n):
        joint = k in (0, n - 1)
        m.frame(strap_lat.frame(0, k), a1=(2, 2, 2) if joint else None,
                a2=(1, 1, 1) if joint else None)
    return m


def vase():
    m = Model("vase", "A vase of revolution: a closed flat bottom, a bulging body, a narrow "
              "neck and a flared lip, 8 columns around.")
    base = 0.55
    body = [(base, 0.0), (0.85, 0.3), (1.05, 0.85), (0.92, 1.4), (0.55, 1.9), (0.4, 2.25),
            (0.44, 2.55), (0.62, 2.8), (0.78, 2.9)]
    rings = [(0.0, 0.0), (base / 2, 0.0)] + profile([(body, 7)])
    lat = revolution(m, rings)
    m.grid_frames(lat, len(rings) // 2, 8)
    return m


def hat():
    m = Model("hat", "A hat: a domed crown closed at the top, a band and a wide brim "
              "(a flat annulus of two rows curling up at the edge), 8 columns around.")
    crown = [(0.0, 1.05), (0.3, 1.03), (0.52, 0.97), (0.6, 0.8), (0.61, 0.55), (0.62, 0.3)]
    band = [(0.62, 0.3), (0.635, 0.15), (0.63, 0.0)]
    brim = [(0.63, 0.0), (1.0, 0.0), (1.3, 0.02), (1.5, 0.12)]
    rings = profile([(crown, 3, (1.0, 1.0, 1.0)), (band, 1), (brim, 2)])
    rings = [(r, z) if r > 1e-9 else (0.0, z) for r, z in rings]
    rings.reverse()  # from the brim's edge up to the top of the crown
    lat = revolution(m, rings)
    m.grid_frames(lat, len(rings) // 2, 8)
    return m


def dress():
    m = Model("dress", "A dress: an oval bodice narrowing at the waist, a flaring skirt whose "
              "hem waves in eight folds, open at the hem and neckline, and two shoulder "
              "straps whose ends are neckline edges (branches).")
    # (z, x radius, y radius) from the hem up to the neckline; the front faces -y.
    keys = [(0.0, 0.95, 0.88), (0.4, 0.66, 0.56), (0.8, 0.45, 0.33), (1.05, 0.34, 0.25),
            (1.4, 0.44, 0.31), (1.7, 0.40, 0.27)]
    rows = 6
    levels = resample([k for k in keys], 2 * rows, [1.5, 1.5, 1.2, 1.2, 1.0, 1.0, 0.9, 0.9,
                                                     1.0, 1.0, 0.8, 0.8])
    cols = 8
    even = column_angles([360.0 / cols] * cols)
    # At the neckline the odd columns, where the straps start, are narrow; the columns
    # even out from the bust down to the waist.
    neck = column_angles([65.0, 25.0] * (cols // 2))

    def position(i, j):
        z, rx, ry = levels[i]
        t = min(1.0, max(0.0, (z - 1.05) / 0.5))
        a = even[j] + (neck[j] - even[j]) * t * t * (3 - 2 * t)
        fold = max(0.0, (0.8 - z) / 0.8) ** 1.6  # folds fade out towards the hips
        wave = 1.0 if j % 2 else -1.0  # frame corners in, middles out
        s = 1.0 + 0.07 * fold * wave
        return (rx * s * math.cos(a), ry * s * math.sin(a), z - 0.03 * fold * wave)

    lat = m.lattice(rows, cols, position)
    m.grid_frames(lat, rows, cols)
    top = 2 * rows

    # Shoulder straps: from a front neckline edge (columns 7 and 5) over the shoulder to
    # the back edge (columns 1 and 3); slot b pairs the inner corners, middles, outer corners.
    n = 3
    lift = 0.26
    for front, back in (((14, 15, 16), (4, 3, 2)), ((12, 11, 10), (6, 7, 8))):
        def strap(b, a, front=front, back=back):
            if a == 0:
                return lat[top, front[b]]
            if a == 2 * n:
                return lat[top, back[b]]
            t = a / (2 * n)
            p = lerp(m.vertices[lat[top, front[b]]], m.vertices[lat[top, back[b]]], t)
            return add(p, (0.0, 0.0, lift * math.sin(math.pi * t) ** 0.8))

        strap_lat = m.lattice(1, n, strap, periodic=False)
        for k in range(n):
            m.frame(strap_lat.frame(0, k))
    return m


def sculpt():
    m = Model("sculpt", "The seed's Fig. 8(d): one gently curved square patch sculpted by "
              "two local forces, raising a bump in each of two regions of the patch.")
    corners = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
    lift = 0.1
    points = []
    for k in range(4):
        a, b = corners[k], corners[(k + 1) % 4]
        points += [a, add(lerp(a, b, 0.5), (0, 0, lift))]
    indices = [m.vertex(p) for p in points]

    def force(bump, region):
        # Centre displacement of a region force: -f0 / (π² (a1/Lu² + a2/Lv²)).
        lu, lv = region[1] - region[0], region[3] - region[2]
        fz = -bump * math.pi ** 2 * (1 / lu ** 2 + 1 / lv ** 2)
        return {"f0": (0.0, 0.0, round(fz)), "region": region}

    m.frame(indices, forces=[force(0.15, (0.2, 0.45, 0.2, 0.45)),
                             force(0.15, (0.6, 0.9, 0.55, 0.8))])
    return m


def grid_forces():
    m = Model("grid-forces", "The seed's Fig. 9: a wavy sheet of 4 x 4 frames, listed in "
              "mixed orientations (rotated and mirrored), with one force pushing up the "
              "middle 2 x 2 frames.")
    n = 4

    def position(i, j):
        x, y = j / 2, i / 2
        return (x, y, 0.18 * math.sin(0.5 * math.pi * x) + 0.12 * math.sin(0.75 * math.pi * y))

    lat = m.lattice(n, n, position, periodic=False)
    middle = []
    for r in range(n):
        for c in range(n):
            v = lat.frame(r, c)
            variant = (3 * r + c) % 8  # every rotation, with and without mirroring
            if variant >= 4:
                v = [v[0]] + v[1:][::-1]  # mirrored: u and v swap
            turn = 2 * (variant % 4)
            v = v[turn:] + v[:turn]  # listed from another corner
            k = m.frame(v)
            if 1 <= r <= 2 and 1 <= c <= 2:
                middle.append(k)
    # A whole-frame force lifts each listed patch by f0 / (2π²) at its centre.
    m.forces.append({"f0": (0.0, 0.0, -6.0), "frames": middle})
    return m


MODELS = [mug, basket, vase, hat, dress, sculpt, grid_forces]


def write_models(named_texts, check_only, script):
    """Writes each (name, text) to examples/NAME.json, or with check_only compares the files
    with what would be written; returns the exit status (1: some file is stale). Shared by
    every example generator."""
    stale = []
    for name, text in named_texts:
        path = os.path.join(EXAMPLES, name + ".json")
        if check_only:
            try:
                with open(path) as f:
                    if f.read() != text:
                        stale.append(path)
            except FileNotFoundError:
                stale.append(path)
            continue
        os.makedirs(EXAMPLES, exist_ok=True)
        with open(path, "w") as f:
            f.write(text)
        print("%s -> %s" % (name, os.path.relpath(path, ROOT)))
    if stale:
        print("out of date: %s (run python3 scripts/%s)"
              % (", ".join(os.path.relpath(p, ROOT) for p in stale), script))
        return 1
    return 0


def run(main, errors, script):
    """Exits with main(sys.argv), or with 1 after 'SCRIPT: message' on stderr when it raises
    one of `errors`. Shared by every example generator."""
    try:
        sys.exit(main(sys.argv))
    except errors as error:
        print("%s: %s" % (script, error), file=sys.stderr)
        sys.exit(1)


def main(argv):
    if any(a in ("-h", "--help") for a in argv[1:]):
        print(__doc__.strip())
        return 0
    named_texts = []
    for make in MODELS:
        model = make()
        print(check(model))
        named_texts.append((model.name, model.json_text()))
    return write_models(named_texts, "--check" in argv[1:], "make_examples.py")


if __name__ == "__main__":
    run(main, ModelError, "make_examples")
