// An automatic layout of vertex frames for any triangle mesh (closed, several boundary loops,
// handles, several components), adaptive to the mesh's curvature, and the search for the
// smallest one whose fitted model reaches a target RMS (docs/rebuild.md, "The automatic
// layout").
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "pdesurf/mesh.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/rebuild.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

/// How the simplified triangles become quads (each quad one frame).
enum class QuadConstruction {
  /// Every triangle split into three quads (its centroid and edge midpoints): 3 frames a
  /// triangle.
  SplitTriangles,
  /// Triangles paired across their shared edges into quads where the quad is convex and
  /// close to square (greedily, the best pairs first); then every quad split into four and
  /// every unpaired triangle into three: about 2 frames a triangle.
  PairTriangles,
};

struct AutoLayoutOptions {
  /// About this many frames (at least the fewest the mesh's topology allows).
  std::uint32_t frames = 200;
  /// Edges whose two triangles' normals differ by more than this angle (degrees) are creases
  /// and stay on frame edges (chains of them shorter than kMinCreaseChain of the diagonal
  /// are taken for noise and ignored). Boundary edges are always kept on frame edges.
  double creaseAngle = 60.0;
  /// Pairing makes the smaller model at equal RMS (docs/rebuild.md, "Split or pair").
  QuadConstruction construction = QuadConstruction::PairTriangles;
};

/// Crease chains shorter than this fraction of the bounding-box diagonal are taken for noise:
/// on a scan such as CGAL's lion-head, a 2 % bound kept 156 edges of its mane's grooves as
/// creases (they stalled the simplification at 57 triangles when 40 were asked for), 10 %
/// keeps 99 of them and the simplification reaches its target; a CAD part's creases
/// (fandisk_large.off) run longer.
inline constexpr double kMinCreaseChain = 0.1;

struct AutoLayout {
  /// Frames from quadLayout over `quads`, every vertex then put on the mesh (its closest
  /// point, where the mesh there faces as the frames round it do).
  VertexFrameModel model;
  PolygonMesh quads;                 ///< the quads the frames come from
  std::size_t baseTriangles = 0;     ///< triangles of the simplified mesh
  std::size_t components = 0;        ///< connected components of the mesh (one model for all)
  std::size_t creaseEdges = 0;       ///< crease and boundary edges of the input kept on edges
  std::size_t skippedTriangles = 0;  ///< triangles without area, left out
};

/// Simplifies `mesh` by CGAL's edge collapse with Garland–Heckbert plane quadrics to about
/// frames / 3 triangles (frames / 2 when pairing), creases and boundaries kept on edges, no
/// triangle turned over; makes quads (`construction`) and frames from them. The frames face
/// as the mesh's triangles do. Throws LayoutError naming `source` when the mesh has no
/// triangle with area, or a triangle cannot join the others (an edge of three triangles, a
/// vertex where two fans meet, triangles oriented against their neighbours).
AutoLayout autoLayout(const Mesh& mesh, const AutoLayoutOptions& options,
                      const std::string& source);

/// An automatic layout fitted and measured as `compare` measures it.
struct AutoFit {
  AutoLayout layout;
  FitResult fit;
  MeshDistance distance;  ///< the fitted model's tessellation against the mesh, both ways
  /// The same tessellation's normals against the mesh's: folded area, RMS deviation.
  NormalDeviation normals;
  /// Fitted with FitOptions::preventFolds on (the target search's second try of a layout
  /// whose plain fit folded).
  bool foldsPrevented = false;
  /// n where the layout is the disk's n × n grid (gridLayout), the target search's other
  /// candidate on a disk (TargetSearchOptions::tryGrid); 0 where it is the automatic layout
  /// (then `layout` tells how it was made).
  std::uint32_t grid = 0;
  /// The larger of the two one-way RMS values, relative to the diagonal.
  double worseRms() const;
};

/// The bound on a model's folded area (a share of its area, 0.1 %): the target
/// search accepts no layout whose fitted model folds more.
inline constexpr double kMaxFoldedArea = 1e-3;

/// The target search's default bound on a model's RMS normal deviation (degrees; AutoFit::
/// normals): a model that reaches the RMS with frames too coarse for the shape's bends (the
/// bear's ears flat flaps at 56 frames, 13.7°, where 118 frames deviate 7.8°) is refused. The
/// polygon peer of the benchmark deviates 7.4–9.6° on the scans at 0.2 % RMS (docs/rebuild.md,
/// "A target accuracy", says how this value was chosen).
inline constexpr double kMaxNormalDeviation = 10.0;

/// Where the fitted layouts reach the RMS within the fold bound but deviate more than the
/// normal bound, and a growth step lowers the deviation by less than this fraction per
/// doubling of the frames, the deviation has stopped falling (a scan's noise, or facets finer
/// than any smooth surface follows, set its floor): the search grows no further and takes the
/// layout before that step (TargetSearch::Stop::NormalsStalled). A smooth surface's deviation
/// falls as the frames' size, about 29 % a doubling.
inline constexpr double kNormalStall = 0.1;

/// Where layouts reach the target RMS but fold more than the bound or deviate more than the
/// normal bound, the search grows the frame count up to this factor past the first count that
/// reached the RMS (four doublings), then gives up the bounds (the lion head at 0.2 %: 73
/// frames reached the RMS, about 350 the fold bound too, before the Jacobian barrier;
/// three_peaks at 0.4 %: 23 frames the RMS, 103 folded 0.117 %).
inline constexpr double kGrowthPastRms = 16.0;

/// Past the first count that reached the RMS, the search grows no layout whose model would
/// take more than this many times the mesh's own storage (storageBytes of both, the layout's
/// before its fit): the bounds alone then ask for the frames, and a model several times the
/// mesh it stands for is no answer a user wants (CGAL's bones.off, 4,204 triangles in 26
/// components: 1,576 frames reach 0.4 % at 1.9× the mesh's bytes, and the folds held the
/// search until 8,816 frames, 10.5×, eight minutes, still folding 0.113 %). The largest layout
/// under the cap is tried before the search gives up the bounds (the femur's 2,350 frames,
/// 1.46×, within both; docs/rebuild.md, "A target accuracy").
inline constexpr double kMaxStorageRatio = 2.0;

/// ... but the cap is never below this many bytes (about 1,000 frames): a small mesh's
/// smallest layouts already outweigh it (the icosahedron's 12 frames take 3.9× its 382
/// bytes, and its 60 follow its facets exactly), and searching them costs little.
inline constexpr std::size_t kMinStorageCap = 128 * 1024;

/// No layout is asked for with fewer frames than this: the fewest a closed surface's
/// simplification can give (a tetrahedron's four triangles, three quads each).
inline constexpr std::uint32_t kFewestFrames = 12;

struct TargetSearchOptions {
  double targetRms = 0.002;  ///< both one-way RMS values at most this (of the diagonal)
  /// ... and the folded share of the model's area at most this (AutoFit::normals; 1 or
  /// more: no bound) ...
  double maxFoldedArea = kMaxFoldedArea;
  /// ... and the model's RMS normal deviation at most this many degrees (AutoFit::normals;
  /// 180: no bound).
  double maxNormalDeviation = kMaxNormalDeviation;
  AutoLayoutOptions layout;  ///< its `frames` is not read: the search sets it per trial
  /// The first count tried (at least kFewestFrames). The frame count grows from it by
  /// `growth` until the target is reached, then is bisected until the counts that miss and
  /// reach it are within `precision` of each other.
  std::uint32_t firstFrames = kFewestFrames;
  double growth = 2.0;
  double precision = 0.15;
  std::uint32_t maxFrames = 20000;  ///< no layout larger than this is tried
  /// Past the first count that reached the RMS, no layout whose model would take more than
  /// this many times the mesh's storage, and more than minStorageCap bytes, is tried
  /// (kMaxStorageRatio, kMinStorageCap; a ratio of 0: no such cap).
  double maxStorageRatio = kMaxStorageRatio;
  std::size_t minStorageCap = kMinStorageCap;
  /// On a disk (one boundary loop, one component), also try the n × n grid (gridLayout) for
  /// every n whose n² frames are fewer than the automatic layout's answer, and answer with the
  /// grid where it meets the target in fewer bytes (storageBytes): a smooth height field such
  /// as three_peaks is reached by a grid of fewer frames (docs/rebuild.md, "A target
  /// accuracy").
  bool tryGrid = true;
  /// Every trial's fit. Unlike a plain FitOptions, its normalWeight is kNormalWeight by
  /// default: the bounds above judge each trial, and with the term a smaller layout meets them
  /// (docs/rebuild.md, "Normals").
  FitOptions fit = [] {
    FitOptions f;
    f.normalWeight = kNormalWeight;
    return f;
  }();
  std::uint32_t resolution = 17;  ///< samples per patch side for the measure
  DistanceOptions distance;
  /// Called after each trial, with its frame request and result.
  std::function<void(std::uint32_t requested, const AutoFit&)> onTrial;
};

/// Which of a target's three criteria a fitted layout meets.
struct TargetCheck {
  bool rms = false;      ///< both one-way RMS values within the target
  bool folds = false;    ///< folded area within its bound
  bool normals = false;  ///< RMS normal deviation within its bound
  bool all() const { return rms && folds && normals; }
};

/// `fit` measured against the target of `options` (targetRms, maxFoldedArea,
/// maxNormalDeviation).
TargetCheck checkTarget(const AutoFit& fit, const TargetSearchOptions& options);

/// The most bytes a layout tried past the RMS may take, for a mesh of `meshBytes`
/// (storageBytes): maxStorageRatio times them, at least minStorageCap; infinite where
/// maxStorageRatio is 0 (no cap).
double storageCap(std::size_t meshBytes, const TargetSearchOptions& options);

struct TargetSearch {
  /// Why the frame count stopped growing.
  enum class Stop {
    Reached,         ///< a trial reached the target (then bisected)
    LayoutStopped,   ///< the mesh is simplified no further, or maxFrames was tried
    GrowthLimit,     ///< kGrowthPastRms times the first count that reached the RMS
    NormalsStalled,  ///< the normal deviation fell by less than kNormalStall a doubling
    StorageLimit,    ///< past the RMS, a larger layout's model would outweigh the mesh
                     ///< (maxStorageRatio times its storage)
  };
  /// The smallest trial that reached the target; else, where the normal deviation stalled,
  /// the trial before the stalling step (it reached the RMS within the fold bound, or that
  /// step's trial did); else the closest: one within the RMS and fold bounds of the least
  /// deviation, else one within the RMS of the least folded area, else the lowest RMS.
  AutoFit best;
  bool reached = false;  ///< `best` meets all three criteria (`met`)
  TargetCheck met;       ///< the criteria `best` meets
  Stop stop = Stop::Reached;
  /// The largest frame count tried that missed the target (0: none did). Where the target
  /// was reached, `best` was asked for at most (1 + precision) times this many frames.
  std::uint32_t missedBelow = 0;
  std::uint32_t trials = 0;  ///< fits made (a layout fitted plainly and guarded counts two)
};

/// One automatic layout of about `options.frames` frames, fitted and measured.
AutoFit fitAutoLayout(const Mesh& mesh, const AutoLayoutOptions& layout, const FitOptions& fit,
                      std::uint32_t resolution, const DistanceOptions& distance,
                      const std::string& source);

/// The smallest automatic layout whose fitted model reaches the target both ways, folds no
/// more than `options.maxFoldedArea` and deviates no more than `options.maxNormalDeviation`.
/// A trial of n frames fits the layout plainly and, where that reaches the RMS but folds
/// beyond the bound, again with FitOptions::preventFolds; it reaches the target if either fit
/// does. The count starts at `options.firstFrames` and grows by `growth` until a trial
/// reaches the target (or the layout stops growing: the mesh is simplified no more; or the
/// count passes kGrowthPastRms times the first that reached the RMS; or, past that count,
/// the next layout's model would take more than `maxStorageRatio` times the mesh's storage
/// (and `minStorageCap` bytes),
/// where the largest layout under that cap is the last tried; or a trial within the RMS and
/// fold bounds deviates less than kNormalStall a doubling below the trial before),
/// then is bisected geometrically between the largest count that missed and the smallest
/// that reached until they are within `precision`. The counts grown through depend on the
/// mesh alone, and a trial that reaches a target reaches every looser one, so a looser target
/// never gets a larger answer than a tighter one (in frames asked for; docs/rebuild.md, "A
/// target accuracy"). With `tryGrid`, on a disk, the n × n grids (n = 2, 3, 5, 8, 12, 17, …,
/// each the last times √2 rounded up, n² below the automatic answer's frames; the plain fit
/// alone) are tried until one meets the target, then bisected against the largest that
/// missed; the grid that meets it is the answer where its model takes fewer bytes.
TargetSearch searchTargetRms(const Mesh& mesh, const TargetSearchOptions& options,
                             const std::string& source);

}  // namespace pdesurf
