"""pdesurf: PDE-based surface models in Python, numpy arrays in and out.

    import pdesurf
    model = pdesurf.load("examples/mug.json")
    mesh = model.solve().tessellate(resolution=17)
    mesh.vertices, mesh.triangles, mesh.normals      # (N, 3) float64, (M, 3) uint32, (N, 3)

Models (load, parse, vertex_frames) solve into surfaces (Model.solve) that tessellate,
sample and evaluate; meshes (read_mesh, Mesh) are compared, sliced and rebuilt as models
(compare, slice, rebuild); export writes STEP/IGES; Session edits a model with undo and redo.
Errors are pdesurf.Error and its subclasses; bad arguments raise ValueError naming them.
docs/python.md lists every function.
"""

import json as _json
import os as _os

import numpy as _np

from . import _core
from ._errors import (CadError, Error, FileError, InvalidArgumentError, LayoutError, LoftError,
                      MeshIOError, ModelError, SectionError, SliceError, ToleranceError)
from ._core import Mesh, Model, Session, Surface, get_threads, read_mesh, set_threads

__all__ = [
    "load", "parse", "vertex_frames", "read_mesh", "compare", "slice", "rebuild", "export",
    "polygon_peer",
    "set_threads", "get_threads", "release_mesh_memory", "Model", "Surface", "Mesh",
    "Session", "Error", "ModelError", "FileError", "MeshIOError", "LayoutError", "SliceError",
    "InvalidArgumentError", "SectionError", "CadError", "ToleranceError", "LoftError",
]

release_mesh_memory = _core.release_mesh_memory


def load(path):
    """Reads and checks a model file of any type -> Model.

    Raises ModelError (with .file, .path: the JSON path, .message) for an invalid model,
    FileError when the file cannot be read.
    """
    return _core.load_model(_os.fspath(path))


def parse(model, source="<string>"):
    """Parses and checks a model from JSON text or a dict -> Model; `source` names it in
    errors. Raises ModelError."""
    return _core.parse_model(model, source)


def _model_to_dict(self):
    """The model as a dict (the JSON of to_json, parsed)."""
    return _json.loads(self.to_json())


Model.to_dict = _model_to_dict


def _per_frame(value, name, frames):
    """a1 or a2 as (K, 3) rows: a number, a 3-vector or one row per frame."""
    try:
        array = _np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name}: expected a number, a 3-vector or (K, 3) rows") from None
    if array.ndim == 0:
        return _np.full((frames, 3), float(array))
    if array.shape == (3,):
        return _np.tile(array, (frames, 1))
    return array


def vertex_frames(vertices, frames, a1=1.0, a2=1.0, forces=(), shared_forces=(), name=""):
    """A vertex-frame model of arrays -> Model (docs/vertex-frames.md).

    vertices: (N, 3) positions. frames: (K, 8) vertex indices P1..P8 of each frame,
    counter-clockwise from (u, v) = (0, 0). a1, a2: a number, a 3-vector, or (K, 3) rows
    (per frame and component). forces: dicts {"frame": k, "f0": [x, y, z], "region":
    [u0, u1, v0, v1]} (region optional: the whole frame). shared_forces: dicts {"f0": [x, y,
    z], "frames": [k, ...]}. Raises ValueError naming an argument of the wrong shape, dtype,
    a value that is not finite or an index out of range, and ModelError for what the model
    file's parser refuses (a force without a solution, edges that disagree).
    """
    try:
        count = _np.shape(frames)[0] if _np.ndim(frames) == 2 else 0
    except ValueError:  # a ragged list
        raise ValueError("frames: expected (K, 8) vertex indices, got a ragged list") from None
    return _core.vertex_frame_model(vertices, frames, _per_frame(a1, "a1", count),
                                    _per_frame(a2, "a2", count), list(forces),
                                    list(shared_forces), name)


def _as_mesh(mesh, triangles=None, name="mesh"):
    """(Mesh, source) of a Mesh, a mesh file's path, or (vertices, triangles) arrays."""
    if isinstance(mesh, Mesh):
        if triangles is not None:
            raise ValueError("triangles: give them only with a vertex array")
        return mesh, "<mesh>"
    if isinstance(mesh, (str, _os.PathLike)):
        if triangles is not None:
            raise ValueError("triangles: give them only with a vertex array, not a file")
        path = _os.fspath(mesh)
        return read_mesh(path), path
    if triangles is None:
        raise ValueError(f"{name}: expected a Mesh, a mesh file or (vertices, triangles)")
    return Mesh(mesh, triangles), "<arrays>"


def _with_triangles(mesh, source):
    """The mesh, refused (as the CLI refuses it) when it has no triangle."""
    if mesh.triangle_count == 0:
        problem = "the mesh has no triangles"
        raise MeshIOError(f"{source}: {problem}", message=problem, file=source)
    return mesh


def _surface(model, resolution):
    """A Model or a Surface (solved with the defaults) tessellated, or a Mesh as it is."""
    if isinstance(model, Model):
        model = model.solve()
    if isinstance(model, Surface):
        return model.tessellate(resolution)
    mesh, source = _as_mesh(model, name="model")
    return _with_triangles(mesh, source)


def compare(model, mesh, resolution=17, samples=100000):
    """Metro-style distances between a model and a mesh, both ways, as `pdesurf compare
    --json` reports them -> dict with "diagonal" (the mesh's bounding-box diagonal),
    "model_to_mesh" and "mesh_to_model" (each: samples, rms, mean, max, their *_relative
    values divided by the diagonal, max_at, cover_radius), "hausdorff", "hausdorff_relative".

    model: a Model or Surface (tessellated at `resolution`, as build) or a Mesh; mesh: a
    Mesh, a mesh file or a (vertices, triangles) pair. The GIL is released meanwhile.
    """
    a = _surface(model, resolution)
    if isinstance(mesh, tuple) and len(mesh) == 2:
        mesh = Mesh(*mesh)
    b, source = _as_mesh(mesh, name="mesh")
    return _core.distance(a, _with_triangles(b, source), samples)


def slice(mesh, axis="z", count=10, range=None, near=None, track=False):  # noqa: A001
    """Cuts a mesh by `count` planes perpendicular to `axis` ("x", "y", "z") -> one dict a
    plane, as `pdesurf slice` prints them: index, coordinate, points ((n, 3), the closed
    loop counter-clockwise seen from the axis' positive side), length, area, centroid, loops.

    range: (a, b), planes from a to b (default: the mesh's extent cut into `count` slabs, a
    plane in the middle of each); near: keep the loop nearest this point; track: follow the
    part from plane to plane. Raises SliceError when a plane misses the mesh or cuts no
    closed loop.
    """
    if isinstance(mesh, tuple) and len(mesh) == 2:
        mesh = Mesh(*mesh)
    m, source = _as_mesh(mesh)
    return _core.slice_mesh(_with_triangles(m, source), axis, count, range, near, track)


def _fraction(value, name):
    """A fraction given as a number or a string ('0.002' or '0.2%')."""
    text = str(value).strip()
    scale = 100.0 if text.endswith("%") else 1.0
    try:
        x = float(text[:-1] if scale == 100.0 else text) / scale
    except ValueError:
        raise ValueError(f"{name}: expected a fraction (0.002) or a percentage ('0.2%'), "
                         f"got {value!r}") from None
    if not 0.0 < x < 1.0:
        raise ValueError(f"{name}: must be in (0, 1) of the diagonal, got {value!r}")
    return x


def _check_rebuild_options(options):
    """rebuild's keywords checked before any work, as `pdesurf rebuild` checks its options
    (the library's checkRebuildOptions; pdesurf.batch checks a collection's options with it
    before starting). Raises ValueError naming the option."""
    _core.check_rebuild_options(**options)


def rebuild(vertices, triangles=None, kind="vertex-frames", grid=None, layout=None, tube=None,
            iterations=30, tolerance=1e-3, smoothness=1e-5, fit_samples=9, prevent_folds=False,
            fold_weight=1e-5, normal_weight=None, fit_shape=False, frames=None, target_rms=None,
            max_normal_deviation=None, quads=None, crease_angle=None, resolution=17,
            samples=100000, axis="z", count=25, range=None, near=None, track=False, modes=8,
            points=128, a=1.0, ends="natural", exact=False, name=None, progress=None):
    """Rebuilds a mesh as a model, as `pdesurf rebuild` does (the same library call) ->
    (model, report).

    The mesh: (vertices, triangles) arrays, a Mesh, or a mesh file's path (then triangles is
    None). kind="vertex-frames" fits a layout of frames, one of grid=(U, V) (a grid on a
    disk-like mesh), layout=QUADS_FILE (one frame per quad) or tube=(RINGS, SECTORS) (the
    part chosen by axis, range, near, track), or, with none of them, the automatic layout of
    any mesh: about `frames` frames (default 200), or the smallest whose fitted model reaches
    target_rms both ways (a fraction of the diagonal, 0.002, or a string '0.2%') within
    0.1 % folded and max_normal_deviation degrees of RMS normal deviation (default 10; 180:
    no bound), shaped by quads ('pair' or 'split') and crease_angle (degrees, default 60);
    with iterations, tolerance, smoothness, fit_samples, prevent_folds, fold_weight
    (--fold-weight), normal_weight (--normal-weight; None: 3e-4 with target_rms, else 0),
    fit_shape as the CLI's options; progress(iteration), if given, is called after each
    iteration. kind="cross-sections" slices the mesh (axis, count, range,
    near, track), fits each section by `modes` Fourier modes over `points` points and joins
    them by the C4 chain (a, ends: "natural" or "estimated", exact). The options are checked
    as the CLI checks them: ValueError names the first that cannot be used.

    report: "rms" (model -> mesh, mesh -> model), "mean", "max": relative to the mesh's (or
    the part's) bounding-box diagonal; "distances" (as compare's), "normals" (folded_area,
    rms_degrees, reversed: the model's normals against the mesh's), "storage_bytes" (the
    seed's Table 1 convention); vertex frames also "frames", "iterations", "stop_reason";
    cross sections and tubes "part" (the mesh part measured against), cross sections
    "sections" and "part_storage_bytes"; the automatic layout "mesh_storage_bytes", and with
    target_rms "target_reached", "rms_reached", "folds_reached", "normals_reached", "trials"
    and "grid" (n where the answer is the disk's n × n grid; 0: the automatic layout).
    The GIL is released while fitting and measuring.
    """
    options = {key: value for key, value in locals().items()
               if key not in ("vertices", "triangles", "progress")}
    mesh, source = _as_mesh(vertices, triangles, name="vertices")
    return _core.rebuild(_with_triangles(mesh, source), source, progress, **options)


def polygon_peer(truth, target_rms, samples=100000):
    """The polygon peer of docs/accuracy-storage.md -> dict: the truth simplified by CGAL's
    edge collapses (Garland-Heckbert) to the fewest edges whose RMS, sqrt((a^2 + b^2) / 2) of
    the two one-way RMS distances relative to the truth's diagonal, is at most target_rms (a
    fraction >= 0 such as 0.002, or a string '0.2%'; 0 gives the truth itself).

    Keys: "mesh" (the simplified Mesh), "rms", "bytes" (its storage as the seed's Table 1
    counts it), "reached", "coarser_rms" (the next coarser trial's, which misses the target),
    "trials". truth: a Mesh, a mesh file or (vertices, triangles). Raises ValueError for a
    truth that is not a manifold, oriented triangle mesh. The GIL is released meanwhile.
    """
    if isinstance(truth, tuple) and len(truth) == 2:
        truth = Mesh(*truth)
    mesh, source = _as_mesh(truth, name="truth")
    target = _fraction(target_rms, "target_rms") if isinstance(target_rms, str) else target_rms
    return _core.polygon_peer(_with_triangles(mesh, source), target, samples)


def export(model, path, tolerance=None, max_spans=512):
    """Writes a model's patches as B-spline faces sewn into shells to STEP (.step, .stp) or
    IGES (.igs, .iges), as `pdesurf export` -> its report (faces, exact_faces,
    approximated_faces, tolerance, max_deviation, shells, free_edges, ...).

    model: a Model (solved with the defaults) or a Surface. tolerance: the largest deviation
    of an approximated face (default 1e-4 of the bounding-box diagonal, a goal: the finest fit
    tried is kept); given, a face that misses it raises ToleranceError. Raises CadError for an
    unknown extension or a failed write.
    """
    surface = model.solve() if isinstance(model, Model) else model
    return _core.export_cad(surface, _os.fspath(path), tolerance, max_spans)
