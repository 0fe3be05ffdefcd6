// Editing sessions (include/pdesurf/session.hpp): edits, transforms, undo/redo with grouping,
// cached solves, for a model of any type.
#include "pdesurf/session.hpp"

#include "pdesurf/edit_io.hpp"

namespace pdesurf {

std::shared_ptr<const SolvedModel> ModelSession::solveIfFixed(
    const std::shared_ptr<const AnyModel>& model) const {
  if (pdesurf::hasEditableParts(*model)) return nullptr;
  return std::make_shared<const SolvedModel>(solve(model, source_));
}

ModelSession::ModelSession(AnyModel model, std::string source) : source_(std::move(source)) {
  auto shared = std::make_shared<const AnyModel>(std::move(model));
  auto topology = shared->method().topology(*shared);
  current_ = {shared, solveIfFixed(shared), std::move(topology)};  // may throw: nothing to undo
}

void ModelSession::change(std::shared_ptr<const AnyModel> next,
                          std::shared_ptr<const SolvedModel> solved, std::string_view group,
                          std::shared_ptr<const FrameTopology> topology) {
  // A solution solved on demand is not kept for undo: it is solved again when asked for.
  history_.record(
      State{current_.model, hasEditableParts() ? nullptr : current_.solved, current_.topology},
      group);
  if (!topology) topology = current_.topology;  // the structure stays
  current_ = {std::move(next), std::move(solved), std::move(topology)};
  ++revision_;
}

void ModelSession::apply(const ModelEdit& edit) {
  const EditContext context{current_, history_.groupStart(edit.group),
                            [this]() -> const SolvedModel& { return solved(); }, source_};
  EditResult result = model().method().applyEdit(context, edit);  // may throw: nothing changed
  if (!result.next.solved) result.next.solved = solveIfFixed(result.next.model);  // may throw
  if (result.ownStep) history_.endGroup();
  change(std::move(result.next.model), std::move(result.next.solved),
         result.ownStep ? std::string_view{} : std::string_view(edit.group),
         std::move(result.next.topology));
}

void ModelSession::apply(const Edit& edit, std::string_view group) {
  apply(ModelEdit{edit, std::string(group)});
}

void ModelSession::apply(const ShapeEdit& edit, std::string_view group) {
  apply(ModelEdit{edit, std::string(group)});
}

void ModelSession::transform(const AffineMap& map) {
  checkTransform(model(), map);
  auto next = std::make_shared<const AnyModel>(transformModel(model(), map));
  auto solved = solveIfFixed(next);  // may throw: nothing changed yet
  change(std::move(next), std::move(solved), {});
}

bool ModelSession::undo() {
  if (hasEditableParts()) current_.solved.reset();  // kept for redo: the model alone
  if (!history_.undo(current_)) return false;
  ++revision_;
  return true;
}

bool ModelSession::redo() {
  if (hasEditableParts()) current_.solved.reset();
  if (!history_.redo(current_)) return false;
  ++revision_;
  return true;
}

const SolvedModel& ModelSession::solved(const SolveOptions& options) {
  if (!hasEditableParts()) return *current_.solved;
  if (!current_.solved || solvedRevision_ != revision_ || options != solvedOptions_) {
    current_.solved = std::make_shared<const SolvedModel>(
        pdesurf::solve(current_.model, source_, options, current_.topology));
    solvedRevision_ = revision_;
    solvedOptions_ = options;
  }
  return *current_.solved;
}

}  // namespace pdesurf
