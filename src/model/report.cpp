// report() (include/pdesurf/model.hpp) and modelInfo() (model_info.hpp) of the model layer
// through the model's method, and the SurfaceMethod defaults (method.hpp) a method without its
// own report or info takes; the built-in methods' are in src/methods/. The info's listing and
// JSON are the front ends' (apps/cli/info_command.cpp).
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "pdesurf/method.hpp"
#include "pdesurf/model_info.hpp"

namespace pdesurf {

std::string countText(std::size_t n, const std::string& noun) {
  if (n == 1) return "1 " + noun;
  if (noun == "vertex") return fmt::format("{} vertices", n);
  return fmt::format("{} {}{}", n, noun, noun.ends_with("ch") ? "es" : "s");
}

ModelReport report(const SolvedModel& solved) { return solved.model().method().report(solved); }

ModelInfo modelInfo(const SolvedModel& solved) {
  const SurfaceMethod& method = solved.model().method();
  ModelInfo info = method.info(solved);
  info.source = solved.source();
  info.name = method.name(solved.model());
  return info;
}

const InfoFact* ModelInfo::find(std::string_view key) const {
  for (const InfoFact& fact : facts)
    if (fact.key == key) return &fact;
  return nullptr;
}

InfoFact boxFact(const Vec3& min, const Vec3& max) {
  return {"bbox", "bbox",
          nlohmann::ordered_json{{"min", {min.x(), min.y(), min.z()}},
                                 {"max", {max.x(), max.y(), max.z()}}},
          ""};
}

ModelReport SurfaceMethod::report(const SolvedModel& solved) const {
  return {fmt::format("{}, {}", typeName(), countText(solved.surface().patchCount(), "patch")),
          fmt::format("C0 gap {:.3g}", solved.surface().largestC0Gap())};
}

ModelInfo SurfaceMethod::info(const SolvedModel& solved) const {
  // The box of the samples at this many per patch side.
  constexpr std::uint32_t kInfoBoxSamples = 33;
  const SolvedSurface& surface = solved.surface();
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const PatchSamples& patch : surface.sample(SampleOptions{kInfoBoxSamples}))
    for (const Vec3& p : patch.points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  ModelInfo info;
  info.facts = {{"type", "type", typeName(), ""},
                {"patches", "patches", surface.patchCount(), ""},
                {"C0 gap", "c0_gap", surface.largestC0Gap(), ""},
                boxFact(lo, hi)};
  return info;
}

}  // namespace pdesurf
