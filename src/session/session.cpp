// Editing sessions (include/pdesurf/session.hpp): edits, transforms, undo/redo with grouping,
// cached solves, for a model of any type.
#include "pdesurf/session.hpp"

#include <stdexcept>

#include "pdesurf/edit_io.hpp"

namespace pdesurf {

std::shared_ptr<const SolvedModel> ModelSession::solveIfFixed(
    const std::shared_ptr<const AnyModel>& model) const {
  if (hasEditableParts(*model)) return nullptr;
  return std::make_shared<const SolvedModel>(solveModel(model, source_));
}

ModelSession::ModelSession(AnyModel model, std::string source) : source_(std::move(source)) {
  auto shared = std::make_shared<const AnyModel>(std::move(model));
  std::shared_ptr<const FrameTopology> topology;
  // A type branch: the vertex-frame part edits keep the frames' topology (issue 26 item 2
  // makes the edits a method's own).
  if (const auto* frames = shared->as<VertexFrameModel>())
    topology = std::make_shared<const FrameTopology>(buildTopology(*frames));
  current_ = {shared, solveIfFixed(shared), std::move(topology)};  // may throw: nothing to undo
}

void ModelSession::change(std::shared_ptr<const AnyModel> next,
                          std::shared_ptr<const SolvedModel> solved, std::string_view group,
                          std::shared_ptr<const FrameTopology> topology) {
  // A vertex-frame solution is not kept for undo: it is solved again when asked for.
  history_.record(State{current_.model, editable() ? nullptr : current_.solved, current_.topology},
                  group);
  if (!topology) topology = current_.topology;  // the structure stays
  current_ = {std::move(next), std::move(solved), std::move(topology)};
  ++revision_;
}

void ModelSession::apply(const Edit& edit, std::string_view group) {
  if (const auto* t = std::get_if<TransformModel>(&edit)) {
    transform(t->map);
    return;
  }
  // Not a pdesurf::Error: the caller's slip (an Edit for a model that takes none), not input.
  if (!editable()) throw std::logic_error("ModelSession::apply: the model has no editable parts");
  if (changesStructure(edit)) {
    const VertexFrameSurface& surface = *solved().frames();
    auto next = restructure(*frames(), *current_.topology, surface, edit);  // may throw
    auto topology = std::make_shared<const FrameTopology>(buildTopology(next));
    history_.endGroup();  // a structure edit is a step of its own
    change(std::make_shared<const AnyModel>(std::move(next)), nullptr, {}, std::move(topology));
    return;
  }
  VertexFrameModel next = *frames();
  std::visit(
      [&](const auto& e) {
        using T = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<T, MoveVertex>) {
          next.vertices[e.vertex] = e.position;
        } else if constexpr (std::is_same_v<T, MoveVertices>) {
          for (std::size_t i = 0; i < e.vertices.size(); ++i)
            next.vertices[e.vertices[i]] = e.positions[i];
        } else if constexpr (std::is_same_v<T, SetParameters>) {
          for (std::uint32_t k : e.frames) {
            if (e.a1) next.frames[k].a1 = *e.a1;
            if (e.a2) next.frames[k].a2 = *e.a2;
          }
        } else if constexpr (std::is_same_v<T, SetFrameForces>) {
          next.frames[e.frame].forces = e.forces;
        } else if constexpr (std::is_same_v<T, SetSharedForces>) {
          next.forces = e.forces;
        } else {
          static_assert(std::is_same_v<T, TransformModel> || std::is_same_v<T, ExtrudeEdges> ||
                        std::is_same_v<T, AddFrame> || std::is_same_v<T, DeleteFrames> ||
                        std::is_same_v<T, SplitFrame> || std::is_same_v<T, WeldVertices> ||
                        std::is_same_v<T, WeldEdges> || std::is_same_v<T, FlipFrames> ||
                        std::is_same_v<T, MirrorFrames>);
        }
      },
      edit);
  change(std::make_shared<const AnyModel>(std::move(next)), nullptr, group);
}

void ModelSession::transform(const AffineMap& map) {
  checkTransform(model(), map);
  auto next = std::make_shared<const AnyModel>(transformModel(model(), map));
  auto solved = solveIfFixed(next);  // may throw: nothing changed yet
  change(std::move(next), std::move(solved), {});
}

bool ModelSession::undo() {
  if (editable()) current_.solved.reset();  // kept for redo: the model alone
  if (!history_.undo(current_)) return false;
  ++revision_;
  return true;
}

bool ModelSession::redo() {
  if (editable()) current_.solved.reset();
  if (!history_.redo(current_)) return false;
  ++revision_;
  return true;
}

const SolvedModel& ModelSession::solved(const SolveOptions& options) {
  if (!editable()) return *current_.solved;
  const bool sameOptions =
      options.solver == solvedOptions_.solver && options.seedFrame == solvedOptions_.seedFrame;
  if (!current_.solved || solvedRevision_ != revision_ || !sameOptions) {
    current_.solved = std::make_shared<const SolvedModel>(
        solveModel(current_.model, source_, options, current_.topology));
    solvedRevision_ = revision_;
    solvedOptions_ = options;
  }
  return *current_.solved;
}

}  // namespace pdesurf
