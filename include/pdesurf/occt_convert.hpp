// pdesurf's B-spline surfaces as Open CASCADE geometry, for programs that use Open CASCADE
// themselves (the export, its tests, the benchmark against Geom_BSplineSurface::D1).
#pragma once

#include <Geom_BSplineSurface.hxx>
#include <TopoDS_Face.hxx>

#include "pdesurf/nurbs.hpp"

namespace pdesurf {

/// The same surface, exactly: distinct knots with multiplicities, the same poles.
Handle(Geom_BSplineSurface) toOcct(const NurbsSurface& surface);

/// A face on the surface's whole domain (degenerate boundary edges where a boundary row of
/// poles collapses to a point).
TopoDS_Face makeFace(const NurbsSurface& surface, double tolerance);

}  // namespace pdesurf
