// Editing sessions: on a vertex-frame model, validated edits, undo and redo (a drag is one
// step), and a solved surface cached per revision; on a spectral or cross-section model,
// whole-model transforms with undo and redo. The studio server is a thin HTTP layer over
// this; nothing here knows about HTTP or files.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "pdesurf/spectral_io.hpp"
#include "pdesurf/transform.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf {

/// Moves one vertex.
struct MoveVertex {
  std::uint32_t vertex = 0;
  Vec3 position = Vec3::Zero();
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

/// One change to a model. No edit changes which vertices a frame uses, so the topology
/// (strips, edges, orientation) of a session never changes.
using Edit =
    std::variant<MoveVertex, SetParameters, SetFrameForces, SetSharedForces, TransformModel>;

/// An edit as the studio sends it, with an optional group: consecutive edits of one
/// non-empty group (the moves of one drag, the steps of one slider gesture) undo as one.
struct GroupedEdit {
  Edit edit;
  std::string group;
};

/// Parses and validates an edit against `model`: JSON such as
///   {"op": "move-vertex", "vertex": 3, "position": [0, 1, 2], "group": "drag-7"}
///   {"op": "set-parameters", "frames": [0, 2], "a1": [1, 1, 1], "a2": [2, 2, 2]}
///   {"op": "set-forces", "frame": 1, "forces": [{"f0": [0, 0, 1], "region": [0, 1, 0, 1]}]}
///   {"op": "set-shared-forces", "forces": [{"f0": [0, 0, -1], "frames": [0, 1]}]}
/// Everything the model parser would check of the result is checked (indices in range,
/// finite numbers, regions, forces that have a solution with the frame's a1 and a2).
/// Throws ModelError with source "edit" and the JSON path of the problem.
GroupedEdit parseEdit(std::string_view json, const VertexFrameModel& model);

/// Parses a whole-model transform as the studio sends it (POST /api/transform):
///   {"translate": [x, y, z],
///    "rotate": {"axis": [x, y, z], "degrees": d, "center": [x, y, z]},
///    "scale": s, "center": [x, y, z]}
/// All parts optional but at least one; applied in the order scale (about "center", s > 0),
/// rotate (about its own "center", else the top-level one), translate. "center" defaults to
/// the origin. Throws ModelError with source "transform" and the JSON path of the problem.
AffineMap parseTransform(std::string_view json);

/// Throws ModelError (source "transform") when transformModel(model, map) would be invalid:
/// a force turned onto a component whose a1/Lu² + a2/Lv² is 0 (per-component a1/a2).
void checkTransform(const VertexFrameModel& model, const AffineMap& map);

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

class ModelSession {
 public:
  /// At most this many undo steps are kept (each is a snapshot of the model).
  static constexpr std::size_t kMaxUndo = UndoHistory<VertexFrameModel>::kMaxUndo;

  explicit ModelSession(VertexFrameModel model);

  const VertexFrameModel& model() const { return model_; }
  /// Increases with every change of the model (edit, undo, redo).
  std::uint64_t revision() const { return revision_; }

  /// Applies a valid edit (validate with parseEdit first).
  void apply(const Edit& edit, std::string_view group = {});
  bool undo();
  bool redo();
  std::size_t undoDepth() const { return history_.undoDepth(); }
  std::size_t redoDepth() const { return history_.redoDepth(); }
  /// Ends the current group: the next edit starts a new undo step even if its group is
  /// the same (the end of a drag).
  void endGroup() { history_.endGroup(); }

  /// The surface of the current model, solved on first use after each change; the
  /// topology is built once per session and shared by every solve.
  const VertexFrameSurface& surface(const SolveOptions& options = {});

 private:
  void changed();

  VertexFrameModel model_;
  std::uint64_t revision_ = 0;
  UndoHistory<VertexFrameModel> history_;
  std::shared_ptr<const FrameTopology> topology_;
  std::optional<VertexFrameSurface> surface_;
  std::uint64_t surfaceRevision_ = 0;
  SolveOptions surfaceOptions_;
};

/// A session on a spectral, cross-section or bspline-pde model: the studio shows it and
/// moves, turns and scales it as a whole (curve and net editing are not session edits),
/// with undo and redo.
/// Each model is kept with its solved surface, so undo and redo do not solve again.
class SpectralSession {
 public:
  /// Solves the model; throws ModelError naming `source` when it cannot be solved or is
  /// of another type (vertex frames are a ModelSession).
  SpectralSession(AnyModel model, std::string source);

  const AnyModel& model() const { return current_.model; }
  /// The solved spectral or cross-section model (for a bspline-pde model: empty, its type
  /// "bspline-pde"; bspline() holds the surface).
  const SolvedSpectral& solved() const { return current_.solved; }
  /// The solved bspline-pde model, or nullptr for the spectral types.
  const SolvedBSplinePde* bspline() const {
    return current_.bspline ? &*current_.bspline : nullptr;
  }
  std::uint64_t revision() const { return revision_; }

  /// Transforms and solves the model (one undo step). A solver refusal throws ModelError
  /// and leaves the session as it was.
  void transform(const AffineMap& map);
  bool undo();
  bool redo();
  std::size_t undoDepth() const { return history_.undoDepth(); }
  std::size_t redoDepth() const { return history_.redoDepth(); }

 private:
  struct Solved {
    AnyModel model;
    SolvedSpectral solved;
    std::optional<SolvedBSplinePde> bspline;
  };
  Solved solve(AnyModel model) const;

  std::string source_;
  Solved current_;
  std::uint64_t revision_ = 0;
  UndoHistory<Solved> history_;
};

}  // namespace pdesurf
