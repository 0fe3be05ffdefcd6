// The closest points between a vertex-frame surface and the mesh it is fitted to, both ways
// (CGAL AABB trees): the surface's samples to the mesh's triangles and the mesh's vertices to
// the surface, with the distances they measure and the samples folded over (docs/rebuild.md).
#pragma once

#include <cstdint>
#include <vector>

#include "fit/pairs.hpp"
#include "numerics/triangle_tree.hpp"
#include "pdesurf/mesh.hpp"

namespace pdesurf::fit {

/// The target mesh: its triangles with area in an AABB tree, its vertices as samples.
struct Target {
  detail::Triangles triangles;
  std::vector<Vec3> normals;  ///< unit normal per triangle
  /// Per triangle, bit k: its edge opposite corner k is on the mesh's boundary.
  std::vector<std::uint8_t> boundary;
  detail::Tree tree;
  std::vector<Vec3> samples;    ///< the vertices that triangles with area use
  std::vector<double> weights;  ///< a third of the area of their triangles, summing to 1
  double diagonal = 0.0;

  explicit Target(const Mesh& mesh);
};

/// Samples `surface` on `grid`, pairs the samples with the mesh and the mesh's
/// vertices with the surface, measures the distances and counts the folded samples.
/// The closest points are found in parallel, each into its own slot, and summed in order
/// afterwards: the same result for any number of threads. With `hints` (the evaluation of
/// a surface near this one, with the same layout) each query starts from the triangle its
/// closest point was on there: the same closest points, found sooner.
Evaluation closestPairs(VertexFrameSurface surface, const SampleGrid& grid, const Target& target,
                        const Evaluation* hints = nullptr);

}  // namespace pdesurf::fit
