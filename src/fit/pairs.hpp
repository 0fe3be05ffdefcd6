// What one measurement of a fitted surface against its mesh gives (closest_pairs.cpp): the
// closest-point pairs both ways and the distances, which the fit's least squares (fit.cpp)
// and its a1, a2 step (shape_step.cpp) linearise around.
#pragma once

#include <cstdint>
#include <vector>

#include "pdesurf/rebuild.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf::fit {

/// A closest-point pair: the surface point S(frame, u, v) should be at `target`.
/// The squared distance counted is (S - target)ᵀ M (S - target) with
/// M = n nᵀ + tangentialWeight (I - n nᵀ): along the normal n in full, along the tangent
/// plane a little.
struct Pair {
  std::uint32_t frame = 0;
  double u = 0.0, v = 0.0;
  Vec3 target = Vec3::Zero();
  Vec3 normal = Vec3::Zero();  ///< unit, or zero where none is known (then M = I)
  double weight = 0.0;
  std::int64_t sample = -1;  ///< the surface sample (weights precomputed), or -1: a mesh vertex's
};

/// The pairs at one surface and the distances they measure.
struct Evaluation {
  VertexFrameSurface surface;  ///< the surface measured
  std::vector<Pair> pairs;
  FitMeasure measure;
  std::vector<std::uint32_t> foldsPerFrame;  ///< folded surface samples per frame
  /// +1 where most of the surface (by area) faces as the mesh does, -1 where it faces the
  /// other way: the orientation that folds are counted against.
  double orientation = 1.0;
  /// Per surface sample, the patch's derivatives S_u and S_v there (the fold-free term).
  std::vector<Vec3> du, dv;
  /// Per surface sample, the mesh triangle its closest point is on; per mesh vertex, the
  /// cell of the surface's sample grid its closest point is on: the next evaluation's
  /// hints (a query that starts from a near point prunes the tree at once).
  std::vector<std::uint32_t> meshTriangle, surfaceCell;
};

/// The points of the surface samples on every patch: a g × g grid in (u, v), each with the
/// trapezoid weight of the area it stands for (a border sample half a cell, a corner a
/// quarter).
struct SampleGrid {
  struct Point {
    double u, v, weight;
  };
  explicit SampleGrid(std::uint32_t perSide);
  std::uint32_t perSide;
  std::vector<Point> points;  ///< row by row: (i, j) at j × perSide + i
};

}  // namespace pdesurf::fit
