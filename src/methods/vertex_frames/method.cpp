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
#include "pdesurf/model_info.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"

namespace pdesurf::detail {

namespace {

ModelReport frameReport(const VertexFrameModel& model, const VertexFrameSurface& surface) {
  return {fmt::format("{}, {}", countText(model.frames.size(), "frame"),
                      countText(surface.topology->stripCount, "strip")),
          fmt::format("C0 gap {:.3g}", measureC0Gap(surface).maxGap)};
}

ModelInfo frameInfo(const SolvedModel& solved, const VertexFrameModel& model,
                    const VertexFrameSurface& surface) {
  const FrameTopology& topology = *surface.topology;
  const C0Report c0 = measureC0Gap(surface);
  const Bounds b = surfaceBounds(surface);
  const double diag = b.diagonal();
  const double rel = diag > 0.0 ? c0.maxGap / diag : c0.maxGap;
  std::size_t pinned = 0;
  for (auto p : topology.stripPinned) pinned += p;
  const std::size_t storage = storageBytes(model);
  const std::size_t coincident = coincidentVertices(model);
  ModelInfo info;
  info.keysSorted = true;
  info.facts = {{"vertices", "vertices", model.vertices.size(), ""},
                {"frames", "frames", model.frames.size(), ""},
                {"strips", "strips", topology.stripCount,
                 fmt::format("{} ({} pinned to 0)", topology.stripCount, pinned)},
                {"", "pinned_strips", pinned, ""},
                {"edges", "edges", topology.edges.size(),
                 fmt::format("{} ({} shared)", topology.edges.size(), c0.sharedEdges)},
                {"", "shared_edges", c0.sharedEdges, ""},
                {"C0 gap", "c0_gap", c0.maxGap,
                 fmt::format("{} (relative to the bounding-box diagonal: {})", c0.maxGap, rel)},
                {"", "c0_gap_relative", rel, ""},
                boxFact(b.min, b.max),
                {"storage", "storage_bytes", storage,
                 fmt::format("{} bytes (numbers to six significant digits)", storage)},
                {"", "orientable", topology.orientable, ""},
                {"", "coincident_vertices", coincident, ""},
                {"", "solver",
                 solved.options().vertexFrames.solver == Solver::Local ? "local" : "global", ""},
                {"", "notes", surface.notes, ""}};
  if (!topology.orientable) info.facts.push_back({"orientable", "", false, "no"});
  if (coincident > 0)
    info.facts.push_back(
        {"warning", "", coincident,
         fmt::format("{} {} where another vertex stands, under another index: frames meet "
                     "only through shared indices, so the surface may have cracks there",
                     coincident, coincident == 1 ? "vertex stands" : "vertices stand")});
  return info;
}

class SolvedFrames final
    : public UnitSquarePatches<VertexFrameSurface, &VertexFrameSurface::patches> {
 public:
  using UnitSquarePatches::UnitSquarePatches;

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
  ModelInfo info(const SolvedModel& solved) const override {
    return frameInfo(solved, solved.model().get<VertexFrameModel>(),
                     solved.surface().get<VertexFrameSurface>());
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
