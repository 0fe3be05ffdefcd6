#include "rebuild_auto.hpp"

#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "distance_report.hpp"
#include "pdesurf/analysis.hpp"

namespace pdesurf::cli {

namespace {

std::string madeLine(const AutoLayout& a) {
  return fmt::format(
      "{} from {} of the mesh simplified by Garland–Heckbert quadrics, {} ({} in one model), "
      "{} kept on frame edges{}",
      count(a.model.frames.size(), "frame"), count(a.baseTriangles, "triangle"),
      count(a.components, "component"), a.components == 1 ? "it" : "all",
      count(a.creaseEdges, "crease or boundary edge"),
      a.skippedTriangles == 0
          ? ""
          : fmt::format(" ({} without area left out)", count(a.skippedTriangles, "triangle")));
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
}

void AutoLayoutArgs::check() const {
  if (frames != 0 && !targetRms.empty())
    throw UsageError(
        "--frames and --target-rms both choose the number of frames: give one of them");
}

AutoLayoutOptions AutoLayoutArgs::options() const {
  AutoLayoutOptions o;
  o.frames = frames != 0 ? frames : kDefaultAutoFrames;
  if (creaseAngle >= 0.0) o.creaseAngle = creaseAngle;
  o.construction =
      quads == "split" ? QuadConstruction::SplitTriangles : QuadConstruction::PairTriangles;
  return o;
}

double AutoLayoutArgs::target() const {
  std::string text = targetRms;
  const bool percentage = !text.empty() && text.back() == '%';
  if (percentage) text.pop_back();
  double x = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size())
    throw UsageError(
        fmt::format("--target-rms {}: not a number (a fraction of the diagonal such as 0.002, or a "
                    "percentage such as 0.2%)",
                    targetRms));
  if (percentage) x /= 100.0;
  if (!(x > 0.0 && x < 1.0))
    throw UsageError(fmt::format(
        "--target-rms {}: the target must lie between 0 and the whole diagonal (0 and 1, or "
        "0% and 100%)",
        targetRms));
  return x;
}

VertexFrameModel automaticLayout(const AutoLayoutArgs& args, const Mesh& mesh,
                                 const std::string& meshPath, bool quiet) {
  const AutoLayoutOptions options = args.options();
  AutoLayout a = autoLayout(mesh, options, meshPath);
  if (!quiet)
    fmt::print("automatic layout (about {} asked for): {}\n", count(options.frames, "frame"),
               madeLine(a));
  return std::move(a.model);
}

FitResult searchAutomaticLayout(const AutoLayoutArgs& args, const Mesh& mesh,
                                const std::string& meshPath, const FitOptions& fit,
                                std::uint32_t resolution, bool quiet, VertexFrameModel& layout) {
  TargetSearchOptions o;
  o.targetRms = args.target();
  o.layout = args.options();
  o.fit = fit;
  o.fit.onIteration = nullptr;  // one line a trial instead
  o.resolution = resolution;
  o.onTrial = [&](std::uint32_t requested, const AutoFit& f) {
    if (quiet) return;
    const bool rms = f.worseRms() <= o.targetRms;
    const bool flat = f.normals.foldedArea <= o.maxFoldedArea;
    fmt::print(
        "trial: {} asked for, {} made{}: model -> mesh RMS {}, mesh -> model RMS {}, folded {} "
        "({})\n",
        count(requested, "frame"), f.layout.model.frames.size(),
        f.foldsPrevented && !fit.preventFolds ? ", steps that fold more refused" : "",
        percent(f.distance.aToB.rmsRelative), percent(f.distance.bToA.rmsRelative),
        percent(f.normals.foldedArea),
        rms && flat ? fmt::format("reaches {} within {} folded", percent(o.targetRms),
                                  percent(o.maxFoldedArea))
        : rms       ? fmt::format("reaches {} but folds more than {}", percent(o.targetRms),
                                  percent(o.maxFoldedArea))
                    : fmt::format("misses {}", percent(o.targetRms)));
  };
  TargetSearch s = searchTargetRms(mesh, o, meshPath);
  if (!quiet) {
    const std::size_t frames = s.best.layout.model.frames.size();
    if (s.reached)
      fmt::print(
          "target RMS {} reached both ways within {} folded with {}{} ({} tried): {}\n",
          percent(o.targetRms), percent(o.maxFoldedArea), count(frames, "frame"),
          s.best.foldsPrevented && !fit.preventFolds ? " (steps that fold more refused)" : "",
          count(s.trials, "layout"), madeLine(s.best.layout));
    else if (s.rmsReached)
      fmt::print(
          "target RMS {} reached both ways, but every layout that reached it folds more than {} "
          "({} tried, up to {}x the smallest that reached the RMS): the least folded, {}, "
          "folds {}\n",
          percent(o.targetRms), percent(o.maxFoldedArea), count(s.trials, "layout"),
          kFoldGrowthLimit, count(frames, "frame"), percent(s.best.normals.foldedArea));
    else
      fmt::print(
          "target RMS {} NOT reached ({} tried; the layout grows no further): the closest, {}, "
          "has {} (worse way)\n",
          percent(o.targetRms), count(s.trials, "layout"), count(frames, "frame"),
          percent(s.best.worseRms()));
  }
  const std::string name = layout.name;
  layout = std::move(s.best.layout.model);
  layout.name = name;
  s.best.fit.model.name = name;
  return std::move(s.best.fit);
}

void printStorageAgainstMesh(const VertexFrameModel& model, const Mesh& mesh) {
  const std::size_t modelBytes = storageBytes(model), meshBytes = storageBytes(mesh);
  fmt::print("mesh storage   {} bytes (the model is {:.3g}x of it)\n", meshBytes,
             double(modelBytes) / double(meshBytes));
}

}  // namespace pdesurf::cli
