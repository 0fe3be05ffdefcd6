// Edits and transforms as the studio sends them (JSON), parsed and validated against a model
// with the paths of what is wrong: the edits a ModelSession (session.hpp) applies.
#pragma once

#include <array>
#include <string_view>
#include <vector>

#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"
#include "pdesurf/transform.hpp"

namespace pdesurf {

/// Parses and validates an edit of `model`, of any type, by its method
/// (SurfaceMethod::parseEdit): the one parse of every edit, for ModelSession::apply. The
/// ops each built-in method takes are parseFrameEdit's and parseShapeEdit's below. Throws
/// ModelError with source "edit" and the JSON path of the problem.
ModelEdit parseEdit(std::string_view json, const AnyModel& model);

/// Parses and validates an edit of a vertex-frame model (the method's own parse): JSON such
/// as
///   {"op": "move-vertex", "vertex": 3, "position": [0, 1, 2], "group": "drag-7"}
///   {"op": "move-vertices", "vertices": [3, 4], "positions": [[0, 1, 2], [1, 1, 2]]}
///   {"op": "set-parameters", "frames": [0, 2], "a1": [1, 1, 1], "a2": [2, 2, 2]}
///   {"op": "set-forces", "frame": 1, "forces": [{"f0": [0, 0, 1], "region": [0, 1, 0, 1]}]}
///   {"op": "set-shared-forces", "forces": [{"f0": [0, 0, -1], "frames": [0, 1]}]}
/// and the structure edits (session.hpp), sides as {"frame": k, "side": 0..3} (v = 0, u = 1,
/// v = 1, u = 0):
///   {"op": "extrude", "edges": [{"frame": 0, "side": 1}], "distance": 2}  (distance optional)
///   {"op": "add-frame", "corners": [3, 8, 9, 4]}
///   {"op": "delete-frames", "frames": [2]}
///   {"op": "split-frame", "frame": 0, "parts": 2, "across": "u"}  (or "parts": 4)
///   {"op": "split-frame", "frames": [0, 4], "parts": 4}  (several frames, one undo step)
///   {"op": "weld-vertices", "vertices": [keep, remove]}
///   {"op": "weld-edges", "edges": [{"frame": 0, "side": 3}, {"frame": 5, "side": 1}]}
///   {"op": "flip-frames", "frames": [1]}
///   {"op": "mirror-frames", "frames": [0, 1], "axis": "x"}  (copies across the plane x = 0;
///    "at": 1 across x = 1)
/// A structure edit's indices and shape are checked here; what it would make is checked when
/// the session applies it (restructure).
/// Everything the model parser would check of the result is checked (indices in range,
/// finite numbers, regions, forces that have a solution with the frame's a1 and a2).
/// Throws ModelError with source "edit" and the JSON path of the problem.
GroupedEdit parseFrameEdit(std::string_view json, const VertexFrameModel& model);

/// Parses and validates a shape edit of a spectral, cross-section or B-spline PDE model
/// (session.hpp: ShapeEdit; those methods' own parse), with an optional "group" as
/// parseFrameEdit's:
///   {"op": "move-curve-points", "curve": 2, "points": [0, 5], "positions": [[x, y, z], ...]}
///   {"op": "transform-curve", "curve": 1, "translate": [...], "rotate": {...}, "scale": s,
///    "center": [...], "from": "group-start"}  (the fields of parseTransform; "from", with a
///    "group": applied to the model before the group's first edit, a drag's absolute step)
///   {"op": "set-fourier", "curve": 2, "a0": [...], "a": [[...], ...], "b": [...]}  (any)
///   {"op": "set-operator", "operator": "ugail" | "fu", "N": 3, "a": 2, "modes": 6,
///    "remainder": true}  (any of them; chains: a, modes, remainder)
///   {"op": "set-spine", "spine": [{"u": [...], "moved": [[x, y, z], ...]}]}  (the file's field)
///   {"op": "move-spine-point", "index": 4, "position": [x, y, z]}  (a spine handle, absolute)
///   {"op": "add-section", "index": 2, "curve": {...}}  (curve optional between two sections)
///   {"op": "remove-section", "index": 2}
///   {"op": "move-control-points", "points": [[i, j], ...], "positions": [...]}  (net form)
/// "curve" is a condition's index (spectral), a section's (cross-sections) or a curve's name
/// (bspline-pde: "uMin", "uMax", "vMin", "vMax", "uMinSecond", "vMinSecond", "start", "end").
/// Throws ModelError with source "edit" and the JSON path of the problem; what the edit makes
/// is checked when the session applies it (the method's applyEdit).
GroupedShapeEdit parseShapeEdit(std::string_view json, const AnyModel& model);

/// Parses what a new model is (POST /api/new): {"kind": "single" | "grid" | "tube", "u": 3,
/// "v": 2, "size": 1, "name": "..."}, all but kind optional (NewModelOptions' defaults); other
/// fields are left to the caller. Throws ModelError with source "new model" and the JSON path.
NewModelOptions parseNewModel(std::string_view json);

/// Parses a whole-model transform as the studio sends it (POST /api/transform):
///   {"translate": [x, y, z],
///    "rotate": {"axis": [x, y, z], "degrees": d, "center": [x, y, z]},
///    "scale": s, "center": [x, y, z]}
/// All parts optional but at least one; applied in the order scale (about "center", s > 0),
/// rotate (about its own "center", else the top-level one), translate. "center" defaults to
/// the origin. Throws ModelError with source "transform" and the JSON path of the problem.
AffineMap parseTransform(std::string_view json);

/// Throws ModelError (source "transform") when transformModel(model, map) would be invalid:
/// a force turned onto a component whose a1/Lu² + a2/Lv² is 0 (per-component a1/a2). The
/// other types' solvers accept any valid map's result (transform.hpp).
void checkTransform(const VertexFrameModel& model, const AffineMap& map);
void checkTransform(const AnyModel& model, const AffineMap& map);

/// A question about the points of one patch (the studio's POST /api/patch-uv and
/// /api/patch-points: forces placed on the surface):
///   {"frame": k, "points": [[x, y, z], ...]}  the parameters of the nearest point of each
///   {"frame": k, "uv": [[u, v], ...]}          the points S(u, v), u and v in [0, 1]
/// At most kMaxPoints entries. Throws ModelError with source "patch query" and the JSON path.
struct PatchQuery {
  static constexpr std::size_t kMaxPoints = 4096;
  std::uint32_t frame = 0;
  std::vector<Vec3> points;               ///< when asked with "points"
  std::vector<std::array<double, 2>> uv;  ///< when asked with "uv"
};
PatchQuery parsePatchQuery(std::string_view json, std::size_t frames, bool withPoints);

}  // namespace pdesurf
