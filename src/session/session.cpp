// Editing sessions: edits, undo/redo with grouping, cached solves.
#include "pdesurf/session.hpp"

#include <stdexcept>

#include "pdesurf/model_io.hpp"

namespace pdesurf {

ModelSession::ModelSession(VertexFrameModel model)
    : model_(std::move(model)),
      topology_(std::make_shared<const FrameTopology>(buildTopology(model_))) {}

void ModelSession::changed() {
  ++revision_;
  surface_.reset();
}

void ModelSession::apply(const Edit& edit, std::string_view group) {
  history_.record(model_, group);
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
        } else if constexpr (std::is_same_v<T, SetSharedForces>) {
          model_.forces = e.forces;
        } else {
          static_assert(std::is_same_v<T, TransformModel>);
          model_ = transformModel(model_, e.map);
        }
      },
      edit);
  changed();
}

bool ModelSession::undo() {
  if (!history_.undo(model_)) return false;
  changed();
  return true;
}

bool ModelSession::redo() {
  if (!history_.redo(model_)) return false;
  changed();
  return true;
}

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

// ---------------------------------------------------------------------------------------
// Spectral and cross-section models

SpectralSession::Solved SpectralSession::solve(AnyModel model) const {
  if (auto solved = solveIfSpectral(model, source_))
    return {std::move(model), std::move(*solved), std::nullopt};
  if (const auto* b = std::get_if<BSplinePdeModel>(&model)) {
    SolvedSpectral empty;
    empty.type = "bspline-pde";
    std::optional<SolvedBSplinePde> bspline = solveBSplineModel(*b, source_);
    return {std::move(model), std::move(empty), std::move(bspline)};
  }
  throw ModelError(source_, "$.type", "vertex-frames models open in a ModelSession");
}

SpectralSession::SpectralSession(AnyModel model, std::string source)
    : source_(std::move(source)), current_(solve(std::move(model))) {}

void SpectralSession::transform(const AffineMap& map) {
  Solved next = solve(transformModel(current_.model, map));  // may throw: nothing changed yet
  history_.record(current_, {});
  current_ = std::move(next);
  ++revision_;
}

bool SpectralSession::undo() {
  if (!history_.undo(current_)) return false;
  ++revision_;
  return true;
}

bool SpectralSession::redo() {
  if (!history_.redo(current_)) return false;
  ++revision_;
  return true;
}

}  // namespace pdesurf
