// The frame on a 3 × 3 block of a vertex lattice, shared by the grid and tube layouts: now
// pdesurf::latticeFrame (src/numerics/frame_lattice.hpp), which the studio's new models
// use too.
#pragma once

#include "numerics/frame_lattice.hpp"

namespace pdesurf::detail {

using pdesurf::latticeFrame;

}  // namespace pdesurf::detail
