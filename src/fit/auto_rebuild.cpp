// An automatic layout fitted and measured, and the search for the smallest one that reaches a
// target RMS both ways within the fold bound (docs/rebuild.md, "A target accuracy").
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "pdesurf/auto_layout.hpp"

namespace pdesurf {

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
  auto reached = [&](const AutoFit& f) { return rmsReached(f) && foldFree(f); };
  auto frames = [](const AutoFit& f) { return f.layout.model.frames.size(); };
  // Of two trials that miss, the closer: one that reaches the RMS (folding more than the
  // bound) before one that does not; of two that reach it, the less folded; else the lower
  // RMS.
  auto closer = [&](const AutoFit& a, const AutoFit& b) {
    if (rmsReached(a) != rmsReached(b)) return rmsReached(a);
    return rmsReached(a) ? a.normals.foldedArea < b.normals.foldedArea
                         : a.worseRms() < b.worseRms();
  };
  // Every fit is kept if it is the smallest to reach both so far (`both`), or the closest.
  std::optional<AutoFit> both, closest;
  struct Outcome {
    bool reached, rmsReached;  ///< the target (RMS within the fold bound), the RMS alone
    std::size_t made;          ///< frames made
  };
  FitOptions guarded = options.fit;
  guarded.preventFolds = true;
  auto fit = [&](std::uint32_t n, bool prevent) {
    AutoLayoutOptions layout = options.layout;
    layout.frames = n;
    AutoFit f = fitAutoLayout(mesh, layout, prevent ? guarded : options.fit, options.resolution,
                              options.distance, source);
    f.foldsPrevented = prevent || options.fit.preventFolds;
    ++search.trials;
    if (options.onTrial) options.onTrial(n, f);
    const Outcome out{reached(f), rmsReached(f), frames(f)};
    if (out.reached && (!both || out.made < frames(*both))) both = f;
    if (!closest || closer(f, *closest)) closest = std::move(f);
    return out;
  };
  // One trial of `n` frames: the plain fit, and where it reaches the RMS but folds, the same
  // layout fitted again with the steps that fold more samples refused (FitOptions::
  // preventFolds: a higher RMS, fewer folds). It reaches the target if either fit does. The
  // outcome depends on n and the target alone, never on the trials before it.
  auto trial = [&](std::uint32_t n) {
    Outcome out = fit(n, false);
    if (!out.reached && out.rmsReached && !options.fit.preventFolds)
      out.reached = fit(n, true).reached;
    return out;
  };
  // Grow from the first count by `growth` until a trial reaches the target (or the layout
  // stops growing: the mesh is simplified no more). The counts tried depend on the mesh
  // alone (a layout that makes more frames than asked for, held by creases, is grown from
  // the frames it made), not on the target, so a looser target's first reaching count is
  // never above a tighter one's.
  std::uint32_t miss = 0, hit = 0;
  std::uint32_t n = std::max(options.firstFrames, kFewestFrames);
  std::uint32_t firstRms = 0;  // the first count that reached the RMS (folding beyond the bound)
  std::size_t previous = 0;
  for (;;) {
    const Outcome out = trial(n);
    if (out.reached) {
      hit = n;
      break;
    }
    // A layout that made more frames than asked for stands for every count up to them.
    const auto stands = static_cast<std::uint32_t>(std::max<std::size_t>(n, out.made));
    if (out.rmsReached && firstRms == 0) firstRms = stands;
    miss = stands;
    if (out.made <= previous || n >= options.maxFrames) break;
    previous = out.made;
    n = static_cast<std::uint32_t>(
        std::min<double>(options.maxFrames, std::ceil(stands * options.growth)));
    if (firstRms > 0 && n > kFoldGrowthLimit * firstRms) break;
  }
  // Bisect (geometrically) between the largest count that missed and the smallest that
  // reached, until they are within `precision` of each other.
  while (hit > 0 && miss > 0 && hit > miss * (1.0 + options.precision)) {
    const auto mid = static_cast<std::uint32_t>(std::lround(std::sqrt(double(miss) * hit)));
    if (mid <= miss || mid >= hit) break;
    const Outcome out = trial(mid);
    if (out.reached)
      hit = mid;
    else
      miss = static_cast<std::uint32_t>(std::clamp<std::size_t>(out.made, mid, hit - 1));
  }
  search.best = std::move(both ? *both : *closest);
  search.rmsReached = rmsReached(search.best);
  search.reached = search.rmsReached && foldFree(search.best);
  search.missedBelow = miss;
  return search;
}

}  // namespace pdesurf
