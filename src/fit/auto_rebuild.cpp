// An automatic layout fitted and measured, and the search for the smallest one that reaches a
// target RMS both ways within the fold and normal-deviation bounds (docs/rebuild.md, "A
// target accuracy").
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <utility>

#include "fit/disk_grids.hpp"
#include "pdesurf/analysis.hpp"
#include "pdesurf/auto_layout.hpp"
#include "pdesurf/error.hpp"

namespace pdesurf {

double AutoFit::worseRms() const {
  return std::max(distance.aToB.rmsRelative, distance.bToA.rmsRelative);
}

namespace {

/// Fits `out.layout.model` to the mesh and measures the fitted model as `compare` does.
void fitAndMeasure(AutoFit& out, const Mesh& mesh, const FitOptions& fit, std::uint32_t resolution,
                   const DistanceOptions& distance) {
  out.fit = fitVertexFrames(out.layout.model, mesh, fit);
  const Mesh surface = tessellate(solve(out.fit.model), {resolution});
  out.distance = meshDistance(surface, mesh, distance);
  out.normals = normalDeviation(surface, mesh, distance.threads);
}

}  // namespace

AutoFit fitAutoLayout(const Mesh& mesh, const AutoLayoutOptions& layout, const FitOptions& fit,
                      std::uint32_t resolution, const DistanceOptions& distance,
                      const std::string& source) {
  AutoFit out;
  out.layout = autoLayout(mesh, layout, source);
  fitAndMeasure(out, mesh, fit, resolution, distance);
  return out;
}

TargetCheck checkTarget(const AutoFit& f, const TargetSearchOptions& options) {
  return {f.worseRms() <= options.targetRms, f.normals.foldedArea <= options.maxFoldedArea,
          f.normals.rmsDegrees <= options.maxNormalDeviation};
}

double storageCap(std::size_t meshBytes, const TargetSearchOptions& options) {
  if (!(options.maxStorageRatio > 0.0)) return std::numeric_limits<double>::infinity();
  return std::max(options.maxStorageRatio * double(meshBytes), double(options.minStorageCap));
}

namespace {

/// How near a fit comes to the target: all three criteria met (3), the RMS within the fold
/// bound (2), the RMS alone (1), none (0).
int rank(const TargetCheck& c) {
  if (c.all()) return 3;
  return c.rms ? 1 + int(c.folds) : 0;
}

}  // namespace

TargetSearch searchTargetRms(const Mesh& mesh, const TargetSearchOptions& options,
                             const std::string& source) {
  TargetSearch search;
  auto check = [&](const AutoFit& f) { return checkTarget(f, options); };
  auto frames = [](const AutoFit& f) { return f.layout.model.frames.size(); };
  // Of two fits, the closer to the target: the higher rank; of two within the RMS and fold
  // bounds, the one of less normal deviation; of two within the RMS alone, the less folded;
  // else the lower RMS; of two that reach the target, the smaller.
  auto closer = [&](const AutoFit& a, const AutoFit& b) {
    const int ra = rank(check(a)), rb = rank(check(b));
    if (ra != rb) return ra > rb;
    switch (ra) {
      case 3:
        return frames(a) < frames(b);
      case 2:
        return a.normals.rmsDegrees < b.normals.rmsDegrees;
      case 1:
        return a.normals.foldedArea < b.normals.foldedArea;
      default:
        return a.worseRms() < b.worseRms();
    }
  };
  // What a trial found: its closer fit (plain or guarded), what that meets, the frames made,
  // and the plain fit's normal deviation (which depends on the mesh and n alone).
  struct Trial {
    AutoFit fit;
    TargetCheck met;
    std::size_t made;
    double deviation;
  };
  // Every trial's fit is kept if it is the smallest to reach the target so far, or the
  // closest.
  std::optional<AutoFit> reached, closest;
  FitOptions guarded = options.fit;
  guarded.preventFolds = true;
  // A fit made: counted, and reported with the frames asked for.
  auto counted = [&](std::uint32_t requested, AutoFit f) {
    ++search.trials;
    if (options.onTrial) options.onTrial(requested, f);
    return f;
  };
  // `layout`'s model fitted with `fit` and measured.
  auto fitted = [&](AutoLayout layout, const FitOptions& fit) {
    AutoFit f;
    f.layout = std::move(layout);
    fitAndMeasure(f, mesh, fit, options.resolution, options.distance);
    f.foldsPrevented = fit.preventFolds;
    return f;
  };
  // The automatic layout of about `n` frames (milliseconds: made before a trial is decided
  // on).
  auto layoutOf = [&](std::uint32_t n) {
    AutoLayoutOptions layoutOptions = options.layout;
    layoutOptions.frames = n;
    return autoLayout(mesh, layoutOptions, source);
  };
  // One trial of `n` frames (`layout` is layoutOf(n)): the plain fit, and where it reaches the
  // RMS but folds beyond the bound, the same layout fitted again with the steps that fold
  // more samples refused (FitOptions::preventFolds: a higher RMS, fewer folds). It reaches the
  // target if either fit does. The outcome depends on n and the target alone, never on the
  // trials before it.
  auto trial = [&](std::uint32_t n, AutoLayout layout) {
    AutoFit plain = counted(n, fitted(std::move(layout), options.fit));
    const TargetCheck c = check(plain);
    Trial t{{}, c, frames(plain), plain.normals.rmsDegrees};
    if (c.rms && !c.folds && !options.fit.preventFolds) {
      AutoFit second = counted(n, fitted(plain.layout, guarded));
      if (closer(second, plain)) std::swap(plain, second);
      t.met = check(plain);
    }
    if (t.met.all() && (!reached || t.made < frames(*reached))) reached = plain;
    if (!closest || closer(plain, *closest)) closest = plain;
    t.fit = std::move(plain);
    return t;
  };
  // Grow from the first count by `growth` until a trial reaches the target (or the layout
  // stops growing: the mesh is simplified no more). The counts tried depend on the mesh
  // alone (a layout that makes more frames than asked for, held by creases, is grown from
  // the frames it made), not on the target, so a looser target's first reaching count is
  // never above a tighter one's.
  std::uint32_t miss = 0, hit = 0;
  std::uint32_t n = std::max(options.firstFrames, kFewestFrames);
  AutoLayout layout = layoutOf(n);
  std::uint32_t firstRms = 0;  // the first count that reached the RMS (missing a bound)
  std::optional<Trial> previous;
  std::optional<AutoFit> beforeStall;  // the trial before the deviation stalled
  // Past the RMS, no layout whose model would take more bytes than this.
  const double cap = storageCap(storageBytes(mesh), options);
  bool capped = false;  // this trial's layout is the largest under the storage cap
  search.stop = TargetSearch::Stop::LayoutStopped;
  for (;;) {
    Trial t = trial(n, std::move(layout));
    if (t.met.all()) {
      hit = n;
      search.stop = TargetSearch::Stop::Reached;
      break;
    }
    // A layout that made more frames than asked for stands for every count up to them.
    const auto stands = static_cast<std::uint32_t>(std::max<std::size_t>(n, t.made));
    if (t.met.rms && firstRms == 0) firstRms = stands;
    miss = stands;
    if (capped) {
      search.stop = TargetSearch::Stop::StorageLimit;
      break;
    }
    // Within the RMS and fold bounds, but the deviation fell by less than kNormalStall a
    // doubling: more frames will not bring it within its bound.
    if (previous && t.met.rms && t.met.folds &&
        t.deviation >
            previous->deviation *
                std::pow(1.0 - kNormalStall, std::log2(double(t.made) / double(previous->made)))) {
      search.stop = TargetSearch::Stop::NormalsStalled;
      const bool before = previous->met.rms && previous->met.folds;
      beforeStall = std::move(before ? previous->fit : t.fit);
      break;
    }
    if (n >= options.maxFrames) break;
    n = static_cast<std::uint32_t>(
        std::min<double>(options.maxFrames, std::ceil(stands * options.growth)));
    if (firstRms > 0 && n > kGrowthPastRms * firstRms) {
      search.stop = TargetSearch::Stop::GrowthLimit;
      break;
    }
    layout = layoutOf(n);
    // The mesh is simplified no further: the same layout again would fit the same model.
    if (layout.model.frames.size() <= t.made) break;
    // Past the RMS, a layout over the storage cap is shrunk (its count scaled by the cap over
    // its bytes, a few times) to the largest under it, which is tried last; where none is
    // larger than this trial's, the search stops here.
    if (firstRms > 0 && std::isfinite(cap)) {
      double bytes = double(storageBytes(layout.model));
      if (bytes > cap) {
        for (int k = 0; k < 8 && bytes > cap && n > stands; ++k) {
          n = std::max(stands, static_cast<std::uint32_t>(n * cap / bytes));
          layout = layoutOf(n);
          bytes = double(storageBytes(layout.model));
        }
        if (bytes > cap || layout.model.frames.size() <= t.made) {
          search.stop = TargetSearch::Stop::StorageLimit;
          break;
        }
        capped = true;
      }
    }
    previous = std::move(t);
  }
  // Bisect (geometrically) between the largest count that missed and the smallest that
  // reached, until they are within `precision` of each other.
  while (hit > 0 && miss > 0 && hit > miss * (1.0 + options.precision)) {
    const auto mid = static_cast<std::uint32_t>(std::lround(std::sqrt(double(miss) * hit)));
    if (mid <= miss || mid >= hit) break;
    const Trial t = trial(mid, layoutOf(mid));
    if (t.met.all())
      hit = mid;
    else
      miss = static_cast<std::uint32_t>(std::clamp<std::size_t>(t.made, mid, hit - 1));
  }
  search.best = std::move(reached ? *reached : beforeStall ? *beforeStall : *closest);
  // The disk's n × n grids with fewer frames than that answer: the first in the sequence
  // 2, 3, 5, 8, 12, 17, ... (each the last times √2, rounded up; the answer's frames cap it)
  // that meets the target, bisected against the largest before it that missed. A grid that
  // meets it answers where its model takes fewer bytes than the automatic layout's (or that
  // one misses). The plain fit alone: the guarded second fit would double the grids' cost.
  if (options.tryGrid && mesh.triangleCount() > 0) {
    const std::size_t cap = frames(search.best);
    std::unique_ptr<detail::DiskGrids> disk;  // parameterised once, at the first grid
    auto gridTrial = [&](std::uint32_t side) -> std::optional<AutoFit> {
      if (!disk) try {
          disk = std::make_unique<detail::DiskGrids>(mesh, source);
        } catch (const LayoutError&) {
          return std::nullopt;  // not a disk
        }
      AutoLayout grid;
      grid.model = disk->grid({side, side});
      grid.components = 1;
      AutoFit f = fitted(std::move(grid), options.fit);
      f.grid = side;
      return counted(side * side, std::move(f));
    };
    std::optional<AutoFit> gridHit;
    std::uint32_t gridMiss = 1, side = 2;
    while (std::size_t{side} * side < cap) {
      std::optional<AutoFit> f = gridTrial(side);
      if (!f) break;
      if (check(*f).all()) {
        gridHit = std::move(f);
        break;
      }
      gridMiss = side;
      side = std::max(side + 1, static_cast<std::uint32_t>(std::ceil(side * std::sqrt(2.0))));
    }
    while (gridHit && gridHit->grid > gridMiss + 1) {
      const std::uint32_t mid = (gridMiss + gridHit->grid) / 2;
      std::optional<AutoFit> f = gridTrial(mid);
      if (f && check(*f).all())
        gridHit = std::move(f);
      else
        gridMiss = mid;
    }
    if (gridHit && (!check(search.best).all() ||
                    storageBytes(gridHit->fit.model) < storageBytes(search.best.fit.model)))
      search.best = std::move(*gridHit);
  }
  search.met = check(search.best);
  search.reached = search.met.all();
  search.missedBelow = miss;
  return search;
}

}  // namespace pdesurf
