// Rebuilding a mesh as a vertex-frame model: where the frames come from (layouts) and where
// their vertices go (fitting). docs/rebuild.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "pdesurf/error.hpp"
#include "pdesurf/mesh.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

// ---------------------------------------------------------------------------------------
// Layouts: a vertex-frame model whose vertices are a first guess, ready to be fitted.

/// A quad mesh as polygons: `faces[f]` lists the corners of face f (indices into points).
struct PolygonMesh {
  std::vector<Vec3> points;
  std::vector<std::vector<std::uint32_t>> faces;
};

/// Reads the polygons of an OBJ, OFF or PLY file as they are (quads stay quads), through
/// CGAL's polygon-soup readers. Throws LayoutError naming the file when it cannot be read.
PolygonMesh readPolygonMesh(const std::string& path);

/// One frame per quad: corners a b c d become P1 P3 P5 P7 (so the frame's normal
/// S_u × S_v turns as the quad does), and each edge gets one midpoint vertex, shared by
/// the two frames on it (P2, P4, P6, P8), placed at the edge's middle. The model lists the
/// quads' used vertices first (in file order), then one midpoint per edge: V + E vertices.
/// Throws LayoutError naming the face when one is not a quad (or repeats a corner) or an
/// edge is shared by more than two faces. `source` names the mesh in messages.
VertexFrameModel quadLayout(const PolygonMesh& quads, const std::string& source);

/// A U × V grid of frames laid on a mesh with one boundary loop (a disk), through a
/// parameterisation of the mesh onto the unit square (docs/rebuild.md).
struct GridLayoutOptions {
  std::uint32_t u = 8, v = 8;  ///< frames along each side of the square
};

/// Throws LayoutError (naming `source`) when the mesh is not a manifold disk.
VertexFrameModel gridLayout(const Mesh& disk, const GridLayoutOptions& options,
                            const std::string& source);

// ---------------------------------------------------------------------------------------
// Fitting: the vertex positions that put the surface on the mesh (a1, a2, forces fixed).

/// The distances of one fit iteration, measured between the surface samples and the mesh
/// both ways (the closest points the next step is built on), relative to the mesh's
/// bounding-box diagonal.
struct FitMeasure {
  double rmsToMesh = 0.0, meanToMesh = 0.0, maxToMesh = 0.0;     ///< surface samples -> mesh
  double rmsToModel = 0.0, meanToModel = 0.0, maxToModel = 0.0;  ///< mesh vertices -> surface
  /// Surface samples whose patch normal disagrees (cos < 0) with the mesh's normal at their
  /// closest point, against the orientation most of the samples agree on: folds.
  std::uint32_t foldedSamples = 0;
  std::uint32_t samples = 0;  ///< surface samples in all
  /// The share of the surface's area (the samples' area weights) that the folded samples
  /// stand for.
  double foldedArea = 0.0;
  /// sqrt((rmsToMesh² + rmsToModel²) / 2): the quantity each step may not increase.
  double rms() const;
};

struct FitIteration {
  std::uint32_t iteration = 0;  ///< 0: the start
  FitMeasure measure;
  double step = 0.0;  ///< the fraction of the least-squares step taken (1: all of it; 0: none)
  /// An iteration of the shape fit (FitOptions::fitShape): the least squares moved the
  /// forces with the vertices, and `parameterStep` is the fraction of the a1, a2 step taken
  /// (0: no fraction of it lowered the RMS).
  bool shape = false;
  double parameterStep = 0.0;
};

struct FitOptions {
  std::uint32_t maxIterations = 30;
  /// Stops when an iteration lowers the RMS by less than this fraction of it.
  double tolerance = 1e-3;
  /// Surface samples per patch side (≥ 3), a grid including the patch's borders; 0 chooses
  /// as many as make the surface samples about as many as the mesh's vertices, from 4 to 9
  /// (faster on large layouts, coarser: fewer than 9 samples a side raise the RMS the fit
  /// reaches on small ones, e.g. the elephant's leg as 4 × 9 frames).
  std::uint32_t samplesPerSide = 9;
  /// Weight of the smoothness term: the mean squared umbrella Laplacian of the vertex
  /// positions over the frame graph (each vertex against the mean of the vertices next to
  /// it along frame sides), against the mean squared distances (docs/rebuild.md).
  double smoothness = 1e-5;
  /// How much a pair's distance along the tangent plane counts against its distance along
  /// the normal, at the first iteration (1: the plain distance, point to point; small:
  /// nearly point to plane, Gauss–Newton on the true distances, much faster near the
  /// answer). It then adapts: a tenth after two full steps in a row, ten times after a
  /// shortened step or a step that failed whole and halved (src/fit/fit.cpp).
  /// Pairs whose foot is on a boundary count the plain distance.
  double tangentialWeight = 0.1;
  /// Halvings of a step the line search tries before it gives up.
  std::uint32_t maxHalvings = 8;
  /// Refuses steps that fold more surface samples over (FitMeasure::foldedSamples) than the
  /// current surface has (or 0.5 % of the samples, if more): where a step would, the
  /// vertices of the frames that fold more stay and the rest of the step is tried again.
  /// Off by default: it costs RMS (docs/rebuild.md, Limits).
  bool preventFolds = false;
  /// Weight λ of the fold-free term: λ diag² / A · Σ_k ∫∫ |S_v - ρ_k m × S_u|² du dv over
  /// every frame k, m the mesh's normal at the closest point (turned to the surface's
  /// orientation), ρ_k the frame's aspect (docs/rebuild.md, "Folds"). It keeps each patch's
  /// map from (u, v) to the surface close to a rotation and scale in the mesh's tangent
  /// plane, so its Jacobian cannot turn over. 0: off (the distances alone).
  double conformalWeight = 1e-5;
  /// Weight ν of the normal-alignment term: ν diag² · Σ_i w_i ((S_u·m)² / |S_u|² +
  /// (S_v·m)² / |S_v|²) over the surface samples, w_i a sample's share of the surface's
  /// area and m the mesh's normal at its closest point: the squared sines of the patch
  /// tangents' tilt out of the mesh's tangent plane, against the mean squared distances
  /// (docs/rebuild.md, "Normals"). It pulls the patches' tangents, and so their normals,
  /// towards the mesh's, most where the C0 seams between frames kink. 0: off (the default
  /// for now: it costs about 1.6× the fit's time; kNormalWeight is what the sweep chose).
  /// Finite, ≥ 0.
  double normalWeight = 0.0;
  /// After the vertex fit stops, fits the shape too, for up to maxIterations more
  /// iterations: a whole-frame sculpting force per frame (its f0 joins the vertices in the
  /// least squares: with a1, a2 fixed it only adds f0-proportional sin(πu) sin(πv) to the
  /// patch, 0 on its border, so C0 holds) and a1, a2 per frame (positive, in
  /// [kMinShapeParameter, kMaxShapeParameter]: a damped Gauss–Newton step in their
  /// logarithms on the same closest-point pairs, taken whole or halved only where it lowers
  /// the RMS). The start model may have no forces, and its a1, a2 must be in that range.
  /// docs/rebuild.md, "Fitting the shape".
  bool fitShape = false;
  /// Called with the start and after every accepted iteration (progress reports).
  std::function<void(const FitIteration&)> onIteration;
};

/// The normal-alignment weight the sweep of docs/rebuild.md ("Normals") chose: the RMS normal
/// deviation 8–18 % lower at 100 frames, the RMS at most 15 % higher (`--normal-weight 3e-4`).
inline constexpr double kNormalWeight = 3e-4;

/// The range --fit-shape keeps every a1 and a2 in (per component): positive, so every
/// force has a solution (a1 + a2 > 0) and the PDE stays elliptic; three decades either side
/// of the default 1, so that six significant digits keep them meaningful.
inline constexpr double kMinShapeParameter = 1e-3;
inline constexpr double kMaxShapeParameter = 1e3;

struct FitResult {
  VertexFrameModel model;
  std::vector<FitIteration> iterations;  ///< [0] is the start
  std::string stopReason;                ///< why the iterations stopped, in words
};

/// Moves the vertices of `start` (a layout) so that its surface lies on `target`: each
/// iteration pairs surface samples with their closest points on the mesh and mesh vertices
/// with their closest points on the surface, solves the linear least-squares problem in
/// the vertex positions (with the strips' cubic coefficients as the global solver sets
/// them), and takes the step, halved until the measured RMS does not increase. With
/// FitOptions::fitShape, then the forces and a1, a2 as well. Throws InvalidArgument
/// for a start model fitShape cannot take (forces already, a1 or a2 out of range).
FitResult fitVertexFrames(const VertexFrameModel& start, const Mesh& target,
                          const FitOptions& options = {});

}  // namespace pdesurf
