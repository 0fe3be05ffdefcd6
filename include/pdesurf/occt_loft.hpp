// The peer a CAD user reaches for to rebuild a shape from cross sections: Open CASCADE's
// loft (BRepOffsetAPI_ThruSections) through periodic interpolating B-spline sections,
// meshed for measuring (docs/rebuild.md compares it with the global chain).
#pragma once

#include <span>

#include "pdesurf/error.hpp"
#include "pdesurf/mesh.hpp"
#include "pdesurf/spectral.hpp"

namespace pdesurf {

/// A smooth (not ruled) loft through the sections, each a periodic B-spline interpolating
/// its points in their order (prepared sections: aligned, equally spaced), triangulated by
/// BRepMesh with `deflection` as the largest distance of the mesh from the surface.
Mesh occtLoft(std::span<const SampledCurve> sections, double deflection);

}  // namespace pdesurf
