// report() and infoText() of the model layer (include/pdesurf/model.hpp) through the model's
// method, and the SurfaceMethod defaults (method.hpp) a method without its own report takes;
// the built-in methods' reports are in src/methods/.
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "pdesurf/method.hpp"

namespace pdesurf {

std::string countText(std::size_t n, const std::string& noun) {
  if (n == 1) return "1 " + noun;
  if (noun == "vertex") return fmt::format("{} vertices", n);
  return fmt::format("{} {}{}", n, noun, noun.ends_with("ch") ? "es" : "s");
}

ModelReport report(const SolvedModel& solved) { return solved.model().method().report(solved); }

std::string infoText(const SolvedModel& solved, bool json) {
  return solved.model().method().info(solved, json);
}

ModelReport SurfaceMethod::report(const SolvedModel& solved) const {
  return {fmt::format("{}, {}", typeName(), countText(solved.surface().patchCount(), "patch")),
          fmt::format("C0 gap {:.3g}", solved.surface().largestC0Gap())};
}

std::string SurfaceMethod::info(const SolvedModel& solved, bool json) const {
  // The box of the samples at this many per patch side.
  constexpr std::uint32_t kInfoBoxSamples = 33;
  const SolvedSurface& surface = solved.surface();
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const PatchSamples& patch : surface.sample(SampleOptions{kInfoBoxSamples}))
    for (const Vec3& p : patch.points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  const std::string& name = this->name(solved.model());
  const double gap = surface.largestC0Gap();
  if (json) {
    const nlohmann::ordered_json j = {
        {"model", solved.source()},
        {"name", name},
        {"type", typeName()},
        {"patches", surface.patchCount()},
        {"c0_gap", gap},
        {"bbox", {{"min", {lo.x(), lo.y(), lo.z()}}, {"max", {hi.x(), hi.y(), hi.z()}}}}};
    return j.dump(2) + "\n";
  }
  std::string out;
  out += fmt::format("model      {}{}\n", solved.source(), name.empty() ? "" : " (" + name + ")");
  out += fmt::format("type       {}\npatches    {}\nC0 gap     {}\n", typeName(),
                     surface.patchCount(), gap);
  out += fmt::format("bbox       [{}, {}, {}] to [{}, {}, {}]\n", lo.x(), lo.y(), lo.z(), hi.x(),
                     hi.y(), hi.z());
  return out;
}

}  // namespace pdesurf
