// Editing sessions on models of any type (ModelSession): edits, whole-model transforms, undo
// and redo, the solved model cached per revision. The studio server is a thin HTTP layer over
// this; nothing here knows about HTTP or files (edit_io.hpp parses and checks the edits).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "pdesurf/model.hpp"
#include "pdesurf/transform.hpp"

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

/// An editing session on a model of any type: validated edits of its editable parts (vertex
/// frames: vertices, a1/a2, forces), whole-model transforms of every type, undo and redo (a
/// drag is one step), and the solved model cached per revision. Models without editable parts
/// are solved whenever they change and kept with their solution, so undo and redo do not
/// solve again; a vertex-frame model is solved on first use after each change, on a topology
/// built once per session.
class ModelSession {
 public:
  /// One undo step holds the model as it was and, for a model without editable parts, its
  /// solution (both shared, never copied by undo or redo).
  struct State {
    std::shared_ptr<const AnyModel> model;
    std::shared_ptr<const SolvedModel> solved;
  };
  /// At most this many undo steps are kept.
  static constexpr std::size_t kMaxUndo = UndoHistory<State>::kMaxUndo;

  /// Starts a session; a model without editable parts is solved now (its solver's refusal
  /// throws ModelError naming `source`).
  explicit ModelSession(AnyModel model, std::string source = "model");

  const AnyModel& model() const { return *current_.model; }
  /// The editable vertex-frame model, or nullptr when the model has no editable parts
  /// (it is then only transformed whole).
  const VertexFrameModel* frames() const { return std::get_if<VertexFrameModel>(&model()); }
  bool editable() const { return frames() != nullptr; }
  /// Increases with every change of the model (edit, transform, undo, redo).
  std::uint64_t revision() const { return revision_; }

  /// Applies a valid edit (validate with parseEdit first); edits other than TransformModel
  /// need editable(). A transform goes through transform().
  void apply(const Edit& edit, std::string_view group = {});
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

  /// The current model solved (vertex frames with `options`; the other types ignore them).
  const SolvedModel& solved(const SolveOptions& options = {});

 private:
  /// Records the current state for undo and makes `next` current.
  void change(std::shared_ptr<const AnyModel> next, std::shared_ptr<const SolvedModel> solved,
              std::string_view group);
  /// The state's solution when the model has no editable parts (else null: solved lazily).
  std::shared_ptr<const SolvedModel> solveIfFixed(
      const std::shared_ptr<const AnyModel>& model) const;

  std::string source_;
  State current_;
  std::uint64_t revision_ = 0;
  UndoHistory<State> history_;
  std::shared_ptr<const FrameTopology> topology_;  // vertex frames: built once
  std::uint64_t solvedRevision_ = 0;
  SolveOptions solvedOptions_;
};

}  // namespace pdesurf
