// The shape edits of B-spline PDE models (ShapeEditsOf<BSplinePdeModel>, shape_edits.hpp):
// their curves by file name, the shared corners (every curve end that sat where a moved end
// sat moves with it), a net's given control points ("move-control-points"), the handles;
// private to src/methods/.
#pragma once

#include "methods/shape_edits/shape_edits.hpp"

namespace pdesurf::detail {

/// The B-spline PDE method's shape edits (bspline_pde/edits.cpp).
extern const ShapeEditsOf<BSplinePdeModel> kBSplinePdeEdits;

}  // namespace pdesurf::detail
