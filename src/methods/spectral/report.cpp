// The reports of "spectral" and "cross-sections" models: `build`'s summary and quality,
// `info` (docs/spectral.md).
#include "methods/reports.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "pdesurf/model_info.hpp"

namespace pdesurf::detail {

namespace {

using Json = nlohmann::ordered_json;

/// Samples per patch side for the bounding box `info` reports: the box of these samples.
constexpr std::uint32_t kInfoBoxRows = 65, kInfoBoxColumns = 128;

std::string operatorText(const SpectralOperator& op) {
  if (op.kind == OperatorKind::Fu) return fmt::format("∂⁶u + a ∂⁶v, a = {}", op.a);
  return fmt::format("(∂²u + a² ∂²v)^{}, a = {}", op.power, op.a);
}

}  // namespace

ModelReport spectralReport(const SolvedSpectral& solved) {
  const SpectralPatch& first = solved.patchAt(0);
  ModelReport r;
  r.summary =
      fmt::format("{}, order {}, {} mode{}, {}", solved.type, first.op().order(), first.modes(),
                  first.modes() == 1 ? "" : "s", countText(solved.patchCount(), "patch"));
  double worst = 0.0;
  for (std::size_t k = 0; k < solved.patchCount(); ++k)
    for (double e : conditionErrors(solved.patchAt(k))) worst = std::max(worst, e);
  r.quality = fmt::format("condition error {:.3g}", worst);
  if (solved.chain) {
    double gap = 0.0;
    for (const JointGap& g : measureJointGaps(*solved.chain)) gap = std::max(gap, g.c0Relative);
    r.quality += fmt::format(", joint C0 gap {:.3g}", gap);
  }
  return r;
}

ModelInfo spectralInfo(const SolvedSpectral& solved) {
  // Box of a dense sample of the shown surface.
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (std::size_t k = 0; k < solved.patchCount(); ++k) {
    const auto [u0, u1] = solved.range(k);
    for (std::uint32_t i = 0; i < kInfoBoxRows; ++i)
      for (std::uint32_t j = 0; j < kInfoBoxColumns; ++j) {
        const Vec3 p = solved.patchAt(k).position(u0 + (u1 - u0) * i / (kInfoBoxRows - 1.0),
                                                  2.0 * std::numbers::pi * j / kInfoBoxColumns);
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
  }
  // Condition errors of every patch (relative, docs/spectral.md), and the joints.
  Json patchList = Json::array();
  double worstCondition = 0.0;
  for (std::size_t k = 0; k < solved.patchCount(); ++k) {
    const SpectralPatch& p = solved.patchAt(k);
    const std::vector<double> errors = conditionErrors(p);
    Json conditions = Json::array();
    for (std::size_t i = 0; i < errors.size(); ++i) {
      conditions.push_back({{"u", p.conditions()[i].u},
                            {"derivative", p.conditions()[i].derivative},
                            {"error_relative", errors[i]}});
      worstCondition = std::max(worstCondition, errors[i]);
    }
    patchList.push_back({{"patch", k},
                         {"u", {solved.range(k).first, solved.range(k).second}},
                         {"order", p.op().order()},
                         {"modes", p.modes()},
                         {"remainder", p.hasRemainder()},
                         {"conditions", std::move(conditions)}});
  }
  Json joints = Json::array();
  double c0 = 0, c1 = 0, c2 = 0;
  if (solved.chain)
    for (const JointGap& g : measureJointGaps(*solved.chain)) {
      joints.push_back({{"curve", g.curve},
                        {"c0", g.c0},
                        {"c1", g.c1},
                        {"c2", g.c2},
                        {"c0_relative", g.c0Relative},
                        {"c1_relative", g.c1Relative},
                        {"c2_relative", g.c2Relative}});
      c0 = std::max(c0, g.c0Relative);
      c1 = std::max(c1, g.c1Relative);
      c2 = std::max(c2, g.c2Relative);
    }
  // A chain's own operator: its patches' are in their local parameters.
  const SpectralOperator& op = solved.chain ? solved.chain->op : solved.patchAt(0).op();
  const SpectralPatch& first = solved.patchAt(0);
  ModelInfo info;
  info.facts = {
      {"type", "type", solved.type, ""},
      {"operator", "operator", operatorText(op),
       fmt::format("{} (order {}), {} Fourier modes{}", operatorText(op), op.order(), first.modes(),
                   first.hasRemainder() ? " + remainder" : "")},
      {"", "order", op.order(), ""},
      {"patches", "patches", solved.patchCount(), ""},
      {"conditions", "condition_error_relative", worstCondition,
       fmt::format("largest error {:.3g} (relative to the curves' size)", worstCondition)}};
  if (solved.chain)
    info.facts.push_back(
        {"joints", "", joints.size(),
         fmt::format("{} ({}): largest relative gap C0 {:.3g}, C1 {:.3g}, C2 {:.3g}", joints.size(),
                     chainMethodName(solved.chain->method), c0, c1, c2)});
  info.facts.push_back(boxFact(lo, hi));
  info.facts.push_back({"", "patch_details", std::move(patchList), ""});
  if (solved.chain) {
    info.facts.push_back({"", "method", chainMethodName(solved.chain->method), ""});
    info.facts.push_back({"", "joints", std::move(joints), ""});
  }
  return info;
}

}  // namespace pdesurf::detail
