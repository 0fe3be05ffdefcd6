// The reports of "spectral" and "cross-sections" models: `build`'s summary and quality,
// `info` (docs/spectral.md).
#include "methods/reports.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace pdesurf::detail {

namespace {

using Json = nlohmann::ordered_json;

Json pointJson(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

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

std::string spectralInfo(const SolvedSpectral& solved, const std::string& path,
                         const std::string& name, bool json) {
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
  if (json) {
    Json j = {{"model", path},
              {"name", name},
              {"type", solved.type},
              {"operator", operatorText(op)},
              {"order", op.order()},
              {"patches", solved.patchCount()},
              {"condition_error_relative", worstCondition},
              {"bbox", {{"min", pointJson(lo)}, {"max", pointJson(hi)}}},
              {"patch_details", std::move(patchList)}};
    if (solved.chain) {
      j["method"] = chainMethodName(solved.chain->method);
      j["joints"] = std::move(joints);
    }
    return j.dump(2) + "\n";
  }
  std::string out;
  out += fmt::format("model      {}{}\n", path, name.empty() ? "" : " (" + name + ")");
  out += fmt::format("type       {}\n", solved.type);
  out += fmt::format("operator   {} (order {}), {} Fourier modes{}\n", operatorText(op), op.order(),
                     solved.patchAt(0).modes(),
                     solved.patchAt(0).hasRemainder() ? " + remainder" : "");
  out += fmt::format("patches    {}\n", solved.patchCount());
  out += fmt::format("conditions largest error {:.3g} (relative to the curves' size)\n",
                     worstCondition);
  if (solved.chain)
    out += fmt::format("joints     {} ({}): largest relative gap C0 {:.3g}, C1 {:.3g}, C2 {:.3g}\n",
                       joints.size(), chainMethodName(solved.chain->method), c0, c1, c2);
  out += fmt::format("bbox       [{}, {}, {}] to [{}, {}, {}]\n", lo.x(), lo.y(), lo.z(), hi.x(),
                     hi.y(), hi.z());
  return out;
}

}  // namespace pdesurf::detail
