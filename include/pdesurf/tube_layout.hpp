// A tube-like part of a mesh as a vertex-frame layout: rings from slicing (the aligned,
// least-twist sections of the cross-section rebuild) and sectors around them, closed round
// the tube (docs/rebuild.md, "A tube from rings and sectors").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pdesurf/mesh.hpp"
#include "pdesurf/mesh_slice.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

struct TubeLayoutOptions {
  std::uint32_t rings = 4;    ///< R: frames along the tube (2R + 1 slicing planes)
  std::uint32_t sectors = 8;  ///< S: frames around it (2S vertices on every ring)
  /// The planes and the loop each keeps, as `rebuild --as cross-sections` chooses them
  /// (axis, range, near, track); `count` is set to 2R + 1. Without a range: the mesh's
  /// extent along the axis (an open tube cut square at its ends).
  SliceOptions slice;
};

struct TubeLayout {
  /// Frame r·S + s spans rings 2r…2r+2 and points 2s…2s+2 (mod 2S) of them, u around the
  /// tube (counter-clockwise about the axis), v along it, so its normal S_u × S_v points out
  /// of the tube. Its vertices: the (R + 1) even rings' 2S points and the R odd rings' S
  /// points at even j, (R + 1)·2S + R·S in all, numbered as the frames first reach them.
  VertexFrameModel model;
  /// The part of the mesh between the end planes (sectionedPart): what the layout is fitted
  /// to and measured against.
  Mesh part;
  std::vector<MeshSection> sections;  ///< the 2R + 1 loops the rings come from
};

/// Slices the mesh by 2R + 1 planes, prepares the loops (prepareSections: oriented alike,
/// resampled by arc length, aligned with the least twist) at 2S points each, and lays the
/// R × S frames on them. Throws LayoutError naming `source` and the plane when a plane misses
/// the part, cuts several loops without near/track, or its loop cannot be prepared; and for
/// fewer than 1 ring or 3 sectors.
TubeLayout tubeLayout(const Mesh& mesh, const TubeLayoutOptions& options,
                      const std::string& source);

}  // namespace pdesurf
