// Edits and transforms as the studio sends them (JSON), parsed and validated against a model
// with the paths of what is wrong: the edits a ModelSession (session.hpp) applies.
#pragma once

#include <string_view>

#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"
#include "pdesurf/transform.hpp"

namespace pdesurf {

/// Parses and validates an edit against `model`: JSON such as
///   {"op": "move-vertex", "vertex": 3, "position": [0, 1, 2], "group": "drag-7"}
///   {"op": "set-parameters", "frames": [0, 2], "a1": [1, 1, 1], "a2": [2, 2, 2]}
///   {"op": "set-forces", "frame": 1, "forces": [{"f0": [0, 0, 1], "region": [0, 1, 0, 1]}]}
///   {"op": "set-shared-forces", "forces": [{"f0": [0, 0, -1], "frames": [0, 1]}]}
/// Everything the model parser would check of the result is checked (indices in range,
/// finite numbers, regions, forces that have a solution with the frame's a1 and a2).
/// Throws ModelError with source "edit" and the JSON path of the problem.
GroupedEdit parseEdit(std::string_view json, const VertexFrameModel& model);

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

}  // namespace pdesurf
