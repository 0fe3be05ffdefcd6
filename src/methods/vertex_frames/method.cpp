// The "vertex-frames" method (include/pdesurf/method.hpp): its description, its solved
// surface (VertexFrameSurface), its reports, its edits (Edit, session.hpp: parsed by
// parseFrameEdit, the structure edits made by restructure).
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/json_reader.hpp"
#include "methods/builtin.hpp"
#include "pdesurf/analysis.hpp"
#include "pdesurf/edit_io.hpp"
#include "pdesurf/error.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"

namespace pdesurf::detail {

namespace {

ModelReport frameReport(const VertexFrameModel& model, const VertexFrameSurface& surface) {
  return {fmt::format("{}, {}", countText(model.frames.size(), "frame"),
                      countText(surface.topology->stripCount, "strip")),
          fmt::format("C0 gap {:.3g}", measureC0Gap(surface).maxGap)};
}

std::string frameInfo(const SolvedModel& solved, const VertexFrameModel& model,
                      const VertexFrameSurface& surface, bool json) {
  const std::string& modelPath = solved.source();
  const C0Report c0 = measureC0Gap(surface);
  const Bounds b = surfaceBounds(surface);
  const double diag = b.diagonal();
  const double rel = diag > 0.0 ? c0.maxGap / diag : c0.maxGap;
  std::size_t pinned = 0;
  for (auto p : surface.topology->stripPinned) pinned += p;
  const std::size_t storage = storageBytes(model);
  const std::size_t coincident = coincidentVertices(model);
  if (json) {
    nlohmann::json j = {
        {"model", modelPath},
        {"name", model.name},
        {"vertices", model.vertices.size()},
        {"frames", model.frames.size()},
        {"strips", surface.topology->stripCount},
        {"pinned_strips", pinned},
        {"edges", surface.topology->edges.size()},
        {"shared_edges", c0.sharedEdges},
        {"orientable", surface.topology->orientable},
        {"c0_gap", c0.maxGap},
        {"c0_gap_relative", rel},
        {"bbox",
         {{"min", {b.min.x(), b.min.y(), b.min.z()}}, {"max", {b.max.x(), b.max.y(), b.max.z()}}}},
        {"storage_bytes", storage},
        {"coincident_vertices", coincident},
        {"solver", solved.options().vertexFrames.solver == Solver::Local ? "local" : "global"},
        {"notes", surface.notes}};
    return j.dump(2) + "\n";
  }
  std::string out;
  out += fmt::format("model      {}{}\n", modelPath,
                     model.name.empty() ? "" : " (" + model.name + ")");
  out += fmt::format("vertices   {}\nframes     {}\n", model.vertices.size(), model.frames.size());
  out += fmt::format("strips     {} ({} pinned to 0)\n", surface.topology->stripCount, pinned);
  out += fmt::format("edges      {} ({} shared)\n", surface.topology->edges.size(), c0.sharedEdges);
  out += fmt::format("C0 gap     {} (relative to the bounding-box diagonal: {})\n", c0.maxGap, rel);
  out += fmt::format("bbox       [{}, {}, {}] to [{}, {}, {}]\n", b.min.x(), b.min.y(), b.min.z(),
                     b.max.x(), b.max.y(), b.max.z());
  out += fmt::format("storage    {} bytes (numbers to six significant digits)\n", storage);
  if (!surface.topology->orientable) out += "orientable no\n";
  if (coincident > 0)
    out += fmt::format(
        "warning    {} {} where another vertex stands, under another index: frames "
        "meet only through shared indices, so the surface may have cracks there\n",
        coincident, coincident == 1 ? "vertex stands" : "vertices stand");
  return out;
}

class SolvedFrames final
    : public UnitSquarePatches<VertexFrameSurface, &VertexFrameSurface::patches> {
 public:
  using UnitSquarePatches::UnitSquarePatches;

  Mesh tessellate(const TessellateOptions& options) const override {
    return pdesurf::tessellate(value_, options);
  }
  NurbsModel toNurbs(const NurbsExportOptions& options) const override {
    return pdesurf::toNurbs(value_, options);
  }
  double largestC0Gap() const override { return measureC0Gap(value_).maxGap; }
  const std::vector<std::string>& notes() const override { return value_.notes; }
};

/// The model after an edit that keeps the frame structure: the vertices, a1/a2 or forces set.
VertexFrameModel withPartsSet(VertexFrameModel next, const Edit& edit) {
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
  return next;
}

class VertexFramesMethod final : public MethodOf<VertexFrameModel> {
 public:
  const char* typeName() const override { return "vertex-frames"; }
  const char* patchName() const override { return "frame"; }
  AnyModel parse(const nlohmann::json& document, const std::string& source) const override {
    return parseVertexFrameDocument(document, Reader(source));
  }
  std::string serialize(const AnyModel& model) const override {
    return serializeVertexFrameModel(model.get<VertexFrameModel>());
  }
  std::shared_ptr<const SolvedSurface> solve(
      const AnyModel& model, const std::string&, const SolveOptions& options,
      const std::shared_ptr<const FrameTopology>& topology) const override {
    const auto& frames = model.get<VertexFrameModel>();
    const VertexFrameSolveOptions& own = options.vertexFrames;
    return std::make_shared<const SolvedFrames>(topology ? pdesurf::solve(frames, topology, own)
                                                         : pdesurf::solve(frames, own));
  }
  void checkSolveOptions(const AnyModel& model, const SolveOptions& options) const override {
    const std::size_t n = model.get<VertexFrameModel>().frames.size();
    if (options.vertexFrames.seedFrame < n) return;
    throw InvalidArgument(fmt::format("out of range, the model has {} frame{} (indices 0 to {})", n,
                                      n == 1 ? "" : "s", n - 1));
  }
  void checkTransform(const AnyModel& model, const AffineMap& map) const override {
    pdesurf::checkTransform(model.get<VertexFrameModel>(), map);
  }
  ModelReport report(const SolvedModel& solved) const override {
    return frameReport(solved.model().get<VertexFrameModel>(),
                       solved.surface().get<VertexFrameSurface>());
  }
  std::string info(const SolvedModel& solved, bool json) const override {
    return frameInfo(solved, solved.model().get<VertexFrameModel>(),
                     solved.surface().get<VertexFrameSurface>(), json);
  }
  ModelEdit parseEdit(std::string_view json, const AnyModel& model) const override {
    GroupedEdit e = parseFrameEdit(json, model.get<VertexFrameModel>());
    return {std::move(e.edit), std::move(e.group)};
  }
  EditResult applyEdit(const EditContext& context, const ModelEdit& edit) const override {
    const AnyModel& model = *context.current.model;
    const Edit& e = edit.as<Edit>(typeName());
    if (const auto* t = std::get_if<TransformModel>(&e)) {
      pdesurf::checkTransform(model, t->map);
      return {{std::make_shared<const AnyModel>(transformModel(model, t->map)), nullptr, nullptr},
              true};
    }
    const auto& frames = model.get<VertexFrameModel>();
    if (changesStructure(e)) {
      const VertexFrameSurface& surface = *context.solved().frames();
      auto next = restructure(frames, *context.current.topology, surface, e);  // may throw
      auto topology = std::make_shared<const FrameTopology>(buildTopology(next));
      return {{std::make_shared<const AnyModel>(std::move(next)), nullptr, std::move(topology)},
              true};
    }
    return {{std::make_shared<const AnyModel>(withPartsSet(frames, e)), nullptr, nullptr}};
  }
  std::shared_ptr<const FrameTopology> topology(const AnyModel& model) const override {
    return std::make_shared<const FrameTopology>(buildTopology(model.get<VertexFrameModel>()));
  }
  bool hasEditableParts() const override { return true; }
};

}  // namespace

const SurfaceMethod& vertexFramesMethod() {
  static const VertexFramesMethod method;
  return method;
}

}  // namespace pdesurf::detail
