// Editing sessions on models of any type (ModelSession): edits, whole-model transforms, undo
// and redo, the solved model cached per revision. The studio server is a thin HTTP layer over
// this; nothing here knows about HTTP or files (edit_io.hpp parses and checks the edits).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "pdesurf/method.hpp"
#include "pdesurf/model.hpp"
#include "pdesurf/spectral.hpp"
#include "pdesurf/transform.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

/// Moves one vertex.
struct MoveVertex {
  std::uint32_t vertex = 0;
  Vec3 position = Vec3::Zero();
};
/// Moves several vertices at once (a selection dragged or offset): one edit, one undo step.
struct MoveVertices {
  std::vector<std::uint32_t> vertices;
  std::vector<Vec3> positions;  ///< one per vertex
};
/// Sets a1 and/or a2 of one or several frames.
struct SetParameters {
  std::vector<std::uint32_t> frames;
  std::optional<Vec3> a1, a2;
};
/// Replaces the forces (and their regions) of one frame.
struct SetFrameForces {
  std::uint32_t frame = 0;
  std::vector<FrameForce> forces;
};
/// Replaces the model's forces over whole frames (seed Fig. 9).
struct SetSharedForces {
  std::vector<SharedForce> forces;
};

/// Moves, turns or scales the whole model (transformModel): one undo step.
struct TransformModel {
  AffineMap map;
};

// Structure edits (src/session/structure.cpp): they change which vertices the frames use.
// Sides are named by frame and Side (0..3: v = 0, u = 1, v = 1, u = 0, the order of the
// studio's GET /api/boundaries). Each is refused with a ModelError (source "edit", the JSON
// path and the reason) when its result would not be a valid model, changing nothing.

/// New frames on boundary edges (one per edge), each its edge's frame moved across the edge
/// (sharing it, facing the same way, its u and v running on); the new frames of a chain of
/// edges share their walls, whose far corners move by the mean of their edges' offsets.
struct ExtrudeEdges {
  std::vector<FrameSide> edges;
  /// How far the new frames reach; 0: as far as each edge's frame is wide across it.
  double distance = 0.0;
};
/// A new frame on four corner vertices (its P1, P3, P5, P7, in turn round it); a side whose
/// corners already bound an edge takes that edge's middle vertex, so the frames share it. The
/// corners are taken in reverse when that orients the frame as its neighbours.
struct AddFrame {
  std::array<std::uint32_t, 4> corners{};
};
/// Removes frames; vertices only they used go too (indices above them move down).
struct DeleteFrames {
  std::vector<std::uint32_t> frames;
};
/// Splits frames into 2 (across u or v) or 4 (2 × 2), with new vertices on the current
/// surface. Each cut runs on through the neighbours across the edges it crosses (a loop cut),
/// so edges stay shared whole and no vertex is left that no frame uses; frames cut by several
/// of the given frames' loops are cut once in each direction.
struct SplitFrame {
  std::vector<std::uint32_t> frames;  ///< at least one, each once
  bool acrossU = true;                ///< cut at u = 1/2
  bool acrossV = false;               ///< cut at v = 1/2
};
/// Merges vertex `remove` into `keep` (which moves half way to it).
struct WeldVertices {
  std::uint32_t keep = 0, remove = 0;
};
/// Merges two boundary edges (closing a tube): their vertices paired so that the frames stay
/// consistently oriented, each pair kept as its lower index, moved half way.
struct WeldEdges {
  FrameSide first, second;
};
/// Reverses the u direction of frames (P1..P8 mirrored, force regions with them).
struct FlipFrames {
  std::vector<std::uint32_t> frames;
};

/// Copies frames across the plane where coordinate `axis` (0: x, 1: y, 2: z) is `at` (0: the
/// plane through the origin; the studio's plane through the model's centre sets it): each
/// copy's vertices mirrored, its u reversed (so it faces as its original's neighbours do), its
/// forces' f0 mirrored. Vertices on the plane (within kMirrorPlaneTolerance of the model's
/// bounding-box diagonal) are not copied: the copies share them, so the seam is welded.
struct MirrorFrames {
  std::vector<std::uint32_t> frames;
  int axis = 0;
  double at = 0.0;
  static constexpr double kMirrorPlaneTolerance = 1e-6;
};

/// One change to a model. MoveVertex, SetParameters and the forces keep the frame structure
/// (the session's topology); the structure edits make a new one.
using Edit = std::variant<MoveVertex, MoveVertices, SetParameters, SetFrameForces, SetSharedForces,
                          TransformModel, ExtrudeEdges, AddFrame, DeleteFrames, SplitFrame,
                          WeldVertices, WeldEdges, FlipFrames, MirrorFrames>;

/// True for the edits that change which vertices the frames use.
bool changesStructure(const Edit& edit);

/// The model after a structure edit. `surface` is `model` solved (SplitFrame places its new
/// vertices on it). Throws ModelError (source "edit") with the reason when the result would
/// not be a valid model: a side that is not on the boundary, a frame that would use a vertex
/// twice, an edge of three frames, anything parseVertexFrameModel refuses.
VertexFrameModel restructure(const VertexFrameModel& model, const FrameTopology& topology,
                             const VertexFrameSurface& surface, const Edit& edit);

/// The parameters (u, v) in [0, 1]² of the point of `patch` nearest `point`: a grid of
/// kNearestGrid² samples finds the basin, then projected Gauss-Newton steps refine it (the
/// studio maps points picked on the surface mesh to parameters: force regions drawn by hand).
std::array<double, 2> nearestParameters(const VertexFramePatch& patch, const Vec3& point);

/// A starter vertex-frame model on a lattice: one frame, a grid of u × v frames, or a tube
/// of u frames round the z axis and v along it; square frames of side `size` in z = 0 (the
/// grid) or round z (the tube, of circumference u × size). (edit_io.hpp: parseNewModel reads
/// these options from JSON, as the studio's "new model" sends them.)
struct NewModelOptions {
  enum class Kind { Single, Grid, Tube } kind = Kind::Single;
  std::uint32_t u = 1, v = 1;
  double size = 1.0;
  std::string name = "new model";
  /// At most this many frames each way.
  static constexpr std::uint32_t kMaxFrames = 64;
};
/// The new model; throws ModelError (source "new model") for counts out of range (a tube
/// needs at least 3 frames round) or a size that is not finite and above 0.
VertexFrameModel newFrameModel(const NewModelOptions& options);

/// An edit as the studio sends it, with an optional group: consecutive edits of one
/// non-empty group (the moves of one drag, the steps of one slider gesture) undo as one.
struct GroupedEdit {
  Edit edit;
  std::string group;
};

// Edits of spectral, cross-section and B-spline PDE models (ShapeEdit: parsed and applied by
// their methods: src/methods/shape_edits/ and each method's folder). Each names what it changes as
// the model file does; the method checks the result as the file parser would and solves it,
// refusing the edit (a ModelError with the reason, the session unchanged) when either fails.

// The curves they name: CurveRef (method.hpp).
/// Moves points of a curve given as points (a B-spline curve's control points, a boundary
/// curve's samples, a second row's points) to absolute positions: one drag step.
struct MoveCurvePoints {
  CurveRef curve;
  std::vector<std::uint32_t> points;
  std::vector<Vec3> positions;  ///< one per point
  /// A closed curve's points only (a section, a spectral condition given as points): > 0
  /// deforms the curve smoothly round each moved point instead of moving it alone. A point at
  /// arc length s from a moved point (along the closed polygon) moves by w(s / r) times that
  /// point's offset, w(t) = (1 − t²)³ for t < 1 and 0 beyond (a compact bump with w'' = 0 at
  /// its edge), r = falloff × the polygon's length; the offsets of several moved points add.
  /// Within a group (a drag) the offsets and arc lengths are taken from the group's start, so
  /// a drag ends exactly where its last step puts it, whatever the steps before it.
  double falloff = 0.0;
};
/// The largest falloff (half the closed curve's length: the bump then reaches all round).
constexpr double kMaxFalloff = 0.5;
/// The falloff of the studio's point drags on closed curves: a bump an eighth of the way
/// round each side, wide enough that a section's Fourier fit takes it smoothly (a section of
/// 6 modes resolves a twelfth of its length) and narrow enough to stay a local edit.
constexpr double kStudioFalloff = 0.125;

/// What a designer should know before dragging a point of this model, or "" when a point drag
/// stays local and bounded (tests/session/locality_test.cpp): the seed's marching chains
/// ("c2", "shared-curves") pass a moved point on from patch to patch, amplified; a spectral
/// patch of high order through many curves is ill-conditioned between them. Says what to use
/// instead (the global chain, whole-curve moves).
std::string dragAdvice(const AnyModel& model);

/// A shape edit may move the surface out of its box by at most this many times the largest
/// offset of a point it moved (a locally bounded edit reaches 1 to 2: locality_test.cpp), plus
/// kReachRounding of the box's diagonal; beyond, the session refuses it (checkReach).
constexpr double kMaxReach = 10.0;
/// Rounding slack of checkReach, relative to the box's diagonal: the meshes it compares hold
/// float positions (7 digits).
constexpr double kReachRounding = 1e-6;
/// Samples per patch side of the meshes checkReach compares.
constexpr std::uint32_t kReachSamples = 17;
/// Throws ModelError (source "edit", with dragAdvice's advice) when `after`'s surface reaches
/// out of `before`'s box by more than kMaxReach times the largest offset of the points of its
/// curves and nets: a point drag on an ill-conditioned patch that would throw it far away.
void checkReach(const AnyModel& before, const SolvedModel& solvedBefore, const AnyModel& after,
                const SolvedModel& solvedAfter);
/// Moves, turns or scales one whole curve (points or Fourier coefficients: a0 takes the
/// whole map, the modes and a derivative condition's curve the linear part alone).
struct TransformCurve {
  CurveRef curve;
  AffineMap map;
  /// The map applies to the model as it was before the edit's group began (JSON "from":
  /// "group-start"), not to the current one: a drag's steps are then absolute, each one
  /// replacing the last, so the dragged curve ends exactly one map away from where it was.
  bool fromGroupStart = false;
};
/// Sets coefficients of a curve given by Fourier coefficients (a spectral condition's, a
/// section's): a0 and/or the whole lists a, b (absolute: one drag step). The studio drags a
/// Fourier derivative condition's a0, the mean direction the surface leaves its curve in.
struct SetFourier {
  CurveRef curve;
  std::optional<Vec3> a0;
  std::optional<std::vector<Vec3>> a, b;
};
/// Changes a spectral model's operator and options, or a chain's a and modes.
struct SetOperator {
  std::optional<OperatorKind> kind;    ///< spectral only
  std::optional<std::uint32_t> power;  ///< Ugail's N (spectral only)
  std::optional<double> a;             ///< spectral and cross-sections
  std::optional<std::uint32_t> modes;  ///< spectral and cross-sections
  std::optional<bool> remainder;       ///< spectral and cross-sections
  std::optional<ChainMethod> method;   ///< cross-sections only
};
/// Replaces a spectral model's spine edits (its file's "spine" field, seed 003 §4.2).
struct SetSpine {
  std::vector<SpineEdit> edits;
};
/// Moves spine handle `index` of a spectral model (of the spine points its handles list:
/// SurfaceMethod::handles, at their u) to `position`, the other handles held where they are:
/// a spine edit at the handles' u (the file's "spine"), which replaces the model's last one
/// when that is at the same u, else is added. Within a group (a drag) it applies to the model
/// as the group began, so each step replaces the last (the studio's spine drag).
struct MoveSpinePoint {
  std::uint32_t index = 0;
  Vec3 position = Vec3::Zero();
};
/// Inserts a section into a cross-section chain before section `index` (index = count: at
/// the end). Without a curve the section is the chain's surface sampled half way between
/// its neighbours (so the shape barely changes; only between two sections); a chain with
/// explicit "u" gets the mid value too.
struct AddSection {
  std::uint32_t index = 0;
  std::optional<CurveInput> curve;
};
/// Removes section `index` of a cross-section chain (and its "u").
struct RemoveSection {
  std::uint32_t index = 0;
};
/// Moves given control points of a B-spline PDE model's net (rows 0, 1, n_u and columns 0,
/// 1, n_v); the inner points are solved again.
struct MoveControlPoints {
  std::vector<std::array<std::uint32_t, 2>> points;  ///< (i, j): row i along u, column j
  std::vector<Vec3> positions;
};

using ShapeEdit = std::variant<MoveCurvePoints, TransformCurve, SetFourier, SetOperator, SetSpine,
                               MoveSpinePoint, AddSection, RemoveSection, MoveControlPoints>;
/// A shape edit as the studio sends it, with its undo group (as GroupedEdit).
struct GroupedShapeEdit {
  ShapeEdit edit;
  std::string group;
};
/// Points a section sampled from a chain's surface (AddSection) has at least.
constexpr std::size_t kMinSampledSection = 16;

/// The spine points the studio lets a user drag on a spectral model: `count` points of A0 at
/// uniform u over the patch, exactly as `pdesurf spine --count` places them; empty for the
/// other types.
struct SpineHandles {
  std::vector<double> u;
  std::vector<Vec3> points;
};
SpineHandles spineHandles(const SolvedModel& solved, std::uint32_t count);

/// Snapshots of a value for undo and redo. Consecutive changes of one non-empty group
/// undo as one step.
template <typename Model>
class UndoHistory {
 public:
  /// At most this many undo steps are kept.
  static constexpr std::size_t kMaxUndo = 500;

  /// Call before `current` changes: keeps its snapshot unless the change continues the
  /// group of the previous one; clears the redo steps.
  void record(const Model& current, std::string_view group) {
    if (group.empty() || group != group_) {
      undo_.push_back(current);
      if (undo_.size() > kMaxUndo) undo_.erase(undo_.begin());
    }
    group_ = std::string(group);
    redo_.clear();
  }
  /// Swaps `current` with the last snapshot; false when there is none.
  bool undo(Model& current) { return step(undo_, redo_, current); }
  bool redo(Model& current) { return step(redo_, undo_, current); }
  std::size_t undoDepth() const { return undo_.size(); }
  std::size_t redoDepth() const { return redo_.size(); }
  void endGroup() { group_.clear(); }
  /// The snapshot taken when the open group `group` began (the value before its first
  /// change); nullptr when `group` is empty or not the open group.
  const Model* groupStart(std::string_view group) const {
    if (group.empty() || group != group_ || undo_.empty()) return nullptr;
    return &undo_.back();
  }

 private:
  /// Moves `current` onto `to` and the last of `from` into its place.
  bool step(std::vector<Model>& from, std::vector<Model>& to, Model& current) {
    if (from.empty()) return false;
    to.push_back(std::move(current));
    current = std::move(from.back());
    from.pop_back();
    group_.clear();
    return true;
  }

  std::vector<Model> undo_, redo_;
  std::string group_;
};

/// An editing session on a model of any type: its method's edits through one path (parsed by
/// parseEdit, edit_io.hpp, applied by the method: vertex frames' vertices, a1/a2, forces and
/// frame structure; the other types' curves, nets, spines and operators), whole-model
/// transforms of every type, undo and redo (a drag is one step), and the solved model cached
/// per revision. Models without editable parts are solved whenever they change and kept with
/// their solution, so undo and redo do not solve again; a model with editable parts (vertex
/// frames) is solved on first use after each change, on a topology built again only when the
/// frame structure changes.
class ModelSession {
 public:
  /// One undo step holds the model as it was and, for a model without editable parts, its
  /// solution (both shared, never copied by undo or redo); vertex frames' topology is kept
  /// while edits leave the structure alone (shared: a drag re-solves on the same layout).
  using State = ModelState;
  /// At most this many undo steps are kept.
  static constexpr std::size_t kMaxUndo = UndoHistory<State>::kMaxUndo;

  /// Starts a session; a model without editable parts is solved now (its solver's refusal
  /// throws ModelError naming `source`).
  explicit ModelSession(AnyModel model, std::string source = "model");

  const AnyModel& model() const { return *current_.model; }
  /// The vertex-frame model, or nullptr for the other types: a type branch kept for the
  /// studio's frame routes (patch queries, boundaries, forces) and the tests, which read
  /// vertex frames' own data; edits go through apply, whatever the type.
  const VertexFrameModel* frames() const { return model().as<VertexFrameModel>(); }
  /// Whether the model has editable parts (SurfaceMethod::hasEditableParts: vertex frames).
  bool hasEditableParts() const { return pdesurf::hasEditableParts(model()); }
  /// Increases with every change of the model (edit, transform, undo, redo).
  std::uint64_t revision() const { return revision_; }

  /// Applies an edit of the model's method (parseEdit's, edit_io.hpp): the one path of every
  /// edit of every type, by the method's applyEdit. An edit whose result is invalid (a
  /// structure edit restructure refuses, a shape edit the file parser or the solver refuses)
  /// throws ModelError and leaves the session as it was. Edits of one non-empty group undo
  /// as one step; an edit the method makes a step of its own ends the group.
  void apply(const ModelEdit& edit);
  /// The built-in methods' edits given as values (programs, tests): apply({edit, group}).
  /// A TransformCurve from the group's start applies to the model as it was before `group`'s
  /// first edit (the current model when none came yet).
  void apply(const Edit& edit, std::string_view group = {});
  void apply(const ShapeEdit& edit, std::string_view group = {});
  /// Moves, turns or scales the model (one undo step). An invalid result (checkTransform)
  /// or a solver refusal throws ModelError and leaves the session as it was.
  void transform(const AffineMap& map);
  bool undo();
  bool redo();
  std::size_t undoDepth() const { return history_.undoDepth(); }
  std::size_t redoDepth() const { return history_.redoDepth(); }
  /// Ends the current group: the next edit starts a new undo step even if its group is
  /// the same (the end of a drag).
  void endGroup() { history_.endGroup(); }

  /// The current model solved with `options` (each method reads its own member of them).
  const SolvedModel& solved(const SolveOptions& options = {});

 private:
  /// Records the current state for undo and makes `next` current.
  void change(std::shared_ptr<const AnyModel> next, std::shared_ptr<const SolvedModel> solved,
              std::string_view group, std::shared_ptr<const FrameTopology> topology = nullptr);
  /// The state's solution when the model has no editable parts (else null: solved lazily).
  std::shared_ptr<const SolvedModel> solveIfFixed(
      const std::shared_ptr<const AnyModel>& model) const;

  std::string source_;
  State current_;
  std::uint64_t revision_ = 0;
  UndoHistory<State> history_;
  std::uint64_t solvedRevision_ = 0;
  SolveOptions solvedOptions_;
};

}  // namespace pdesurf
