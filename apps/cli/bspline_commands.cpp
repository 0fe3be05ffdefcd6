// `build`, `sample` and `info` of "bspline-pde" models.
#include "bspline_commands.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace pdesurf::cli {
namespace {

using Json = nlohmann::ordered_json;

Json pointJson(const Vec3& p) { return Json::array({p.x(), p.y(), p.z()}); }

const char* knotName(KnotType k) { return k == KnotType::Clamped ? "clamped" : "uniform"; }

double worstResidual(const SolvedBSplinePde& solved) {
  double worst = 0.0;
  for (const BSplineSurface& s : solved.pieces) worst = std::max(worst, pdeResidual(s));
  return worst;
}

std::string knotsText(const BSplineSurface& s) {
  return s.uKnotType() == s.vKnotType()
             ? fmt::format("{} knots", knotName(s.uKnotType()))
             : fmt::format("{} u / {} v knots", knotName(s.uKnotType()), knotName(s.vKnotType()));
}

}  // namespace

std::string bsplineSummary(const SolvedBSplinePde& solved) {
  const BSplineSurface& s = solved.pieces.front();
  return fmt::format("bspline-pde, {} piece{}, {} x {} control points{}, {}", solved.pieces.size(),
                     solved.pieces.size() == 1 ? "" : "s", s.net().nu + 1, s.net().nv + 1,
                     solved.pieces.size() == 1 ? "" : " each", knotsText(s));
}

std::string bsplineQuality(const SolvedBSplinePde& solved) {
  std::string q = fmt::format("PDE residual {:.3g}", worstResidual(solved));
  if (solved.c1Gap) q += fmt::format(", C1 gap {:.3g}", *solved.c1Gap);
  return q;
}

std::string bsplineSampleJson(const SolvedBSplinePde& solved, std::uint32_t grid) {
  Json patches = Json::array();
  for (std::size_t k = 0; k < solved.pieces.size(); ++k) {
    Json points = Json::array();
    for (std::uint32_t j = 0; j < grid; ++j)
      for (std::uint32_t i = 0; i < grid; ++i)
        points.push_back(pointJson(solved.pieces[k].position(static_cast<double>(i) / (grid - 1),
                                                             static_cast<double>(j) / (grid - 1))));
    patches.push_back({{"patch", k},
                       {"grid", grid},
                       {"origin", {solved.origin[k][0], solved.origin[k][1]}},
                       {"points", std::move(points)}});
  }
  return Json{{"patches", std::move(patches)}}.dump() + "\n";
}

std::string bsplineInfoText(const BSplinePdeModel& model, const SolvedBSplinePde& solved,
                            const std::string& path, bool json) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  std::size_t points = 0;
  for (const BSplineSurface& s : solved.pieces) {
    // A B-spline surface lies in the convex hull of its net; the box of a dense sample is
    // the surface's own.
    constexpr int kBoxSamples = 65;
    for (int i = 0; i < kBoxSamples; ++i)
      for (int j = 0; j < kBoxSamples; ++j) {
        const Vec3 p = s.position(i / (kBoxSamples - 1.0), j / (kBoxSamples - 1.0));
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    points += s.net().points.size();
  }
  const BSplineSurface& first = solved.pieces.front();
  const double residual = worstResidual(solved);
  if (json) {
    Json j = {
        {"model", path},
        {"name", model.name},
        {"type", "bspline-pde"},
        {"form", formName(model.form)},
        {"pieces", solved.pieces.size()},
        {"control_points", {first.net().nu + 1, first.net().nv + 1}},
        {"knots", {{"u", knotName(first.uKnotType())}, {"v", knotName(first.vKnotType())}}},
        {"unknowns", std::size_t{first.net().nu - 2} * (first.net().nv - 2) * solved.pieces.size()},
        {"pde_residual", residual}};
    if (solved.c1Gap) {
      j["c1_gap_relative"] = *solved.c1Gap;
      Json seams = Json::array();
      for (const auto& [where, gap] : solved.seamGaps)
        seams.push_back({{"seam", where}, {"c1_gap_relative", gap}});
      j["seams"] = std::move(seams);
      j["constraint_residual_relative"] = *solved.constraintResidual;
      j["closed"] = solved.closedV;
    }
    j["bbox"] = {{"min", pointJson(lo)}, {"max", pointJson(hi)}};
    return j.dump(2) + "\n";
  }
  std::string out;
  out += fmt::format("model      {}{}\n", path, model.name.empty() ? "" : " (" + model.name + ")");
  out += fmt::format("type       bspline-pde ({})\n", formName(model.form));
  out += fmt::format("pieces     {}{}, {} x {} control points{}, {}\n", solved.pieces.size(),
                     solved.closedV ? " (closed in v)" : "", first.net().nu + 1, first.net().nv + 1,
                     solved.pieces.size() == 1 ? "" : " each", knotsText(first));
  out += fmt::format("PDE        largest |x_uuuvvv| {:.3g} (relative to its terms)\n", residual);
  if (solved.c1Gap) {
    std::string perSeam;
    for (const auto& [where, gap] : solved.seamGaps)
      perSeam += fmt::format("{}{}: {:.3g}", perSeam.empty() ? "" : ", ", where, gap);
    out += fmt::format("seams      C1 gap {:.3g} (relative; {}), constraint residual {:.3g}\n",
                       *solved.c1Gap, perSeam, *solved.constraintResidual);
  }
  out += fmt::format("bbox       [{}, {}, {}] to [{}, {}, {}]\n", lo.x(), lo.y(), lo.z(), hi.x(),
                     hi.y(), hi.z());
  return out;
}

}  // namespace pdesurf::cli
