// The CGAL module's public API in one include (docs/library.md): mesh distances, layouts
// (grid, quad mesh, tube, automatic) and the fit that rebuilds a mesh as a vertex-frame model.
// Links pdesurf::cgal, which also lets readMesh read OFF and STL files. GPL-3.0-or-later, as
// the CGAL packages it compiles in (README.md, "Licence").
#pragma once

#include "pdesurf/pdesurf.hpp"

#include "pdesurf/auto_layout.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/rebuild.hpp"
#include "pdesurf/tube_layout.hpp"
