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

}  // namespace

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
      } catch (const InvalidArgument& e) {
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
