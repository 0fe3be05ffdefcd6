// The CGAL module's public API in one include (docs/library.md): mesh distances, layouts
// (grid, quad mesh, tube, automatic), the fit that rebuilds a mesh as a vertex-frame model, and
// rebuild(): a mesh rebuilt as a model of either kind, measured, in one call.
// Links pdesurf::cgal, which also lets readMesh read OFF and STL files. GPL-3.0-or-later, as
// the CGAL packages it compiles in (README.md, "Licence").
#pragma once

#include "pdesurf/pdesurf.hpp"

#include "pdesurf/auto_layout.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/mesh_rebuild.hpp"
#include "pdesurf/rebuild.hpp"
#include "pdesurf/tube_layout.hpp"
