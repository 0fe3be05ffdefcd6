// The curve a shape edit names in a model (curveTarget): the parser of shape edits
// (src/io/shape_edit_io.cpp) checks that it exists, the session's shape edits
// (shape_edits.cpp) change it.
#pragma once

#include <string>
#include <vector>

#include "pdesurf/session.hpp"

namespace pdesurf::detail {

/// A curve of a model, to change: a spectral curve (points or Fourier) or a list of points,
/// with what its points are (positions, or vectors: a derivative condition, a tangent) and
/// its JSON path in the model file.
struct CurveTarget {
  CurveInput* input = nullptr;
  std::vector<Vec3>* points = nullptr;
  bool vectors = false;
  std::string path;
};

/// The curve `ref` names in `model` (a copy the edit changes); throws ModelError (source
/// "edit", at `path`) when the model has no such curve.
CurveTarget curveTarget(AnyModel& model, const CurveRef& ref, const std::string& path);

}  // namespace pdesurf::detail
