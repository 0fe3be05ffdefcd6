// The Open CASCADE module's public API in one include (docs/library.md): STEP and IGES files
// of models, and Open CASCADE's loft through cross sections. Links pdesurf::occt.
// (<pdesurf/occt_convert.hpp> gives the patches as Open CASCADE geometry, for programs that
// use Open CASCADE themselves.)
#pragma once

#include "pdesurf/pdesurf.hpp"

#include "pdesurf/cad_export.hpp"
#include "pdesurf/occt_loft.hpp"
