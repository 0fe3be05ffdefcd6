// Measurements of solved surfaces and models: continuity gaps, bounds, storage.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

/// Relative C0 gap (gap / bounding-box diagonal) that counts as exact continuity: each
/// coefficient is a small-integer combination of a few vertices, so two patches evaluate
/// a shared edge with a rounding error of a few tens of ulps of the model's size;
/// 1e-12 leaves several hundred times that as headroom and is far below anything visible.
constexpr double kC0RelativeTolerance = 1e-12;

struct Bounds {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());
  void add(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  double diagonal() const { return min.x() <= max.x() ? (max - min).norm() : 0.0; }
};

struct C0Report {
  double maxGap = 0.0;          ///< largest distance between two patches on a shared edge
  std::size_t sharedEdges = 0;  ///< edges run by two or more sides
  std::uint32_t worstEdge = 0;  ///< index into topology.edges of the largest gap
};

/// Samples every shared edge at `samples` parameters (ends included) on each side that
/// runs it and measures the distance to the first side's point at the same place.
C0Report measureC0Gap(const VertexFrameSurface& surface, std::uint32_t samples = 65);

/// Bounds of the surface: every patch sampled on a samples × samples grid and every force
/// region on a grid of its own, then the most extreme points refined by a local search to
/// about 1e-12 in parameter. Exact up to that refinement unless a patch hides an extreme
/// narrower than the sampling in a place no sample reaches (not a certified bound).
Bounds surfaceBounds(const VertexFrameSurface& surface, std::uint32_t samples = 17);

/// How many vertices that frames use stand exactly where another used vertex stands: frames
/// join only through shared indices, so such pairs are likely cracks a user meant to close.
std::size_t coincidentVertices(const VertexFrameModel& model);

/// The model's storage in bytes under the seed's Table 1 convention: every number written
/// to six significant digits as plain text, one space between numbers and a newline after
/// each record: a vertex (x y z), a frame (its 8 indices, a1, a2, then f0 and region of
/// each force), a shared force (f0 and its frame indices).
std::size_t storageBytes(const VertexFrameModel& model);

/// Mean and Gaussian curvature of the surface at a point, from its analytic first and second
/// derivatives. `mean` takes the sign of the studio's colouring: positive where the surface
/// bends away from its normal `n` (a sphere with outward normals: 1/R); K = 1/R² there.
struct Curvature {
  double mean = 0.0, gaussian = 0.0;
};

/// Below this (E G − F²)/(E + G)², the first fundamental form is taken as singular (a pole:
/// a frame's edge collapsed to a point) and the curvature is taken just inside the patch,
/// kPoleCurvatureStep toward its centre in each parameter.
constexpr double kSingularMetric = 1e-12;
constexpr double kPoleCurvatureStep = 1e-3;

/// The curvature of `patch` at (u, v) for the normal direction `n` (only its side counts).
Curvature patchCurvature(const VertexFramePatch& patch, double u, double v, const Vec3& n);

struct Mesh;
/// The analytic curvature at every vertex of `mesh`, the tessellation of `surface` at
/// `resolution` samples per patch side (with patch ids and normals): each vertex's
/// parameters on the patches of its triangles are those of the nearest sample of that
/// patch's grid; a vertex shared by several patches takes the mean of their values (the
/// surface is C0 there, the curvature may jump). Returns mean, Gaussian per vertex.
std::vector<float> meshCurvatures(const VertexFrameSurface& surface, const Mesh& mesh,
                                  std::uint32_t resolution);

struct CrossSectionModel;
/// The same convention for a polygon mesh (x y z per vertex, three indices per triangle:
/// the seed's polygon models) and a cross-section model (a and the mode count, each curve's
/// Fourier coefficients or points, the chain parameters when given).
std::size_t storageBytes(const Mesh& mesh);
std::size_t storageBytes(const CrossSectionModel& model);

}  // namespace pdesurf
