// An automatic layout fitted and measured, and the search for the smallest one that reaches a
// target RMS both ways (docs/rebuild.md, "A target accuracy").
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "pdesurf/auto_layout.hpp"

namespace pdesurf {

namespace {

/// No layout is asked for with fewer frames than this: the fewest a closed surface's
/// simplification can give (a tetrahedron's four triangles, three quads each).
constexpr std::uint32_t kFewestFrames = 12;

}  // namespace

double AutoFit::worseRms() const {
  return std::max(distance.aToB.rmsRelative, distance.bToA.rmsRelative);
}

AutoFit fitAutoLayout(const Mesh& mesh, const AutoLayoutOptions& layout, const FitOptions& fit,
                      std::uint32_t resolution, const DistanceOptions& distance,
                      const std::string& source) {
  AutoFit out;
  out.layout = autoLayout(mesh, layout, source);
  out.fit = fitVertexFrames(out.layout.model, mesh, fit);
  out.distance = meshDistance(tessellate(solve(out.fit.model), {resolution}), mesh, distance);
  return out;
}

TargetSearch searchTargetRms(const Mesh& mesh, const TargetSearchOptions& options,
                             const std::string& source) {
  TargetSearch search;
  auto trial = [&](std::uint32_t frames) {
    AutoLayoutOptions layout = options.layout;
    layout.frames = frames;
    AutoFit f =
        fitAutoLayout(mesh, layout, options.fit, options.resolution, options.distance, source);
    ++search.trials;
    if (options.onTrial) options.onTrial(frames, f);
    return f;
  };
  auto reaches = [&](const AutoFit& f) { return f.worseRms() <= options.targetRms; };
  // The bracket: `miss` frames miss the target (0: none tried), `hit` reach it.
  std::uint32_t miss = 0, hit = 0;
  std::optional<AutoFit> hitFit, closest;
  auto keepClosest = [&](AutoFit&& f) {
    if (!closest || f.worseRms() < closest->worseRms()) closest = std::move(f);
  };
  std::uint32_t n = std::max(options.layout.frames, kFewestFrames);
  AutoFit first = trial(n);
  if (reaches(first)) {
    // Shrink until a layout misses, or the layout stops shrinking.
    hit = n;
    std::size_t made = first.layout.model.frames.size();
    hitFit = std::move(first);
    while (hit > kFewestFrames) {
      n = std::max(kFewestFrames, static_cast<std::uint32_t>(std::floor(hit / options.growth)));
      AutoFit f = trial(n);
      if (f.layout.model.frames.size() >= made) break;
      made = f.layout.model.frames.size();
      if (!reaches(f)) {
        miss = n;
        break;
      }
      hit = n;
      hitFit = std::move(f);
    }
  } else {
    // Grow until a layout reaches it, or the layout stops growing (the mesh itself).
    miss = n;
    std::size_t made = first.layout.model.frames.size();
    keepClosest(std::move(first));
    while (n < options.maxFrames) {
      n = std::min(options.maxFrames, static_cast<std::uint32_t>(std::ceil(n * options.growth)));
      AutoFit f = trial(n);
      if (reaches(f)) {
        hit = n;
        hitFit = std::move(f);
        break;
      }
      miss = n;
      const bool grew = f.layout.model.frames.size() > made;
      made = f.layout.model.frames.size();
      keepClosest(std::move(f));
      if (!grew) break;
    }
  }
  if (!hitFit) {
    search.best = std::move(*closest);
    return search;
  }
  // Bisect (geometrically) between the counts that miss and reach.
  while (miss > 0 && hit > miss * (1.0 + options.precision)) {
    const auto mid = static_cast<std::uint32_t>(std::lround(std::sqrt(double(miss) * hit)));
    if (mid <= miss || mid >= hit) break;
    AutoFit f = trial(mid);
    if (reaches(f) && f.layout.model.frames.size() <= hitFit->layout.model.frames.size()) {
      hit = mid;
      hitFit = std::move(f);
    } else {
      miss = mid;
    }
  }
  search.best = std::move(*hitFit);
  search.reached = true;
  return search;
}

}  // namespace pdesurf
