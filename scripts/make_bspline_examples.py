#!/usr/bin/env python3
"""Generates the B-spline PDE example models of issue 5 (seed 004) in examples/.

Usage, from the repository root:

    python3 scripts/make_bspline_examples.py [--check]

Standard library only and deterministic: the same files come out every run.

  bspline-wave.json      Example 1: n = 5, uniform knots, a wavy square net (Fig. 1)
  bspline-catenoid.json  Example 2: n = 7, uniform knots, given points on the catenoid
                         (cosh t cos s, cosh t sin s, t), s in [0, pi], t in [0, acosh 2]
  bspline-spiral.json    Example 3: n = 10, clamped knots, given points on
                         (u sin u cos v, u cos u cos v, u sin v), (u, v) in [0, pi] x [0, 2 pi]
  bspline-blend.json     Example 4: four boundary curves, 2 x 2 pieces, C1 across the seams
  bspline-tube.json      Example 5: two closed curves, a closed C1 blend of 2 pieces
  bspline-dome.json      the boundary form: four sampled curves and two tangent functions

The seed prints none of its control points: the given points here are ours, of the kind of
its figures (docs/bspline-pde.md). With --check nothing is written: the files on disk are
compared with what would be.
"""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_examples import write_models  # noqa: E402  (one writer for every generator)
from make_spectral_examples import dump  # noqa: E402  (one JSON layout)



def given(i, j, n_u, n_v):
    """Seed condition 3.1: rows 0, 1, n_u and columns 0, 1, n_v are given."""
    return i <= 1 or i == n_u or j <= 1 or j == n_v


def net_model(name, description, knots, n_u, n_v, point):
    rows = [[list(point(i, j)) if given(i, j, n_u, n_v) else None for j in range(n_v + 1)]
            for i in range(n_u + 1)]
    return {"type": "bspline-pde", "name": name, "description": description, "knots": knots,
            "net": rows}


def clamped_greville(n):
    """The Greville abscissae of a clamped cubic knot vector with control points 0..n."""
    lam = 1.0 / (n - 2)
    knots = [0.0] * 4 + [k * lam for k in range(1, n - 2)] + [1.0] * 4
    return [(knots[i + 1] + knots[i + 2] + knots[i + 3]) / 3.0 for i in range(n + 1)]


def wave():
    return net_model(
        "bspline-wave",
        "Seed 004 Example 1: n = 5, uniform knots; rows 0, 1, 5 and columns 0, 1, 5 of a wavy "
        "square net are given, the 9 inner points solve the sixth-order PDE.",
        "uniform", 5, 5,
        lambda i, j: (i, j, math.sin(1.3 * i) * math.cos(0.9 * j) + 0.1 * i * j))


def catenoid():
    top = math.acosh(2.0)
    return net_model(
        "bspline-catenoid",
        "Seed 004 Example 2: n = 7, uniform knots; the given points lie on the catenoid "
        "(cosh t cos s, cosh t sin s, t), s in [0, pi], t in [0, acosh 2].",
        "uniform", 7, 7,
        lambda i, j: (math.cosh(top * j / 7) * math.cos(math.pi * i / 7),
                      math.cosh(top * j / 7) * math.sin(math.pi * i / 7), top * j / 7))


def spiral():
    g = clamped_greville(10)

    def point(i, j):
        u, v = math.pi * g[i], 2.0 * math.pi * g[j]
        return (u * math.sin(u) * math.cos(v), u * math.cos(u) * math.cos(v), u * math.sin(v))

    return net_model(
        "bspline-spiral",
        "Seed 004 Example 3: n = 10, clamped knots; the given points lie on (u sin u cos v, "
        "u cos u cos v, u sin v), (u, v) in [0, pi] x [0, 2 pi], at the Greville abscissae. Row "
        "0 is a pole. With only rows 0, 1, 10 given, u is a quadratic through them: the surface "
        "is far from the sampled one inside (docs/bspline-pde.md).",
        "clamped", 10, 10, point)


def bspline(points):
    return {"bspline": [list(p) for p in points]}


def blend():
    # A region over [0, 2]^2: two opposite sides arch up, the other two dip.
    def side(f, count=7):
        return bspline([f(k / (count - 1)) for k in range(count)])

    return {
        "type": "bspline-pde",
        "name": "bspline-blend",
        "description": "Seed 004 Example 4: four clamped boundary curves become 2 x 2 PDE "
                       "pieces, C1 across the seams; the points the seed leaves 'chosen' "
                       "minimise the thin-plate energy (docs/bspline-pde.md).",
        "blend": {
            "n": 6,
            "uMin": side(lambda t: (0.0, 2.0 * t, 0.6 * math.sin(math.pi * t))),
            "uMax": side(lambda t: (2.0, 2.0 * t, 0.6 * math.sin(math.pi * t))),
            "vMin": side(lambda t: (2.0 * t, 0.0, -0.3 * math.sin(math.pi * t))),
            "vMax": side(lambda t: (2.0 * t, 2.0, -0.3 * math.sin(math.pi * t))),
        },
    }


def tube():
    def ring(radius, z, dx, wobble, count):
        pts = []
        for k in range(count):
            a = 2.0 * math.pi * k / (count - 1)
            r = radius * (1.0 + wobble * math.cos(3.0 * a))
            pts.append((dx + r * math.cos(a), r * math.sin(a), z))
        pts[-1] = pts[0]  # closed: first point = last point
        return bspline(pts)

    return {
        "type": "bspline-pde",
        "name": "bspline-tube",
        "description": "Seed 004 Example 5: two closed curves (a circle and a three-lobed ring "
                       "above it) become a closed tube of 2 PDE pieces, C1 all around.",
        "closed-blend": {"n": 6, "start": ring(1.0, 0.0, 0.0, 0.0, 13),
                         "end": ring(0.6, 1.5, 0.3, 0.15, 19)},
    }


def dome():
    # x(u, v) = (2u, 2v, h(u, v)): four sampled sides and the tangents across u = 0 and v = 0.
    def h(u, v):
        return 0.5 * math.sin(math.pi * u) * math.sin(math.pi * v) + 0.2 * u

    def hu(u, v):
        return 0.5 * math.pi * math.cos(math.pi * u) * math.sin(math.pi * v) + 0.2

    def hv(u, v):
        return 0.5 * math.pi * math.sin(math.pi * u) * math.cos(math.pi * v)

    count = 17
    ts = [k / (count - 1) for k in range(count)]

    def samples(f):
        return {"points": [list(f(t)) for t in ts], "t": ts}

    return {
        "type": "bspline-pde",
        "name": "bspline-dome",
        "description": "The boundary form: four sampled boundary curves of a dome over "
                       "[0, 2]^2 and the cross-boundary tangents along u = 0 and v = 0; the "
                       "curves are fitted on clamped knots and the inner points solve the PDE.",
        "knots": "clamped",
        "boundary": {
            "nu": 8, "nv": 8,
            "uMin": samples(lambda t: (0.0, 2.0 * t, h(0.0, t))),
            "uMax": samples(lambda t: (2.0, 2.0 * t, h(1.0, t))),
            "vMin": samples(lambda t: (2.0 * t, 0.0, h(t, 0.0))),
            "vMax": samples(lambda t: (2.0 * t, 2.0, h(t, 1.0))),
            "uMinSecond": {"tangent": samples(lambda t: (2.0, 0.0, hu(0.0, t)))},
            "vMinSecond": {"tangent": samples(lambda t: (0.0, 2.0, hv(t, 0.0)))},
        },
    }


def main(argv):
    if any(a in ("-h", "--help") for a in argv[1:]):
        print(__doc__.strip())
        return 0
    models = [wave(), catenoid(), spiral(), blend(), tube(), dome()]
    return write_models([(m["name"], dump(m, 12) + "\n") for m in models], "--check" in argv[1:],
                        "make_bspline_examples.py")


if __name__ == "__main__":
    sys.exit(main(sys.argv))
