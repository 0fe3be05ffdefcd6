// The frame on a 3 × 3 block of a vertex lattice: the grid and tube layouts of rebuild
// (src/fit) and new models (src/session/structure.cpp) lay frames out with it. Private to the
// library; here, beside the kernels every layer builds with, because those two users sit in
// different layers (engines and io). Its users see vertex_frames.hpp (engines and above).
#pragma once

#include <cstdint>

#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

/// The frame whose P1 is lattice point (i, j), u running along i and v along j: P1..P8
/// counter-clockwise from (i, j) round the block's border (its centre is no vertex).
/// `at(i, j)` names a lattice point's vertex, called in P1..P8 order.
template <class At>
Frame latticeFrame(At&& at, std::uint32_t i, std::uint32_t j) {
  Frame f;
  f.vertices = {at(i, j),         at(i + 1, j),     at(i + 2, j), at(i + 2, j + 1),
                at(i + 2, j + 2), at(i + 1, j + 2), at(i, j + 2), at(i, j + 1)};
  return f;
}

}  // namespace pdesurf
