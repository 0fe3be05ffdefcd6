// rebuild(): the orchestration `pdesurf rebuild` and pdesurf.rebuild share
// (include/pdesurf/mesh_rebuild.hpp): the layout or the sections, the fit, the measure.
#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "pdesurf/analysis.hpp"
#include "pdesurf/mesh_rebuild.hpp"
#include "pdesurf/section_rebuild.hpp"
#include "pdesurf/tube_layout.hpp"

namespace pdesurf {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

AutoLayoutOptions autoLayoutOptions(const RebuildOptions& o) {
  AutoLayoutOptions layout;
  layout.frames = o.frames != 0 ? o.frames : kDefaultAutoFrames;
  if (o.creaseAngle) layout.creaseAngle = *o.creaseAngle;
  layout.construction = o.quads.value_or(QuadConstruction::PairTriangles);
  return layout;
}

}  // namespace

TargetSearchOptions targetSearchOptions(const RebuildOptions& o) {
  TargetSearchOptions search;
  search.targetRms = o.targetRms.value_or(0.0);
  search.maxNormalDeviation = o.maxNormalDeviation.value_or(kMaxNormalDeviation);
  search.layout = autoLayoutOptions(o);
  search.fit = o.fit;
  search.fit.normalWeight = o.normalWeight.value_or(kNormalWeight);
  search.fit.onIteration = nullptr;  // one report a trial instead
  search.resolution = o.resolution;
  return search;
}

namespace {

AutoLayoutReport layoutReport(const AutoLayout& a, std::uint32_t requested) {
  return {requested,    a.model.frames.size(), a.baseTriangles,
          a.components, a.creaseEdges,         a.skippedTriangles};
}

/// The model's tessellation against the reference both ways, and its normals.
void measure(RebuildReport& report, const Mesh& surface, const Mesh& reference,
             std::size_t samples) {
  DistanceOptions distance;
  distance.samples = samples;
  report.distance = meshDistance(surface, reference, distance);
  report.normals = normalDeviation(surface, reference);
  report.measured = true;
}

void describeReference(RebuildReport& report, const Mesh& reference) {
  report.referenceStorageBytes = storageBytes(reference);
  report.referenceTriangles = reference.triangleCount();
  report.referenceVertices = reference.vertexCount();
}

RebuildResult rebuildVertexFrames(const Mesh& mesh, const RebuildOptions& o,
                                  const RebuildProgress& progress) {
  RebuildReport report;
  std::optional<Mesh> part;
  FitOptions fit = o.fit;
  fit.normalWeight = o.normalWeight.value_or(0.0);
  fit.onIteration = progress.onIteration;
  const std::string name =
      o.name.empty() ? std::filesystem::path(o.source).stem().string() + " (vertex frames)"
                     : o.name;
  auto t0 = Clock::now();
  FitResult fitted;
  if (!o.grid && !o.tube && o.quadsPath.empty() && o.targetRms) {
    TargetSearchOptions search = targetSearchOptions(o);
    search.onTrial = progress.onTrial;
    TargetSearch s = searchTargetRms(mesh, search, o.source);
    report.search = TargetSearchReport{search.targetRms,
                                       search.maxFoldedArea,
                                       search.maxNormalDeviation,
                                       s.reached,
                                       s.met,
                                       s.stop,
                                       s.trials,
                                       s.best.foldsPrevented,
                                       s.best.worseRms(),
                                       s.best.normals.foldedArea,
                                       s.best.normals.rmsDegrees};
    report.automatic = layoutReport(s.best.layout, search.layout.frames);
    report.automatic->grid = s.best.grid;
    fitted = std::move(s.best.fit);
  } else {
    VertexFrameModel layout;
    if (!o.quadsPath.empty()) {
      layout = quadLayout(readPolygonMesh(o.quadsPath), o.quadsPath);
    } else if (o.grid) {
      layout = gridLayout(mesh, {(*o.grid)[0], (*o.grid)[1]}, o.source);
    } else if (o.tube) {
      // The tube is fitted to, and measured against, the part between its end planes.
      TubeLayout tube = tubeLayout(mesh, {(*o.tube)[0], (*o.tube)[1], o.slice}, o.source);
      layout = std::move(tube.model);
      part = std::move(tube.part);
    } else {
      const AutoLayoutOptions options = autoLayoutOptions(o);
      AutoLayout a = autoLayout(mesh, options, o.source);
      report.automatic = layoutReport(a, options.frames);
      if (progress.onLayout) progress.onLayout(*report.automatic);
      layout = std::move(a.model);
    }
    layout.name = name;
    report.ms.layout = msSince(t0);
    t0 = Clock::now();
    fitted = fitVertexFrames(layout, part ? *part : mesh, fit);
  }
  report.ms.fit = msSince(t0);
  fitted.model.name = name;
  report.name = name;
  const Mesh& reference = part ? *part : mesh;
  if (o.measure) {
    t0 = Clock::now();
    const Mesh surface = tessellate(solve(fitted.model), {o.resolution});
    measure(report, surface, reference, o.samples);
    report.ms.measure = msSince(t0);
  }
  describeReference(report, reference);
  report.storageBytes = storageBytes(fitted.model);
  report.frames = fitted.model.frames.size();
  report.vertices = fitted.model.vertices.size();
  report.iterations = std::move(fitted.iterations);
  report.stopReason = std::move(fitted.stopReason);
  return {std::move(fitted.model), std::move(report), std::move(part), {}, {}};
}

RebuildResult rebuildCrossSections(const Mesh& mesh, const RebuildOptions& o) {
  RebuildReport report;
  report.kind = RebuildKind::CrossSections;
  SectionRebuildOptions options;
  options.slice = o.slice;
  options.modes = o.modes;
  options.exact = o.exact;
  options.prep.points = o.points;
  options.a = o.a;
  options.ends = o.ends;
  options.name = o.name.empty() ? modelDisplayName("", o.source) : o.name;
  auto t0 = Clock::now();
  SectionRebuild rebuilt = rebuildFromSections(mesh, options);
  report.ms.fit = msSince(t0);
  const auto& sections = rebuilt.sections;
  report.sections = sections.size();
  report.from = sections.front().coordinate;
  report.to = sections.back().coordinate;
  rebuilt.model.description =
      fmt::format("{} rebuilt by pdesurf rebuild from {} sections along {} in [{}, {}]", o.source,
                  sections.size(), axisName(o.slice.axis), report.from, report.to);
  t0 = Clock::now();
  Mesh part = sectionedPart(mesh, o.slice.axis, sections);
  if (o.measure) {
    const Mesh surface =
        tessellate(rebuilt.chain, chainMeasureOptions(rebuilt.chain.patches.size()));
    try {
      measure(report, surface, part, o.samples);
    } catch (const InvalidArgument& e) {
      throw InvalidArgument(std::string("the rebuilt part: ") + e.what());
    }
  }
  report.ms.measure = msSince(t0);
  describeReference(report, part);
  report.storageBytes = storageBytes(rebuilt.model);
  report.name = rebuilt.model.name;
  return {std::move(rebuilt.model), std::move(report), std::move(part), std::move(rebuilt.sections),
          std::move(rebuilt.prepared)};
}

}  // namespace

RebuildResult rebuild(const Mesh& mesh, const RebuildOptions& options,
                      const RebuildProgress& progress) {
  checkRebuildOptions(options);
  return options.kind == RebuildKind::VertexFrames ? rebuildVertexFrames(mesh, options, progress)
                                                   : rebuildCrossSections(mesh, options);
}

}  // namespace pdesurf
