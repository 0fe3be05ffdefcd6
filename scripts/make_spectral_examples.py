#!/usr/bin/env python3
"""Generates the spectral and cross-section example models of issue 4 in examples/.

Usage, from the repository root:

    python3 scripts/make_spectral_examples.py [--check] [--pdesurf PATH] [--regions DIR]

Standard library only and deterministic: the same files come out every run.

  shell.json           the sea shell, order 12 (seed 003 eqs. 26-28, Fig. 3)
  klein-bottle.json    the Klein bottle, order 40 (seed 003 eqs. 29-31, Fig. 4)
  membrane.json        the membrane with derivative curves, order 8 (seed 003 Figs. 5-6,
                       eqs. 32-35)
  vase-sections.json   a fluted vase from 12 planar cross sections given as points
                       (cross-sections model, the global chain: C4 at the sections)
  elephant-leg.json    a leg and the trunk of CGAL's elephant.off (Debian libcgal-demo),
  elephant-trunk.json  rebuilt by `pdesurf rebuild --as cross-sections` (25 sections)

The elephant models need the CLI (PATH from --pdesurf, else $PDESURF, else build/pdesurf)
and scripts/cgal_data finds the mesh. The part of the mesh each one rebuilds is also
written as an OBJ (default out/, --regions) so that `pdesurf compare` can measure the
distance both ways (docs/examples.md).

With --check nothing is written: the files on disk are compared with what would be.
"""

import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_examples import run, write_models  # noqa: E402  (one writer for every generator)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TWO_PI = 2.0 * math.pi


# ---------------------------------------------------------------------------------------
# Writing

def number(x, digits):
    """JSON text of a number with `digits` significant digits, no negative zero."""
    if abs(x) < 1e-13:
        return "0"
    text = format(x, ".%dg" % digits)
    value = float(text)
    if value == int(value) and abs(value) < 1e15:
        return str(int(value))
    return text


def dump(value, digits, indent=0):
    """JSON with objects indented, arrays of numbers on one line and arrays of points one
    point per line."""
    pad = "  " * indent
    if isinstance(value, dict):
        items = ['%s  %s: %s' % (pad, json.dumps(k), dump(v, digits, indent + 1))
                 for k, v in value.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(value, (list, tuple)):
        if all(isinstance(x, (int, float)) for x in value):
            return "[" + ", ".join(number(x, digits) for x in value) + "]"
        if all(isinstance(x, (list, tuple)) and all(isinstance(y, (int, float)) for y in x)
               for x in value):
            rows = [pad + "  " + dump(x, digits, indent + 1) for x in value]
            return "[\n" + ",\n".join(rows) + "\n" + pad + "]"
        rows = [pad + "  " + dump(x, digits, indent + 1) for x in value]
        return "[\n" + ",\n".join(rows) + "\n" + pad + "]"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return number(value, digits)
    return json.dumps(value, ensure_ascii=False)


def fourier(a0, modes):
    """A Fourier curve: a0 and {n: (a_n, b_n)} (n ≥ 1; missing modes are zero)."""
    top = max(modes) if modes else 0
    zero = (0.0, 0.0, 0.0)
    return {"fourier": {"a0": list(a0),
                        "a": [list(modes.get(n, (zero, zero))[0]) for n in range(1, top + 1)],
                        "b": [list(modes.get(n, (zero, zero))[1]) for n in range(1, top + 1)]}}


def sampled(f, count):
    """count points f(v_j), v_j = 2π j / count."""
    return [f(TWO_PI * j / count) for j in range(count)]


# ---------------------------------------------------------------------------------------
# Seed 003: the sea shell (eqs. 26-28)

def shell():
    """Seed 003 prints, with α = 0.2, β = 1, γ = 0.1,

        x = α(1 - u/2π) cos 2u (1 + cos v) + γ cos 2u                 (26)
        y = β(1 - u/2π) sin 2u (1 + cos v) + γ sin 2u                 (27)
        z = γ u/2π + α(1 - v/2π) sin v                                (28)

    for "12 cross sectional ellipses along u ... with 0 ≤ u ≤ π". As printed, the roles of
    β and γ are swapped between (27) and (28), and (28) has v where u belongs: with β in (27) the
    tube is 5 times wider along y than along x (no shell is), γ = 0.1 lifts the whole
    shell by 0.05 per whorl while the tube is 0.4 wide (the whorls would overlap), and the factor
    (1 - v/2π) makes each section a lopsided teardrop, not an ellipse. These are the
    standard sea-shell equations (a = 0.2, b = 1, c = 0.1) with (α, β, γ) = (a, b, c);
    the intended ones, used here, are

        x = α(1 - u/2π) cos 2u (1 + cos v) + γ cos 2u
        y = α(1 - u/2π) sin 2u (1 + cos v) + γ sin 2u
        z = β u/2π + α(1 - u/2π) sin v

    Each section is then a circle of radius α(1 - u/2π) in the plane through the shell's
    axis at angle 2u. The printed range 0 ≤ u ≤ π is one whorl of that: a bent horn, not a
    shell, and the factor (1 - u/2π), which shrinks the tube to nothing at u = 2π, shows the
    intended range is 0 ≤ u ≤ 2π (the standard one): two whorls closing to the apex. The 12
    sections are at u_i = 2πi/11 (the last one the apex, a point), placed at i/11 along the
    patch; each is given by 48 points at uniform v (the seed took 300 points and fitted 6
    Fourier modes; these sections have modes 0 and 1 only)."""
    alpha, beta, gamma = 0.2, 1.0, 0.1
    conditions = []
    for i in range(12):
        s = TWO_PI * i / 11

        def point(v, s=s):
            w = alpha * (1 - s / TWO_PI)
            return [w * math.cos(2 * s) * (1 + math.cos(v)) + gamma * math.cos(2 * s),
                    w * math.sin(2 * s) * (1 + math.cos(v)) + gamma * math.sin(2 * s),
                    beta * s / TWO_PI + w * math.sin(v)]

        conditions.append({"u": i / 11, "derivative": 0, "curve": {"points": sampled(point, 48)}})
    return {"type": "spectral", "name": "shell",
            "description": "A sea shell as one order-12 PDE patch (Ugail N = 6) through 12 "
                           "circular sections of the sea-shell surface (two whorls to the "
                           "apex), seed 003 eqs. 26-28 (Fig. 3) with their misprints corrected.",
            "operator": "ugail", "N": 6, "modes": 6, "placement": "given",
            "parameterization": "uniform", "remainder": True, "conditions": conditions}


# ---------------------------------------------------------------------------------------
# Seed 003: the Klein bottle (eqs. 29-31)

def klein_bottle():
    """Seed 003 eqs. 29-31 with α = 6, β = 16, γ = 4(1 - cos(u)/2), u ∈ [0, 2π]:

        u < π:  x = α cos u (1 + sin u) + γ cos u cos v,   y = β sin u + γ sin u cos v
        u ≥ π:  x = α cos u (1 + sin u) + γ cos(v + π),    y = β sin u
                z = γ sin v

    These are the standard "bottle" Klein-bottle equations and are right as printed. Each
    section is a circle of radius γ (modes 0 and 1 in v), given here by its Fourier
    coefficients (the seed fitted 6 modes to 300 points of each; the fit is these
    coefficients). The first and last sections (u = 0, 2π) are the same circle run in
    opposite directions: the bottle's gluing.

    One choice differs from a literal reading of the seed, forced by the mathematics and
    checked numerically (docs/examples.md):

    * Placement. 40 sections at uniform u make the order-40 interpolant oscillate by 10^8
      between the sections (Runge's phenomenon: the mode-1 data have a kink at u = π, where
      the two branches of the equations meet, and the uniform-node interpolation of a
      39th-degree-like space amplifies it), although every condition is met to 1e-11. The
      sections are therefore taken at the Chebyshev-Lobatto points of the bottle's
      parameter, u_k = π (1 - cos(πk/39)), and placed at u_k / 2π along the patch: the same
      bottle, with an interpolant that stays on it.

    Ugail's a is the seed's default, a = N = 20: mode 1 (roots ±20 of multiplicity 20) is
    solved in quad precision (docs/spectral.md, "Precision")."""
    alpha, beta = 6.0, 16.0
    conditions = []
    for k in range(40):
        t = 0.5 * (1 - math.cos(math.pi * k / 39))  # Chebyshev-Lobatto in [0, 1]
        if k == 39:
            t = 1.0
        s = TWO_PI * t
        g = 4 * (1 - math.cos(s) / 2)
        centre = [alpha * math.cos(s) * (1 + math.sin(s)), beta * math.sin(s), 0.0]
        if s < math.pi:
            a1 = [g * math.cos(s), g * math.sin(s), 0.0]  # cos v
        else:
            a1 = [-g, 0.0, 0.0]  # cos(v + π) = -cos v
        b1 = [0.0, 0.0, g]  # sin v
        conditions.append({"u": t, "derivative": 0, "curve": fourier(centre, {1: (a1, b1)})})
    return {"type": "spectral", "name": "klein-bottle",
            "description": "The Klein bottle as one order-40 PDE patch (Ugail N = 20, a = 20) "
                           "through 40 circular sections of the bottle surface, seed 003 "
                           "eqs. 29-31 (Fig. 4), the sections at Chebyshev-Lobatto points.",
            "operator": "ugail", "N": 20, "modes": 6, "placement": "given",
            "remainder": True, "conditions": conditions}


# ---------------------------------------------------------------------------------------
# Seed 003: the membrane with derivative curves (Figs. 5-6, eqs. 32-35)

MEMBRANE_A = 2.0              # Ugail's a (the seed's default would be N = 4: see membrane())
MEMBRANE_U = (0.2, 0.8)       # u of p2 and p3
MEMBRANE_LOBES = (5, 0.15)    # lobes of the derivative curves and their relative depth
MEMBRANE_DT = (1, 2)          # depth multiples on d (d1, d2) and t (t1, t2)


def membrane():
    """Fig. 5 is a biharmonic membrane through four position curves p1..p4 (circles round
    the z axis here: a barrel-shaped vesicle open at both ends). Fig. 6 adds first and
    second u-derivative conditions at the u of p2 and p3, made from four more curves d1,
    t1, d2, t2 by the finite-difference formulas eqs. 32-35:

        ∂X/∂u  at p2 = α (d1 - p2)             ∂X/∂u  at p3 = β (p3 - d2)
        ∂²X/∂u² at p2 = γ (p2 - 2 d1 + t1)      ∂²X/∂u² at p3 = η (p3 - 2 d2 + t2)

    with α = β = 3 and γ = η = 9. d1 and t1 lie one and two "steps" above p2, d2 and t2
    below p3, and have 5 lobes (d2, t2 turned by 36°): the derivative curves put the lobes
    into the membrane next to p2 and p3 while it still passes through p1..p4 (the surface
    does not pass through d1, t1, d2, t2: seed §4.1). 8 conditions: order 8 (Ugail N = 4).

    Two choices keep the membrane a membrane. Derivative conditions at p2 and p3 leave the
    end strips [0, u2] and [u3, 1] held by one position curve each, and the lobe modes
    (4 and 6) solve (D² - a²n²)^4 A = 0 there: the part of the lobes the derivative curves
    ask for at p2 returns near p1 and p4 amplified, the more so the larger a n. With
    p2, p3 at u = 1/3, 2/3 and the seed's a = N = 4 the lobes reach over 10 times the membrane's
    radius near u = 1/12 (an independent 60-digit solve of such conditions agrees: the
    model, not the engine). So p2 and p3 sit at u = 0.2 and 0.8 and a = 2: the lobes then
    stay within 0.12 of the circles (end strips no larger than near p2, p3)."""
    def circle(r, z, lobes=0, depth=0.0, turn=0.0):
        # r(v) = r (1 + depth cos(k v + t)) round the z axis at height z, k = lobes, as
        # Fourier modes: x = r cos v + h [cos((k+1)v + t) + cos((k-1)v + t)],
        # y = r sin v + h [sin((k+1)v + t) - sin((k-1)v + t)], h = r depth / 2.
        modes = {1: ([r, 0, 0], [0, r, 0])}
        if lobes:
            h = 0.5 * r * depth
            ct, st = math.cos(turn), math.sin(turn)
            for n, s in ((lobes + 1, 1.0), (lobes - 1, -1.0)):
                # x: h[cos((k±1)v + t)] = h ct cos - h st sin
                # y: ±h[sin((k±1)v + t)] = ±h (st cos + ct sin)
                a = [h * ct, s * h * st, 0.0]
                b = [-h * st, s * h * ct, 0.0]
                if n in modes:
                    a0, b0 = modes[n]
                    a = [x + y for x, y in zip(a0, a)]
                    b = [x + y for x, y in zip(b0, b)]
                modes[n] = (a, b)
        return {"a0": [0.0, 0.0, z], "modes": modes}

    def curve(c):
        return fourier(c["a0"], c["modes"])

    def combine(weights):
        """Σ w_i c_i of circle() results (a linear combination of Fourier curves)."""
        a0 = [0.0, 0.0, 0.0]
        modes = {}
        for w, c in weights:
            a0 = [x + w * y for x, y in zip(a0, c["a0"])]
            for n, (a, b) in c["modes"].items():
                pa, pb = modes.get(n, ([0.0] * 3, [0.0] * 3))
                modes[n] = ([x + w * y for x, y in zip(pa, a)], [x + w * y for x, y in zip(pb, b)])
        return {"a0": a0, "modes": modes}

    # The Fig. 5 membrane: the circles of a smooth vesicle profile R(u), Z(u) at u = 0,
    # u2, u3, 1. The derivative curves are placed where the finite differences of that
    # profile put them (so that, without lobes, eqs. 32-35 give the profile's own
    # derivatives and the membrane stays smooth), then given 5 lobes: the lobes are what
    # the derivative conditions add (Fig. 6). Derivative curves far from these places make
    # the polynomial part of the solution (mode 0) overshoot in the end strips.
    def radius(u, k=0):
        w = [0.45 + 0.75 * math.sin(math.pi * u), 0.75 * math.pi * math.cos(math.pi * u),
             -0.75 * math.pi ** 2 * math.sin(math.pi * u)]
        return w[k]

    def height(u, k=0):
        return [2.0 * u, 2.0, 0.0][k]

    alpha = beta = 3.0
    gamma = eta = 9.0
    u2, u3 = MEMBRANE_U
    p1, p2, p3, p4 = (circle(radius(u), height(u)) for u in (0.0, u2, u3, 1.0))
    lobes, depth = MEMBRANE_LOBES
    # d1 = p2 + X_u / α,  t1 = 2 d1 - p2 + X_uu / γ  (eqs. 32, 34 solved for d1, t1)
    rd1 = radius(u2) + radius(u2, 1) / alpha
    zd1 = height(u2) + height(u2, 1) / alpha
    rt1 = 2 * rd1 - radius(u2) + radius(u2, 2) / gamma
    zt1 = 2 * zd1 - height(u2) + height(u2, 2) / gamma
    d1 = circle(rd1, zd1, lobes, depth * MEMBRANE_DT[0])
    t1 = circle(rt1, zt1, lobes, depth * MEMBRANE_DT[1])
    # d2 = p3 - X_u / β,  t2 = X_uu / η - p3 + 2 d2  (eqs. 33, 35), lobes turned by 36°:
    # cos(5(v - π/5)) = cos(5v - π).
    rd2 = radius(u3) - radius(u3, 1) / beta
    zd2 = height(u3) - height(u3, 1) / beta
    rt2 = radius(u3, 2) / eta - radius(u3) + 2 * rd2
    zt2 = height(u3, 2) / eta - height(u3) + 2 * zd2
    d2 = circle(rd2, zd2, lobes, depth * MEMBRANE_DT[0], math.pi)
    t2 = circle(rt2, zt2, lobes, depth * MEMBRANE_DT[1], math.pi)
    du1 = combine([(alpha, d1), (-alpha, p2)])
    du2 = combine([(beta, p3), (-beta, d2)])
    duu1 = combine([(gamma, p2), (-2 * gamma, d1), (gamma, t1)])
    duu2 = combine([(eta, p3), (-2 * eta, d2), (eta, t2)])
    conditions = [
        {"u": 0, "derivative": 0, "curve": curve(p1)},
        {"u": u2, "derivative": 0, "curve": curve(p2)},
        {"u": u2, "derivative": 1, "curve": curve(du1)},
        {"u": u2, "derivative": 2, "curve": curve(duu1)},
        {"u": u3, "derivative": 0, "curve": curve(p3)},
        {"u": u3, "derivative": 1, "curve": curve(du2)},
        {"u": u3, "derivative": 2, "curve": curve(duu2)},
        {"u": 1, "derivative": 0, "curve": curve(p4)},
    ]
    return {"type": "spectral", "name": "membrane",
            "description": "A fluid membrane (vesicle) through four position circles with "
                           "first and second derivative conditions at the middle two, made "
                           "from lobed curves by the finite differences of seed 003 "
                           "eqs. 32-35: an order-8 PDE patch (Ugail N = 4, Figs. 5-6).",
            "operator": "ugail", "N": 4, "a": MEMBRANE_A, "modes": 6, "placement": "given",
            "remainder": True, "conditions": conditions}


# ---------------------------------------------------------------------------------------
# Seed 002: a vase from planar cross sections given as points

def chain_spacing(count, length):
    """Positions of `count` sections over [0, length] for a c2 chain: equal gaps.

    The engine matches derivatives across a joint in the chain parameter s, in which curve
    i sits at s = i (src/spectral/chain.cpp, docs/spectral.md): a patch over q intervals
    has ∂s = ∂t / q, so a root over 5 intervals and patches over 3 meet at the same speed
    and equally spaced sections need nothing special."""
    return [length * i / (count - 1) for i in range(count)]


def vase_profile(z):
    """Radius and flute depth of the vase at height z ∈ [0, 2.4]: a wide foot, a narrow
    waist at z ≈ 1.4 and a flared mouth. The profile must vary slowly against the spacing
    of the sections: a c2 chain propagates the first and second derivatives of each patch
    into the next, so a profile that turns sharply between sections makes the later
    patches overshoot (docs/examples.md)."""
    return 0.6 + 0.3 * math.cos(2.2 * z), 0.05 + 0.03 * math.sin(1.3 * z)


def vase_sections():
    """12 horizontal sections of a fluted vase: a profile radius r(z) (foot, belly, neck,
    lip) times 1 + ε cos(6θ + φ), the flutes turning slowly (φ) up the vase. Each section
    is 90 points at uniform θ, so the chord-length v is not θ, and the 6 flutes put
    x and y modes 5 and 7 into each curve: with 6 Fourier modes the remainder carries
    mode 7 and the curves are still met exactly. Heights from chain_spacing (why there)."""
    curves = []
    for i, z in enumerate(chain_spacing(12, 2.4)):
        r, e = vase_profile(z)
        phase = 0.12 * i
        pts = []
        for j in range(90):
            t = TWO_PI * j / 90
            rho = r * (1 + e * math.cos(6 * t + phase))
            pts.append([rho * math.cos(t), rho * math.sin(t), z])
        curves.append({"points": pts})
    return {"type": "cross-sections", "name": "vase-sections",
            "description": "A fluted vase from 12 planar cross sections given as points (6 "
                           "flutes, turning up the vase), a global chain of sixth-order "
                           "patches (a = -1), C4 at the sections: a moved point stays a local "
                           "edit, where the seed's method 2 (c2) passes it on from patch to "
                           "patch.",
            "a": -1, "modes": 6, "method": "global", "parameterization": "chord-length",
            "remainder": True, "curves": curves}


# ---------------------------------------------------------------------------------------
# The elephant: rebuilt by `pdesurf rebuild --as cross-sections`

# The parts, found by slicing elephant.off (y up; extent y in [-0.5, 0.5]). The standing leg
# whose foot is at x = 0.12, z = -0.05 is one loop, with the other legs' loops beside it
# (--near picks it), from above its sole (y = -0.475) to below the belly (y = -0.31, where it
# merges with the body); it is rebuilt from y = -0.45 to -0.32. The raised trunk is the only
# loop of its planes from y = 0.30 (above the tusks and the head, where the planes cut two or
# three loops) to y = 0.48 (the tip); it leans by about 45° at y = 0.30 and curls over above
# y = 0.43, where horizontal planes cut it obliquely; below y = 0.34 a fold of the mesh gives
# its sections a flap. So it is rebuilt where it stands most upright, from y = 0.345 to 0.42
# (--track follows it plane by plane). 25 sections each: the global chain gets no worse with
# more sections (docs/rebuild.md measures 7 to 49).
ELEPHANT_PARTS = [
    {"name": "elephant-leg", "axis": "y", "range": (-0.45, -0.32), "count": 25,
     "near": (0.117, -0.4, -0.045), "track": False,
     "label": "The standing leg", "where": "foot at x = 0.12, z = -0.05; y = -0.45 to -0.32, "
     "from above the foot to below the belly"},
    {"name": "elephant-trunk", "axis": "y", "range": (0.345, 0.42), "count": 25,
     "near": (0.15, 0.345, 0.17), "track": True,
     "label": "The raised trunk", "where": "y = 0.345 to 0.42, where it stands most upright"},
]


def elephant_path():
    done = subprocess.run([os.path.join(ROOT, "scripts", "cgal_data"), "elephant.off"],
                          cwd=ROOT, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError("scripts/cgal_data elephant.off failed: " + done.stderr.strip())
    path = done.stdout.strip()
    return path if os.path.isabs(path) else os.path.join(ROOT, path)


def elephant_models(cli, regions, check_only):
    """Each part as `pdesurf rebuild` writes it (the part of the mesh it rebuilds goes to
    REGIONS/NAME-region.obj unless check_only), with its description."""
    mesh = elephant_path()
    models = []
    with tempfile.TemporaryDirectory() as tmp:
        for part in ELEPHANT_PARTS:
            model_path = os.path.join(tmp, part["name"] + ".json")
            region = os.path.join(regions if not check_only else tmp, part["name"] + "-region.obj")
            os.makedirs(os.path.dirname(region), exist_ok=True)
            args = [cli, "rebuild", mesh, "--as", "cross-sections", "--axis", part["axis"],
                    "--range", repr(part["range"][0]), repr(part["range"][1]),
                    "--count", str(part["count"]), "--near"] + [repr(x) for x in part["near"]]
            args += ["--track"] if part["track"] else []
            args += ["--name", part["name"], "-o", model_path, "--part", region,
                     "--samples", "20000"]
            done = subprocess.run(args, cwd=ROOT, capture_output=True, text=True)
            if done.returncode != 0:
                raise RuntimeError("%s failed: %s" % (" ".join(args), done.stderr.strip()))
            with open(model_path) as f:
                model = json.load(f)
            model["description"] = (
                "%s of CGAL's elephant.off (%s), rebuilt by pdesurf rebuild --as cross-sections "
                "from %d sections: a global C4 chain of sixth-order patches."
                % (part["label"], part["where"], part["count"]))
            models.append(model)
            if not check_only:
                print("%s: %s" % (part["name"], done.stdout.splitlines()[2].strip()))
    return models


# ---------------------------------------------------------------------------------------

def main(argv):
    if any(a in ("-h", "--help") for a in argv[1:]):
        print(__doc__.strip())
        return 0
    args = argv[1:]
    check_only = "--check" in args
    cli = os.environ.get("PDESURF") or os.path.join(ROOT, "build", "pdesurf")
    regions = os.path.join(ROOT, "out")
    if "--pdesurf" in args:
        cli = args[args.index("--pdesurf") + 1]
    if "--regions" in args:
        regions = os.path.abspath(args[args.index("--regions") + 1])
    if not os.path.isabs(cli):
        cli = os.path.abspath(cli)

    models = [(shell(), 12), (klein_bottle(), 12), (membrane(), 12), (vase_sections(), 8)]
    models += [(m, 9) for m in elephant_models(cli, regions, check_only)]
    return write_models([(m["name"], dump(m, digits) + "\n") for m, digits in models],
                        check_only, "make_spectral_examples.py")


if __name__ == "__main__":
    run(main, RuntimeError, "make_spectral_examples")
