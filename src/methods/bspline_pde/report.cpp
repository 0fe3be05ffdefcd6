// The reports of "bspline-pde" models: `build`'s summary and quality, `info`.
#include "methods/reports.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "pdesurf/model_info.hpp"

namespace pdesurf::detail {
namespace {

using Json = nlohmann::ordered_json;

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

ModelReport bsplineReport(const SolvedBSplinePde& solved) {
  const BSplineSurface& s = solved.pieces.front();
  ModelReport r;
  r.summary =
      fmt::format("bspline-pde, {} piece{}, {} x {} control points{}, {}", solved.pieces.size(),
                  solved.pieces.size() == 1 ? "" : "s", s.net().nu + 1, s.net().nv + 1,
                  solved.pieces.size() == 1 ? "" : " each", knotsText(s));
  r.quality = fmt::format("PDE residual {:.3g}", worstResidual(solved));
  if (solved.c1Gap) r.quality += fmt::format(", C1 gap {:.3g}", *solved.c1Gap);
  return r;
}

ModelInfo bsplineInfo(const BSplinePdeModel& model, const SolvedBSplinePde& solved) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
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
  }
  const BSplineSurface& first = solved.pieces.front();
  const double residual = worstResidual(solved);
  ModelInfo info;
  info.facts = {
      {"type", "type", "bspline-pde", fmt::format("bspline-pde ({})", formName(model.form))},
      {"", "form", formName(model.form), ""},
      {"pieces", "pieces", solved.pieces.size(),
       fmt::format("{}{}, {} x {} control points{}, {}", solved.pieces.size(),
                   solved.closedV ? " (closed in v)" : "", first.net().nu + 1, first.net().nv + 1,
                   solved.pieces.size() == 1 ? "" : " each", knotsText(first))},
      {"", "control_points", Json::array({first.net().nu + 1, first.net().nv + 1}), ""},
      {"", "knots", {{"u", knotName(first.uKnotType())}, {"v", knotName(first.vKnotType())}}, ""},
      {"", "unknowns",
       std::size_t{first.net().nu - 2} * (first.net().nv - 2) * solved.pieces.size(), ""},
      {"PDE", "pde_residual", residual,
       fmt::format("largest |x_uuuvvv| {:.3g} (relative to its terms)", residual)}};
  if (solved.c1Gap) {
    Json seams = Json::array();
    std::string perSeam;
    for (const auto& [where, gap] : solved.seamGaps) {
      seams.push_back({{"seam", where}, {"c1_gap_relative", gap}});
      perSeam += fmt::format("{}{}: {:.3g}", perSeam.empty() ? "" : ", ", where, gap);
    }
    info.facts.push_back({"seams", "c1_gap_relative", *solved.c1Gap,
                          fmt::format("C1 gap {:.3g} (relative; {}), constraint residual {:.3g}",
                                      *solved.c1Gap, perSeam, *solved.constraintResidual)});
    info.facts.push_back({"", "seams", std::move(seams), ""});
    info.facts.push_back({"", "constraint_residual_relative", *solved.constraintResidual, ""});
    info.facts.push_back({"", "closed", solved.closedV, ""});
  }
  info.facts.push_back(boxFact(lo, hi));
  return info;
}

}  // namespace pdesurf::detail
