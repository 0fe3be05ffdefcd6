// An editing session on a vertex-frame model: validated edits, undo and redo (a drag is
// one step), and a solved surface cached per revision. The studio server is a thin HTTP
// layer over this; nothing here knows about HTTP or files.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

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

/// One change to a model. No edit changes which vertices a frame uses, so the topology
/// (strips, edges, orientation) of a session never changes.
using Edit = std::variant<MoveVertex, SetParameters, SetFrameForces, SetSharedForces>;

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

class ModelSession {
 public:
  /// At most this many undo steps are kept (each is a snapshot of the model).
  static constexpr std::size_t kMaxUndo = 500;

  explicit ModelSession(VertexFrameModel model);

  const VertexFrameModel& model() const { return model_; }
  /// Increases with every change of the model (edit, undo, redo).
  std::uint64_t revision() const { return revision_; }

  /// Applies a valid edit (validate with parseEdit first).
  void apply(const Edit& edit, std::string_view group = {});
  bool undo();
  bool redo();
  std::size_t undoDepth() const { return undo_.size(); }
  std::size_t redoDepth() const { return redo_.size(); }
  /// Ends the current group: the next edit starts a new undo step even if its group is
  /// the same (the end of a drag).
  void endGroup() { group_.clear(); }

  /// The surface of the current model, solved on first use after each change; the
  /// topology is built once per session and shared by every solve.
  const VertexFrameSurface& surface(const SolveOptions& options = {});

 private:
  void changed();
  /// Moves the current model onto `to` and the last of `from` into its place.
  bool step(std::vector<VertexFrameModel>& from, std::vector<VertexFrameModel>& to);

  VertexFrameModel model_;
  std::uint64_t revision_ = 0;
  std::vector<VertexFrameModel> undo_, redo_;
  std::string group_;
  std::shared_ptr<const FrameTopology> topology_;
  std::optional<VertexFrameSurface> surface_;
  std::uint64_t surfaceRevision_ = 0;
  SolveOptions surfaceOptions_;
};

}  // namespace pdesurf
