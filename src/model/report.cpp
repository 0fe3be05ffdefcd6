// report() and infoText() of the model layer (include/pdesurf/model.hpp), and the reports of
// vertex-frame models; the other types' are in report_spectral.cpp and report_bspline.cpp.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "model/reports.hpp"
#include "pdesurf/analysis.hpp"

namespace pdesurf {

std::string countText(std::size_t n, const std::string& noun) {
  if (n == 1) return "1 " + noun;
  if (noun == "vertex") return fmt::format("{} vertices", n);
  return fmt::format("{} {}{}", n, noun, noun.ends_with("ch") ? "es" : "s");
}

namespace detail {

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
        {"solver", solved.options().solver == Solver::Local ? "local" : "global"},
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

}  // namespace detail

ModelReport report(const SolvedModel& solved) {
  if (const VertexFrameSurface* s = solved.frames())
    return detail::frameReport(std::get<VertexFrameModel>(solved.model()), *s);
  if (const SolvedSpectral* s = solved.spectral()) return detail::spectralReport(*s);
  return detail::bsplineReport(std::get<SolvedBSplinePde>(solved.solved()));
}

std::string infoText(const SolvedModel& solved, bool json) {
  if (const VertexFrameSurface* s = solved.frames())
    return detail::frameInfo(solved, std::get<VertexFrameModel>(solved.model()), *s, json);
  if (const SolvedSpectral* s = solved.spectral())
    return detail::spectralInfo(*s, solved.source(), modelNameOf(solved.model()), json);
  return detail::bsplineInfo(std::get<BSplinePdeModel>(solved.model()),
                             std::get<SolvedBSplinePde>(solved.solved()), solved.source(), json);
}

}  // namespace pdesurf
