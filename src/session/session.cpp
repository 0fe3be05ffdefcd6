// Editing sessions: edits, undo/redo with grouping, cached solves.
#include "pdesurf/session.hpp"

namespace pdesurf {

ModelSession::ModelSession(VertexFrameModel model)
    : model_(std::move(model)),
      topology_(std::make_shared<const FrameTopology>(buildTopology(model_))) {}

void ModelSession::changed() {
  ++revision_;
  surface_.reset();
}

void ModelSession::apply(const Edit& edit, std::string_view group) {
  if (group.empty() || group != group_) {
    undo_.push_back(model_);
    if (undo_.size() > kMaxUndo) undo_.erase(undo_.begin());
  }
  group_ = std::string(group);
  redo_.clear();
  std::visit(
      [&](const auto& e) {
        using T = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<T, MoveVertex>) {
          model_.vertices[e.vertex] = e.position;
        } else if constexpr (std::is_same_v<T, SetParameters>) {
          for (std::uint32_t k : e.frames) {
            if (e.a1) model_.frames[k].a1 = *e.a1;
            if (e.a2) model_.frames[k].a2 = *e.a2;
          }
        } else if constexpr (std::is_same_v<T, SetFrameForces>) {
          model_.frames[e.frame].forces = e.forces;
        } else {
          model_.forces = e.forces;
        }
      },
      edit);
  changed();
}

bool ModelSession::step(std::vector<VertexFrameModel>& from, std::vector<VertexFrameModel>& to) {
  if (from.empty()) return false;
  to.push_back(std::move(model_));
  model_ = std::move(from.back());
  from.pop_back();
  group_.clear();
  changed();
  return true;
}

bool ModelSession::undo() { return step(undo_, redo_); }

bool ModelSession::redo() { return step(redo_, undo_); }

const VertexFrameSurface& ModelSession::surface(const SolveOptions& options) {
  const bool sameOptions =
      options.solver == surfaceOptions_.solver && options.seedFrame == surfaceOptions_.seedFrame;
  if (!surface_ || surfaceRevision_ != revision_ || !sameOptions) {
    surface_ = solve(model_, topology_, options);
    surfaceRevision_ = revision_;
    surfaceOptions_ = options;
  }
  return *surface_;
}

}  // namespace pdesurf
