// Distances between triangle meshes, Metro-style (Cignoni et al. 1998): sample one mesh,
// find each sample's closest point on the other (CGAL AABB trees), both ways.
#pragma once

#include <cstddef>
#include <cstdint>

#include <Eigen/Core>

#include "pdesurf/mesh.hpp"

namespace pdesurf {

using Vec3 = Eigen::Vector3d;

/// How densely a mesh is sampled (Metro's vertex + face sampling). Triangle t is cut into
/// k_t² similar sub-triangles, sampled at their centroids, with
/// k_t = max(ceil(sqrt(samples · area_t / area)), ceil(sqrt(minSamplesPerTriangle))):
/// about `samples` points spread evenly by area, and every triangle sampled. The mesh's
/// vertices are sampled too.
struct DistanceOptions {
  std::size_t samples = 100000;             ///< face samples wanted on each mesh
  std::uint32_t minSamplesPerTriangle = 1;  ///< at least this many on every triangle
  /// Threads that query in parallel; 0: as many as oneTBB allows (every core unless the
  /// program limits it, as the CLI's --threads does). The result is the same for any count
  /// (fixed blocks of samples, merged in order).
  unsigned threads = 0;
};

/// Distances from the samples of one mesh to the closest points of the other.
struct OneWayDistance {
  std::size_t samples = 0;  ///< face samples and vertices
  /// Area-weighted over the face samples (each stands for area_t / k_t² of its triangle):
  /// quadratures of ∫ d dA / A and sqrt(∫ d² dA / A).
  double mean = 0.0, rms = 0.0;
  double max = 0.0;           ///< over every sample, vertices included
  Vec3 maxAt = Vec3::Zero();  ///< the sample where `max` is reached
  /// Every point of the sampled mesh lies within this distance of a face sample, and the
  /// distance to a mesh changes no faster than the point moves: the true largest distance
  /// lies in [max, max + coverRadius].
  double coverRadius = 0.0;
  double meanRelative = 0.0, rmsRelative = 0.0, maxRelative = 0.0;  ///< divided by diagonal
};

/// The two one-way distances between a mesh A and a reference mesh B.
struct MeshDistance {
  /// B's bounding-box diagonal: every relative value is divided by it (Metro's convention,
  /// with B the reference, e.g. the original scanned mesh). 0 leaves them absolute.
  double diagonal = 0.0;
  OneWayDistance aToB, bToA;
  double hausdorff = 0.0;  ///< max(aToB.max, bToA.max), the symmetric Hausdorff distance
  double hausdorffRelative = 0.0;
};

/// Samples A and measures to B, and the other way round. Triangles with collinear corners
/// stand for no area: they are neither sampled nor searched (their edges are their
/// neighbours'). Throws InvalidArgument when a mesh has no triangle with area.
MeshDistance meshDistance(const Mesh& a, const Mesh& b, const DistanceOptions& options = {});

/// How the normals of a mesh A (a model's tessellation, or a simplified polygon) agree with
/// those of a reference mesh B: each triangle of A with area, at its centroid, against the
/// normal of B's triangle closest to that centroid. A's overall orientation is taken by
/// majority (the sign of the area-weighted sum of the cosines), so a surface that faces
/// inwards consistently is not counted as folded; the angles are measured after that flip.
struct NormalDeviation {
  /// The share of A's area whose normal points against B's (cosine below 0 after the flip):
  /// folds, flaps and creases that B does not have.
  double foldedArea = 0.0;
  /// sqrt(Σ area θ² / Σ area), θ the angle between the normals (0° to 180°), in degrees.
  double rmsDegrees = 0.0;
  /// True where A's majority orientation is opposite to B's (A faces the other way).
  bool reversed = false;
};

/// Measures A's normals against B's (NormalDeviation); `threads` as in DistanceOptions.
/// Throws InvalidArgument when a mesh has no triangle with area.
NormalDeviation normalDeviation(const Mesh& a, const Mesh& b, unsigned threads = 0);

}  // namespace pdesurf
