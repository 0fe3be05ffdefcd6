// The models of the B-spline PDE engine (seed 004) as files describe them: `"type":
// "bspline-pde"`, a control net, boundary curves with second rows, or the C1 blends of the
// seed's Examples 4 and 5; and their solutions. docs/model-format.md describes the file
// (bspline_pde_io.hpp writes it); docs/bspline-pde.md the mathematics.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "pdesurf/bspline_pde.hpp"
#include "pdesurf/error.hpp"
#include "pdesurf/mesh.hpp"

namespace pdesurf {

/// A cross-boundary derivative as written in a file: a curve of vectors (a B-spline curve,
/// or samples, linear between them, at `t` or at uniform parameters).
struct TangentCurve {
  BoundaryCurve vectors;
};

/// The second row (column) of a boundary as written: control points, or a tangent.
using SecondRowInput = std::variant<std::vector<Vec3>, TangentCurve>;

/// The boundary form as written (BSplineBoundary, with data instead of functions).
struct BoundaryInput {
  std::uint32_t nu = 3, nv = 3;
  BoundaryCurve uMin, uMax, vMin, vMax;
  SecondRowInput uMinSecond, vMinSecond;
};

/// The engine's boundary for a written one: tangent curves become tangent functions.
BSplineBoundary boundaryOf(const BoundaryInput& input, const BSplinePdeOptions& knots);

/// What a `"type": "bspline-pde"` file says: one of four forms.
struct BSplinePdeModel {
  enum class Form {
    Net,          ///< "net": rows of control points; rows 0, 1, n_u and columns 0, 1, n_v given
    Boundary,     ///< "boundary": four curves and the second row and column (or tangents)
    Blend,        ///< "blend": four curves, 2 × 2 C1 pieces (seed Example 4)
    ClosedBlend,  ///< "closed-blend": two closed curves, a C1 tube of 2 pieces (Example 5)
  };
  std::string name, description;
  Form form = Form::Net;
  BSplinePdeOptions knots;  ///< Net and Boundary; blends are clamped
  ControlNet net;           ///< Net: the inner points are NaN (the solve ignores them)
  BoundaryInput boundary;
  /// Blend: uMin, uMax, vMin, vMax; ClosedBlend: start, end.
  std::vector<BSplineCurve> curves;
  std::uint32_t blendN = 0;  ///< blends: the last control index of each piece
};

/// The member of the file that holds a form: "net", "boundary", "blend", "closed-blend".
const char* formName(BSplinePdeModel::Form form);

/// A B-spline PDE model, solved: one surface, or the pieces of a blend.
struct SolvedBSplinePde {
  std::vector<BSplineSurface> pieces;
  /// Piece k covers the global unit square at origin[k] (blends; {0, 0} for one surface).
  std::vector<std::array<std::uint32_t, 2>> origin;
  bool closedV = false;  ///< the closed blend: V = 2 is V = 0
  /// Blends: the measured constraint residual and C1 gap (C1Blend); nothing for one surface.
  std::optional<double> constraintResidual, c1Gap;
  std::vector<std::pair<std::string, double>> seamGaps;  ///< blends: C1Blend::seamGaps
};

/// Solves a parsed model. The engine's refusals (corners that do not meet, too few samples,
/// a curve that is not closed) become ModelError naming `source` and the model's part.
SolvedBSplinePde solve(const BSplinePdeModel& model, const std::string& source);

/// The mesh for options.resolution points per piece side (at least one segment per knot
/// span): one grid over all pieces, seam points shared (watertight), the closed blend closed
/// in V. patchIds hold the piece of each triangle.
Mesh tessellate(const SolvedBSplinePde& solved, const TessellateOptions& options = {});

}  // namespace pdesurf
