// The core's public API in one include (docs/library.md): models of every method loaded,
// parsed and written, solved, tessellated, sampled and measured; meshes read and written;
// editing sessions with undo. Links pdesurf::pdesurf. The optional modules have their own:
// <pdesurf/cgal.hpp> (pdesurf::cgal) and <pdesurf/occt.hpp> (pdesurf::occt).
#pragma once

// Geometry and meshes.
#include "pdesurf/error.hpp"
#include "pdesurf/geometry.hpp"
#include "pdesurf/mesh.hpp"

// The engines, one per method, and measurements of their surfaces.
#include "pdesurf/analysis.hpp"
#include "pdesurf/bspline_pde.hpp"
#include "pdesurf/bspline_pde_model.hpp"
#include "pdesurf/coons.hpp"
#include "pdesurf/mesh_slice.hpp"
#include "pdesurf/nurbs.hpp"
#include "pdesurf/section_rebuild.hpp"
#include "pdesurf/sections.hpp"
#include "pdesurf/spectral.hpp"
#include "pdesurf/spectral_model.hpp"
#include "pdesurf/vertex_frames.hpp"

// Any model: solved, tessellated, sampled, transformed.
#include "pdesurf/method.hpp"
#include "pdesurf/model.hpp"
#include "pdesurf/model_info.hpp"
#include "pdesurf/transform.hpp"

// Files and sessions.
#include "pdesurf/atomic_file.hpp"
#include "pdesurf/bspline_pde_io.hpp"
#include "pdesurf/edit_io.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"
#include "pdesurf/spectral_io.hpp"
