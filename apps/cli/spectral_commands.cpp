#include "spectral_commands.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace pdesurf::cli {

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

std::string sampleJson(const SolvedSpectral& solved, std::uint32_t grid) {
  Json patches = Json::array();
  for (std::size_t k = 0; k < solved.patchCount(); ++k) {
    const auto [u0, u1] = solved.range(k);
    Json points = Json::array();
    for (std::uint32_t j = 0; j < grid; ++j)
      for (std::uint32_t i = 0; i < grid; ++i) {
        const double u = u0 + (u1 - u0) * static_cast<double>(i) / (grid - 1);
        const double v = 2.0 * std::numbers::pi * static_cast<double>(j) / (grid - 1);
        points.push_back(pointJson(solved.patchAt(k).position(u, v)));
      }
    patches.push_back(
        {{"patch", k}, {"grid", grid}, {"u", {u0, u1}}, {"points", std::move(points)}});
  }
  return Json{{"patches", std::move(patches)}}.dump() + "\n";
}

std::string infoText(const SolvedSpectral& solved, const std::string& path, const std::string& name,
                     bool json) {
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

std::string fitReport(const std::string& path, const std::vector<std::uint32_t>& terms,
                      bool chordLength, bool json) {
  const std::vector<CurveInput> curves = loadCurves(path);
  FourierFitOptions options;
  options.parameterization =
      chordLength ? VParameterization::ChordLength : VParameterization::Uniform;
  Json list = Json::array();
  std::string text;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const auto* sampled = std::get_if<SampledCurve>(&curves[c]);
    if (!sampled)
      throw ModelError(path, fmt::format("$.curves[{}]", c),
                       "this curve is given by Fourier coefficients already: nothing to fit");
    Json fits = Json::array();
    for (std::uint32_t n : terms) {
      FourierFit fit;
      try {
        fit = fitFourier(*sampled, n, options);
      } catch (const std::invalid_argument& e) {
        throw ModelError(path, fmt::format("$.curves[{}]", c), e.what());
      }
      fits.push_back({{"terms", n}, {"max_error", fit.maxError}, {"mean_error", fit.meanError}});
      text += fmt::format("curve {:3}  terms {:3}  max error {:<12.6g} mean error {:.6g}\n", c, n,
                          fit.maxError, fit.meanError);
    }
    list.push_back({{"curve", c}, {"points", sampled->points.size()}, {"fits", std::move(fits)}});
  }
  if (json) return Json{{"curves", std::move(list)}}.dump(2) + "\n";
  return text;
}

std::string spineJson(const SolvedSpectral& solved, std::uint32_t count) {
  Json patches = Json::array();
  for (std::size_t k = 0; k < solved.patchCount(); ++k) {
    const auto [u0, u1] = solved.range(k);
    Json us = Json::array(), points = Json::array();
    for (std::uint32_t i = 0; i < count; ++i) {
      const double u = u0 + (u1 - u0) * static_cast<double>(i) / (count - 1);
      us.push_back(u);
      points.push_back(pointJson(solved.patchAt(k).spine(u)));
    }
    patches.push_back({{"patch", k}, {"u", std::move(us)}, {"points", std::move(points)}});
  }
  return Json{{"patches", std::move(patches)}}.dump() + "\n";
}

}  // namespace pdesurf::cli
