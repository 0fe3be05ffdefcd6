#include "rebuild_auto.hpp"

#include <algorithm>
#include <cstdio>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "distance_report.hpp"

namespace pdesurf::cli {

namespace {

/// A layout this many times larger than the frames asked for was held by its kept edges.
constexpr std::size_t kHeldLayoutFactor = 2;

std::string madeLine(const AutoLayoutReport& a) {
  if (a.grid > 0)
    return fmt::format(
        "{}: the disk's {} × {} grid, which meets the target in fewer bytes than "
        "the automatic layout",
        count(a.frames, "frame"), a.grid, a.grid);
  return fmt::format(
      "{} from {} of the mesh simplified by Garland–Heckbert quadrics, {} ({} in one model), "
      "{} kept on frame edges{}",
      count(a.frames, "frame"), count(a.baseTriangles, "triangle"),
      count(a.components, "component"), a.components == 1 ? "it" : "all",
      count(a.creaseEdges, "crease or boundary edge"),
      a.skippedTriangles == 0
          ? ""
          : fmt::format(" ({} without area left out)", count(a.skippedTriangles, "triangle")));
}

/// "0.1% folded and 10° normal deviation".
std::string boundsText(double maxFoldedArea, double maxNormalDeviation) {
  return fmt::format("{} folded and {:g}° normal deviation", percent(maxFoldedArea),
                     maxNormalDeviation);
}

}  // namespace

void AutoLayoutArgs::add(CLI::App* cmd) {
  cmd->add_option("--frames", frames,
                  "vertex-frames: about N frames in the automatic layout (the default without "
                  "--layout, --grid and --tube; " +
                      std::to_string(kDefaultAutoFrames) + " if neither this nor --target-rms)")
      ->check(CLI::Range(1u, 1000000u));
  cmd->add_option("--target-rms", targetRms,
                  "vertex-frames: the smallest automatic layout whose fitted model's RMS "
                  "distance both ways is at most X of the mesh's bounding-box diagonal (0.002 "
                  "or 0.2%)");
  cmd->add_option("--quads", quads,
                  "vertex-frames, automatic layout: pair (simplified triangles paired into quads, "
                  "each quad split into four, the others into three) or split (each simplified "
                  "triangle into three quads)")
      ->check(CLI::IsMember({"split", "pair"}));
  cmd->add_option("--crease-angle", creaseAngle,
                  "vertex-frames, automatic layout: edges whose triangles' normals differ by "
                  "more than this (degrees, default 60) stay on frame edges")
      ->check(CLI::Range(0.0, 180.0));
  maxNormalDeviationOption = cmd->add_option(
      "--max-normal-deviation", maxNormalDeviation,
      fmt::format("vertex-frames, --target-rms: the model's RMS normal deviation (degrees, "
                  "against the mesh's normals, as compare measures it) at most this too "
                  "(default {:g}; 180: no bound)",
                  kMaxNormalDeviation));
}

void AutoLayoutArgs::apply(RebuildOptions& options) const {
  options.frames = frames;
  if (!targetRms.empty()) options.targetRms = parseTargetRms(targetRms);
  if (!quads.empty()) options.quads = parseQuadConstruction(quads);
  if (creaseAngle >= 0.0) options.creaseAngle = creaseAngle;
  if (maxNormalDeviationOption != nullptr && maxNormalDeviationOption->count() > 0)
    options.maxNormalDeviation = maxNormalDeviation;
}

void printAutomaticLayout(const AutoLayoutReport& layout) {
  fmt::print("automatic layout (about {} asked for): {}\n", count(layout.requested, "frame"),
             madeLine(layout));
  // The simplification stops where it would move a kept edge (a crease, a boundary) or
  // merge a component away: say why the layout is larger than asked, and what lets it go.
  if (layout.frames > kHeldLayoutFactor * layout.requested && layout.creaseEdges > 0)
    fmt::print(
        "  (the kept edges and the components hold the layout at {}, more than {} times the {} "
        "asked for; a larger --crease-angle lets creases go, 180 keeps the boundaries alone)\n",
        count(layout.frames, "frame"), kHeldLayoutFactor, layout.requested);
}

void printTrial(const RebuildOptions& options, std::uint32_t requested, const AutoFit& f) {
  const TargetSearchOptions search = targetSearchOptions(options);
  const TargetCheck met = checkTarget(f, search);
  std::string verdict;
  if (!met.rms)
    verdict = fmt::format("misses {}", percent(search.targetRms));
  else if (met.all())
    verdict = fmt::format("reaches {} within {}", percent(search.targetRms),
                          boundsText(search.maxFoldedArea, search.maxNormalDeviation));
  else
    verdict = fmt::format("reaches {} but {}", percent(search.targetRms),
                          !met.folds
                              ? fmt::format("folds more than {}", percent(search.maxFoldedArea))
                              : fmt::format("deviates more than {:g}°", search.maxNormalDeviation));
  const std::string layout = f.grid > 0
                                 ? fmt::format("the disk's {} × {} grid", f.grid, f.grid)
                                 : fmt::format("{} asked for, {} made", count(requested, "frame"),
                                               f.layout.model.frames.size());
  fmt::print(
      "trial: {}{}: model -> mesh RMS {}, mesh -> model RMS {}, folded {}, "
      "normals {:.3g}° ({})\n",
      layout, f.foldsPrevented && !options.fit.preventFolds ? ", steps that fold more refused" : "",
      percent(f.distance.aToB.rmsRelative), percent(f.distance.bToA.rmsRelative),
      percent(f.normals.foldedArea), f.normals.rmsDegrees, verdict);
  // A search runs for minutes: each trial's line goes out as it ends, also into a pipe or a
  // log file (where stdout is fully buffered).
  std::fflush(stdout);
}

void printSearch(const RebuildOptions& options, const RebuildReport& report) {
  const TargetSearchReport& s = *report.search;
  const TargetSearchOptions search = targetSearchOptions(options);
  const AutoLayoutReport& best = *report.automatic;
  const std::string bounds = boundsText(s.maxFoldedArea, s.maxNormalDeviation);
  const std::string answer =
      fmt::format("{} folds {} and deviates {:.3g}°", count(best.frames, "frame"),
                  percent(s.foldedArea), s.normalDeviation);
  if (s.reached)
    fmt::print(
        "target RMS {} reached both ways within {} with {}{} ({} tried): {}\n",
        percent(s.targetRms), bounds, count(best.frames, "frame"),
        s.foldsPrevented && !options.fit.preventFolds ? " (steps that fold more refused)" : "",
        count(s.trials, "layout"), madeLine(best));
  else if (s.stop == TargetSearch::Stop::NormalsStalled)
    fmt::print(
        "target RMS {} reached both ways within {} folded, but NOT the normal deviation of "
        "{:g}° ({} tried): it fell by less than {:g}% a doubling of the frames; the layout "
        "before that step, {}\n",
        percent(s.targetRms), percent(s.maxFoldedArea), s.maxNormalDeviation,
        count(s.trials, "layout"), 100 * kNormalStall, answer);
  else if (s.stop == TargetSearch::Stop::StorageLimit)
    fmt::print(
        "target RMS {} reached both ways, but NOT within {} ({} tried): a larger layout's "
        "model would take more than {:.0f} bytes ({:g}x the mesh's storage, at least {}); the "
        "closest, {} (--frames N fits a layout of any size)\n",
        percent(s.targetRms), bounds, count(s.trials, "layout"),
        storageCap(report.referenceStorageBytes, search), search.maxStorageRatio,
        search.minStorageCap, answer);
  else if (s.met.rms)
    fmt::print(
        "target RMS {} reached both ways, but NOT within {} ({} tried, up to {}x the smallest "
        "that reached the RMS{}): the closest, {}\n",
        percent(s.targetRms), bounds, count(s.trials, "layout"), kGrowthPastRms,
        s.stop == TargetSearch::Stop::LayoutStopped ? "; the layout grows no further" : "", answer);
  else
    fmt::print(
        "target RMS {} NOT reached ({} tried; the layout grows no further): the closest, {}, "
        "has {} (worse way)\n",
        percent(s.targetRms), count(s.trials, "layout"), count(best.frames, "frame"),
        percent(s.worseRms));
}

void printStorageAgainstMesh(const RebuildReport& report) {
  fmt::print("mesh storage   {} bytes (the model is {:.3g}x of it)\n", report.referenceStorageBytes,
             double(report.storageBytes) / double(report.referenceStorageBytes));
}

}  // namespace pdesurf::cli
