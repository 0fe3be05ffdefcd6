// The peers a PDE model is measured against at equal accuracy, under seed 000's protocol
// (§4.1, Table 1): a simplified polygon mesh and a least-squares bicubic B-spline surface,
// each the smallest of its kind whose RMS distance to the ground truth is no larger than a
// target (docs/accuracy-storage.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "pdesurf/error.hpp"
#include "pdesurf/mesh.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

/// The benchmark's accuracy of a model against its ground truth: sqrt((a² + b²) / 2) of the
/// two one-way RMS distances a (model to truth) and b (truth to model) that `compare` prints,
/// relative to the truth's bounding-box diagonal (the quantity the fit lowers, FitMeasure).
double accuracyRms(const MeshDistance& d);

/// accuracyRms of `model` against `truth` (the reference), sampled as `options` say.
double accuracyRms(const Mesh& model, const Mesh& truth, const DistanceOptions& options);

// ---------------------------------------------------------------------------------------
// Polygon: CGAL's edge-collapse simplification (Garland–Heckbert, plane quadrics).

struct PolygonPeer {
  Mesh mesh;              ///< the simplified truth
  double rms = 0.0;       ///< accuracyRms against the truth
  std::size_t bytes = 0;  ///< storageBytes(mesh)
  bool reached = false;   ///< rms <= the target (else: the truth itself, unsimplified)
  /// The next coarser simplification tried (one edge fewer kept): its RMS, which misses the
  /// target when `reached` (0 when nothing coarser was possible).
  double coarserRms = 0.0;
  std::uint32_t trials = 0;  ///< simplifications measured by the search
};

/// The truth simplified to the fewest edges whose RMS is no larger than `targetRms`: a
/// bisection on the stop predicate's edge count (the edges kept), each trial simplifying the
/// truth afresh. Throws InvalidArgument when the truth is not a manifold, oriented
/// triangle mesh (naming the triangle).
PolygonPeer simplifiedPeer(const Mesh& truth, double targetRms, const DistanceOptions& distance);

// ---------------------------------------------------------------------------------------
// NURBS: bicubic B-splines on uniform knots (clamped, or periodic where the layout closes),
// non-rational (every weight 1, so no weights are stored).

struct BSplineGrid {
  std::uint32_t nu = 4, nv = 4;           ///< control points along u and v
  bool closedU = false, closedV = false;  ///< periodic (closed round) in u, in v
  std::vector<Vec3> control;              ///< control[j * nu + i]
  /// The surface point at (u, v) in [0, 1]² (u, v wrap where closed).
  Vec3 position(double u, double v) const;
};

/// The surface as a (samplesU × samplesV)-vertex grid of triangles (closed directions welded).
Mesh tessellate(const BSplineGrid& surface, std::uint32_t samplesU, std::uint32_t samplesV);

/// Storage as the seed's Table 1 counts it: the two control-point counts, then x y z of every
/// control point, to six significant digits (knots are uniform, weights 1: neither stored).
std::size_t storageBytes(const BSplineGrid& surface);

/// A point of the truth with the layout parameter it belongs at, and its weight (the area it
/// stands for).
struct ParamSample {
  double u = 0.0, v = 0.0;
  Vec3 p = Vec3::Zero();
  double weight = 1.0;
};

/// Linear least squares: the control net of nu × nv points minimising Σ w |S(u,v) − p|² +
/// smoothness · (the net's squared second differences, scaled to the data's weight).
BSplineGrid fitBSpline(std::span<const ParamSample> samples, std::uint32_t nu, std::uint32_t nv,
                       bool closedU, bool closedV, double smoothness = 1e-7);

/// How a layout's frames tile its parameter square: frame r·columns + c covers
/// [c, c+1]/columns × [r, r+1]/rows in its own (u, v) (gridLayout, tubeLayout, a quad grid).
struct LayoutGrid {
  std::uint32_t columns = 1, rows = 1;
  bool closedU = false, closedV = false;
};

/// About `samples` points of the truth spread by area, each parameterised by its closest
/// point on the fitted vertex-frame surface (a patch (u, v) mapped through the grid): the
/// layout's parameterisation, which the B-spline peer is fitted on.
std::vector<ParamSample> layoutSamples(const VertexFrameSurface& surface, const LayoutGrid& grid,
                                       const Mesh& truth, std::size_t samples);

struct NurbsPeer {
  BSplineGrid surface;
  double rms = 0.0;
  std::size_t bytes = 0;
  bool reached = false;     ///< rms <= the target (else: the finest net tried)
  double coarserRms = 0.0;  ///< one span coarser along the longer side (misses when reached)
  std::uint32_t trials = 0;
};

/// The coarsest control net (spans along the layout's longer side, the other in proportion)
/// whose fitted surface's RMS is no larger than `targetRms`: doubling, then bisection, up to
/// `maxControlPoints`.
NurbsPeer bsplinePeer(std::span<const ParamSample> samples, const LayoutGrid& grid,
                      const Mesh& truth, double targetRms, const DistanceOptions& distance,
                      std::size_t maxControlPoints = 20000);

}  // namespace pdesurf
