// The studio's binary mesh stream (GET /api/mesh, apps/studio/README.md): a whole mesh, or
// the delta of a mesh against the one the page has, little-endian. No HTTP here: the server
// sends these bytes, tests/studio/mesh_wire_test.cpp decodes them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "pdesurf/mesh.hpp"

namespace pdesurf::studio {

/// Runs of changed vertices closer than this many unchanged ones are merged: a few unchanged
/// vertices cost less than a run.
inline constexpr std::size_t kDeltaRunGap = 8;

/// A whole mesh: four uint32 (V, T, revision mod 2³², resolution), positions float32[3V],
/// normals float32[3V] (zeros when the mesh has none), indices uint32[3T].
std::string encodeMesh(const Mesh& mesh, std::uint64_t revision, std::uint32_t resolution);

/// The vertices whose position or normal differ between `from` and `to` (same topology), as
/// runs start, count, start, count, …; runs closer than kDeltaRunGap vertices are merged.
std::vector<std::uint32_t> changedRuns(const Mesh& from, const Mesh& to);

/// The delta of `to` against `from` (the page's mesh, same triangles): a header of five
/// uint32 (V, T, revision, resolution, run count R), the runs (start, count) as uint32[2R],
/// then the positions float32[3C] and normals float32[3C] of the C changed vertices, in run
/// order.
std::string encodeMeshDelta(const Mesh& from, const Mesh& to, std::uint64_t revision,
                            std::uint32_t resolution);

}  // namespace pdesurf::studio
