// The vertices a TopologyError::Kind::MiddleVertexDiffers names: the file check (io) and the
// structure edits (session) report it, each in its own words.
#pragma once

#include <cstdint>

#include "pdesurf/vertex_frames.hpp"

namespace pdesurf::detail {

struct MiddleMismatch {
  std::uint32_t corner0 = 0, corner1 = 0;  ///< the side's two shared corners
  std::uint32_t middleFirst = 0;           ///< the middle vertex of error.first's side
  std::uint32_t middleSecond = 0;          ///< the middle vertex of error.second's side
};

inline MiddleMismatch middleMismatch(const VertexFrameModel& model, const TopologyError& error) {
  const auto sa = sideSlots(error.first.side), sb = sideSlots(error.second.side);
  const auto& fa = model.frames[error.first.frame].vertices;
  const auto& fb = model.frames[error.second.frame].vertices;
  return {fb[sb[0]], fb[sb[2]], fa[sa[1]], fb[sb[1]]};
}

}  // namespace pdesurf::detail
