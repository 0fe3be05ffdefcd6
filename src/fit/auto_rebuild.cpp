// An automatic layout fitted and measured, and the search for the smallest one that reaches a
// target RMS both ways within the fold bound (docs/rebuild.md, "A target accuracy").
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
  const Mesh surface = tessellate(solve(out.fit.model), {resolution});
  out.distance = meshDistance(surface, mesh, distance);
  out.normals = normalDeviation(surface, mesh, distance.threads);
  return out;
}

TargetSearch searchTargetRms(const Mesh& mesh, const TargetSearchOptions& options,
                             const std::string& source) {
  TargetSearch search;
  auto rmsReached = [&](const AutoFit& f) { return f.worseRms() <= options.targetRms; };
  auto foldFree = [&](const AutoFit& f) { return f.normals.foldedArea <= options.maxFoldedArea; };
  auto frames = [](const AutoFit& f) { return f.layout.model.frames.size(); };
  // Of two trials that miss, the closer: one that reaches the RMS (folding more than the
  // bound) before one that does not; of two that reach it, the less folded; else the lower
  // RMS.
  auto closer = [&](const AutoFit& a, const AutoFit& b) {
    if (rmsReached(a) != rmsReached(b)) return rmsReached(a);
    return rmsReached(a) ? a.normals.foldedArea < b.normals.foldedArea
                         : a.worseRms() < b.worseRms();
  };
  // Every trial is kept if it is the smallest to reach both so far (`both`), or the closest.
  std::optional<AutoFit> both, closest;
  FitOptions guarded = options.fit;
  guarded.preventFolds = true;
  auto trial = [&](std::uint32_t n, bool prevent = false) {
    AutoLayoutOptions layout = options.layout;
    layout.frames = n;
    AutoFit f = fitAutoLayout(mesh, layout, prevent ? guarded : options.fit, options.resolution,
                              options.distance, source);
    f.foldsPrevented = prevent || options.fit.preventFolds;
    ++search.trials;
    if (options.onTrial) options.onTrial(n, f);
    if (rmsReached(f) && foldFree(f) && (!both || frames(f) < frames(*both))) both = f;
    if (!closest || closer(f, *closest)) closest = f;
    return f;
  };
  // First the RMS alone. The bracket: `miss` frames miss it (0: none tried), `hit` reach it.
  std::uint32_t miss = 0, hit = 0;
  std::optional<AutoFit> hitFit;
  std::uint32_t n = std::max(options.layout.frames, kFewestFrames);
  AutoFit first = trial(n);
  if (rmsReached(first)) {
    // Shrink until a layout misses, or the layout stops shrinking.
    hit = n;
    std::size_t made = frames(first);
    hitFit = std::move(first);
    while (hit > kFewestFrames) {
      n = std::max(kFewestFrames, static_cast<std::uint32_t>(std::floor(hit / options.growth)));
      AutoFit f = trial(n);
      if (frames(f) >= made) break;
      made = frames(f);
      if (!rmsReached(f)) {
        miss = n;
        break;
      }
      hit = n;
      hitFit = std::move(f);
    }
  } else {
    // Grow until a layout reaches it, or the layout stops growing (the mesh itself).
    miss = n;
    std::size_t made = frames(first);
    while (n < options.maxFrames) {
      n = std::min(options.maxFrames, static_cast<std::uint32_t>(std::ceil(n * options.growth)));
      AutoFit f = trial(n);
      if (rmsReached(f)) {
        hit = n;
        hitFit = std::move(f);
        break;
      }
      miss = n;
      const bool grew = frames(f) > made;
      made = frames(f);
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
    if (rmsReached(f) && frames(f) <= frames(*hitFit)) {
      hit = mid;
      hitFit = std::move(f);
    } else {
      miss = mid;
    }
  }
  // Then the folds: the smallest layout that reaches the RMS may fold more than the bound
  // (folds do not fall monotonically with the frame count). Such a layout is fitted again
  // with the steps that fold more samples refused (FitOptions::preventFolds: a higher RMS,
  // fewer folds), and the count grows from the smallest by sqrt(growth) a step, up to
  // kFoldGrowthLimit times it, each count fitted plainly and, where that reaches the RMS
  // folded, guarded too, until some trial (this one or an earlier, larger one) reaches both.
  if (!foldFree(*hitFit)) {
    const double step = std::sqrt(options.growth);
    for (n = hit; n <= kFoldGrowthLimit * hit && n <= options.maxFrames;
         n = static_cast<std::uint32_t>(std::ceil(n * step))) {
      if (both && frames(*both) <= n) break;
      const bool folded = n == hit || [&] {
        const AutoFit f = trial(n);
        return rmsReached(f) && !foldFree(f);
      }();
      if (folded && !options.fit.preventFolds && !(both && frames(*both) <= n)) trial(n, true);
    }
  }
  search.best = std::move(both ? *both : *closest);
  search.rmsReached = rmsReached(search.best);
  search.reached = search.rmsReached && foldFree(search.best);
  return search;
}

}  // namespace pdesurf
