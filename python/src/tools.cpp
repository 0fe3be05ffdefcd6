// pdesurf._core's mesh tools: distances between meshes, slicing, the steps of a rebuild
// (layouts, the fit, the cross-section rebuild) and STEP/IGES export. pdesurf/_tools.py puts
// the steps together as `pdesurf rebuild` does (apps/cli/rebuild_command.cpp).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include "core.hpp"
#include "pdesurf/analysis.hpp"
#include "pdesurf/auto_layout.hpp"
#include "pdesurf/cad_export.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/mesh_slice.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/rebuild.hpp"
#include "pdesurf/section_rebuild.hpp"
#include "pdesurf/tube_layout.hpp"
#include "peers.hpp"

namespace pdesurf::python {

namespace {

py::list point(const Vec3& p) { return py::cast(std::vector<double>{p.x(), p.y(), p.z()}); }

/// One direction of a distance, with the keys of `pdesurf compare --json`.
py::dict oneWay(const OneWayDistance& d) {
  using py::arg;
  return py::dict(arg("samples") = d.samples, arg("rms") = d.rms,
                  arg("rms_relative") = d.rmsRelative, arg("mean") = d.mean,
                  arg("mean_relative") = d.meanRelative, arg("max") = d.max,
                  arg("max_relative") = d.maxRelative, arg("max_at") = point(d.maxAt),
                  arg("cover_radius") = d.coverRadius);
}

/// The distance options of `samples` face samples a mesh, checked.
DistanceOptions sampled(std::size_t samples) {
  if (samples < 1) badArgument("samples", "must be at least 1");
  DistanceOptions options;
  options.samples = samples;
  return options;
}

py::dict distance(const Mesh& a, const Mesh& b, std::size_t samples) {
  const DistanceOptions options = sampled(samples);
  MeshDistance d;
  {
    py::gil_scoped_release release;
    d = meshDistance(a, b, options);
  }
  using py::arg;
  return py::dict(arg("diagonal") = d.diagonal, arg("model_to_mesh") = oneWay(d.aToB),
                  arg("mesh_to_model") = oneWay(d.bToA), arg("hausdorff") = d.hausdorff,
                  arg("hausdorff_relative") = d.hausdorffRelative);
}

/// The polygon peer (apps/accuracy/peers.hpp): `truth` simplified to the fewest edges whose
/// accuracy RMS (both ways, relative to the diagonal) is at most `target`.
py::dict polygonPeer(const Mesh& truth, double target, std::size_t samples) {
  if (!(target >= 0.0) || !std::isfinite(target)) badArgument("target", "must be finite, >= 0");
  const DistanceOptions options = sampled(samples);
  PolygonPeer peer = [&] {
    py::gil_scoped_release release;
    return simplifiedPeer(truth, target, options);
  }();
  using py::arg;
  return py::dict(arg("mesh") = std::move(peer.mesh), arg("rms") = peer.rms,
                  arg("bytes") = peer.bytes, arg("reached") = peer.reached,
                  arg("coarser_rms") = peer.coarserRms, arg("trials") = peer.trials);
}

/// The slicing options of `slice` and `rebuild` (their --axis, --count, --range, --near,
/// --track), checked before any work.
SliceOptions sliceOptions(const std::string& axis, std::uint32_t count, const py::object& range,
                          const py::object& near, bool track) {
  SliceOptions slice;
  const std::optional<Axis> parsed = parseAxis(axis);
  if (!parsed) badArgument("axis", "'" + axis + "' is not x, y or z");
  slice.axis = *parsed;
  if (count < 1) badArgument("count", "must be at least 1");
  slice.count = count;
  if (!range.is_none()) {
    const auto r = floatRows(py::make_tuple(range), "range", 2);
    slice.range = std::pair{r.at(0, 0), r.at(0, 1)};
    try {
      slicePlanes(slice, 0.0, 1.0);  // the range's own checks
    } catch (const InvalidArgument& e) {
      badArgument("range", e.what());
    }
  }
  if (!near.is_none()) slice.near = points(floatRows(py::make_tuple(near), "near", 3))[0];
  slice.track = track;
  return slice;
}

py::list sectionList(const std::vector<MeshSection>& sections) {
  py::list out;
  for (const MeshSection& s : sections) {
    py::array_t<double> pts({static_cast<py::ssize_t>(s.points.size()), py::ssize_t{3}});
    for (std::size_t i = 0; i < s.points.size(); ++i)
      for (std::size_t c = 0; c < 3; ++c) pts.mutable_at(i, c) = s.points[i][c];
    using py::arg;
    out.append(py::dict(arg("index") = s.index, arg("coordinate") = s.coordinate,
                        arg("points") = pts, arg("length") = s.length, arg("area") = s.area,
                        arg("centroid") = point(s.centroid), arg("loops") = s.loops));
  }
  return out;
}

Model frameModel(VertexFrameModel model, const std::string& source) {
  return {std::make_shared<const AnyModel>(std::move(model)), source};
}

const VertexFrameModel& framesOf(const Model& model, const char* name) {
  const auto* frames = model.model->as<VertexFrameModel>();
  if (!frames) badArgument(name, "a vertex-frames model is needed");
  return *frames;
}

py::dict measureDict(const FitMeasure& m) {
  using py::arg;
  return py::dict(arg("rms") = m.rms(), arg("rms_to_mesh") = m.rmsToMesh,
                  arg("mean_to_mesh") = m.meanToMesh, arg("max_to_mesh") = m.maxToMesh,
                  arg("rms_to_model") = m.rmsToModel, arg("mean_to_model") = m.meanToModel,
                  arg("max_to_model") = m.maxToModel, arg("folded_samples") = m.foldedSamples,
                  arg("samples") = m.samples);
}

py::dict iterationDict(const FitIteration& it) {
  using py::arg;
  return py::dict(arg("iteration") = it.iteration, arg("step") = it.step, arg("shape") = it.shape,
                  arg("parameter_step") = it.parameterStep,
                  arg("measure") = measureDict(it.measure));
}

/// The fit's options from the CLI's (checked as the CLI checks them).
FitOptions fitOptions(std::uint32_t iterations, double tolerance, double smoothness,
                      std::uint32_t samples, bool preventFolds, double foldWeight, bool fitShape) {
  if (samples == 1 || samples == 2 || samples > 65)
    badArgument("fit_samples", "must be 0 (automatic) or 3 to 65");
  if (!(tolerance >= 0.0 && tolerance <= 1.0)) badArgument("tolerance", "must be in [0, 1]");
  if (!(smoothness >= 0.0 && smoothness <= 1e6)) badArgument("smoothness", "must be in [0, 1e6]");
  if (!(foldWeight >= 0.0 && foldWeight <= 1.0)) badArgument("fold_weight", "must be in [0, 1]");
  FitOptions options;
  options.maxIterations = iterations;
  options.tolerance = tolerance;
  options.smoothness = smoothness;
  options.samplesPerSide = samples;
  options.preventFolds = preventFolds;
  options.conformalWeight = foldWeight;
  options.fitShape = fitShape;
  return options;
}

/// The automatic layout's options (`rebuild --frames --quads --crease-angle`).
AutoLayoutOptions autoLayoutOptions(std::uint32_t frames, double creaseAngle,
                                    const std::string& quads) {
  if (frames < 1 || frames > 1000000) badArgument("frames", "must be 1 to 1000000");
  if (!(creaseAngle >= 0.0 && creaseAngle <= 180.0))
    badArgument("crease_angle", "must be in [0, 180] degrees");
  if (quads != "pair" && quads != "split")
    badArgument("quads", "'" + quads + "' is neither 'pair' nor 'split'");
  AutoLayoutOptions options;
  options.frames = frames;
  options.creaseAngle = creaseAngle;
  options.construction =
      quads == "split" ? QuadConstruction::SplitTriangles : QuadConstruction::PairTriangles;
  return options;
}

py::list iterationList(const std::vector<FitIteration>& iterations) {
  py::list its;
  for (const FitIteration& it : iterations) its.append(iterationDict(it));
  return its;
}

py::tuple fit(const Model& start, const Mesh& mesh, std::uint32_t iterations, double tolerance,
              double smoothness, std::uint32_t samples, bool preventFolds, double foldWeight,
              bool fitShape, const py::object& progress) {
  const VertexFrameModel& layout = framesOf(start, "start");
  FitOptions options =
      fitOptions(iterations, tolerance, smoothness, samples, preventFolds, foldWeight, fitShape);
  if (!progress.is_none())
    options.onIteration = [&](const FitIteration& it) {
      py::gil_scoped_acquire gil;
      progress(iterationDict(it));
    };
  FitResult result;
  {
    py::gil_scoped_release release;
    result = fitVertexFrames(layout, mesh, options);
  }
  return py::make_tuple(frameModel(std::move(result.model), start.source),
                        iterationList(result.iterations), result.stopReason);
}

/// `rebuild --target-rms`: the smallest automatic layout whose fit reaches the target both
/// ways -> (model, iterations, stop_reason, reached, trials).
py::tuple searchTarget(const Mesh& mesh, double target, std::uint32_t frames, double creaseAngle,
                       const std::string& quads, std::uint32_t iterations, double tolerance,
                       double smoothness, std::uint32_t samples, bool preventFolds,
                       double foldWeight, bool fitShape, std::uint32_t resolution,
                       const std::string& name, const std::string& source) {
  if (!(target > 0.0 && target < 1.0))
    badArgument("target_rms", "must be a fraction of the diagonal in (0, 1), or '0.2%'");
  TargetSearchOptions o;
  o.targetRms = target;
  o.layout = autoLayoutOptions(frames, creaseAngle, quads);
  o.fit =
      fitOptions(iterations, tolerance, smoothness, samples, preventFolds, foldWeight, fitShape);
  o.resolution = resolution;
  TargetSearch s;
  {
    py::gil_scoped_release release;
    s = searchTargetRms(mesh, o, source);
  }
  s.best.fit.model.name = name;
  return py::make_tuple(frameModel(std::move(s.best.fit.model), source),
                        iterationList(s.best.fit.iterations), s.best.fit.stopReason, s.reached,
                        s.trials);
}

py::tuple rebuildSections(const Mesh& mesh, const SliceOptions& slice, std::uint32_t modes,
                          std::uint32_t points, double a, const std::string& ends, bool exact,
                          const std::string& name, const std::string& source) {
  if (ends != "natural" && ends != "estimated")
    badArgument("ends", "'" + ends + "' is neither 'natural' nor 'estimated'");
  if (!std::isfinite(a) || a == 0.0) badArgument("a", "must be finite and non-zero");
  if (modes < 1 || modes > 256) badArgument("modes", "must be 1 to 256");
  if (points < 2 * modes + 1)
    badArgument("points", std::to_string(points) + " cannot determine " + std::to_string(modes) +
                              " modes: give at least " + std::to_string(2 * modes + 1));
  SectionRebuildOptions options;
  options.slice = slice;
  options.modes = modes;
  options.exact = exact;
  options.prep.points = points;
  options.a = a;
  options.ends = ends == "natural" ? ChainEnds::Natural : ChainEnds::Estimated;
  options.name = name;
  SectionRebuild rebuilt;
  Mesh part, surface;
  {
    py::gil_scoped_release release;
    rebuilt = rebuildFromSections(mesh, options);
    const auto& s = rebuilt.sections;
    rebuilt.model.description =
        fmt::format("{} rebuilt by pdesurf rebuild from {} sections along {} in [{}, {}]", source,
                    s.size(), axisName(slice.axis), s.front().coordinate, s.back().coordinate);
    part = sectionedPart(mesh, slice.axis, s);
    surface = tessellate(rebuilt.chain, chainMeasureOptions(rebuilt.chain.patches.size()));
  }
  const std::size_t modelBytes = storageBytes(rebuilt.model);
  const Model model{std::make_shared<const AnyModel>(std::move(rebuilt.model)), source};
  return py::make_tuple(model, std::make_shared<Mesh>(std::move(part)),
                        std::make_shared<Mesh>(std::move(surface)), sectionList(rebuilt.sections),
                        modelBytes);
}

py::dict exportCad(const SolvedModel& solved, const std::string& path, const py::object& tolerance,
                   std::uint32_t maxSpans) {
  NurbsExportOptions options;
  if (tolerance.is_none()) {
    options.keepBest = true;  // the default tolerance is a goal (as the CLI's)
  } else {
    const double t = floatRows(py::make_tuple(py::make_tuple(tolerance)), "tolerance", 1).at(0, 0);
    if (t <= 0.0) badArgument("tolerance", "must be a positive distance");
    options.tolerance = t;
  }
  if (maxSpans < 4 || maxSpans > 4096) badArgument("max_spans", "must be 4 to 4096");
  options.maxSpans = maxSpans;
  const CadFormat format = cadFormatFromPath(path);
  NurbsModel nurbs;
  CadExportReport report;
  {
    py::gil_scoped_release release;
    nurbs = toNurbs(solved, options);
    report = writeCad(nurbs, path, format);
  }
  using py::arg;
  const std::size_t exact = nurbs.exactCount();
  return py::dict(
      arg("format") = format == CadFormat::Step ? "step" : "iges",
      arg("faces") = nurbs.faces.size(), arg("exact_faces") = exact,
      arg("approximated_faces") = nurbs.faces.size() - exact, arg("tolerance") = nurbs.tolerance,
      arg("diagonal") = nurbs.diagonal, arg("max_deviation") = nurbs.maxDeviation(),
      arg("faces_over_tolerance") = nurbs.overToleranceCount(), arg("shells") = report.shells,
      arg("free_edges") = report.freeEdges, arg("multiple_edges") = report.multipleEdges,
      arg("degenerated_edges") = report.degeneratedEdges,
      arg("sewing_tolerance") = report.sewingTolerance);
}

}  // namespace

void bindTools(py::module_& m) {
  m.def("distance", &distance, py::arg("a"), py::arg("b"), py::arg("samples") = 100000,
        "Metro-style distances between mesh a (the model's) and reference mesh b, both ways\n"
        "(the keys of `pdesurf compare --json`). The GIL is released meanwhile.");
  m.def("polygon_peer", &polygonPeer, py::arg("truth"), py::arg("target"),
        py::arg("samples") = 100000,
        "The truth simplified (Garland-Heckbert edge collapses) to the fewest edges whose RMS\n"
        "both ways is at most `target` of the diagonal. The GIL is released meanwhile.");
  m.def(
      "slice_mesh",
      [](const Mesh& mesh, const std::string& axis, std::uint32_t count, const py::object& range,
         const py::object& near, bool track) {
        const SliceOptions options = sliceOptions(axis, count, range, near, track);
        std::vector<MeshSection> sections;
        {
          py::gil_scoped_release release;
          sections = sliceMesh(mesh, options);
        }
        return sectionList(sections);
      },
      py::arg("mesh"), py::arg("axis"), py::arg("count"), py::arg("range"), py::arg("near"),
      py::arg("track"), "Each plane's kept closed loop (pdesurf.slice wraps it).");
  m.def(
      "grid_layout",
      [](const Mesh& disk, std::uint32_t u, std::uint32_t v, const std::string& source) {
        if (u < 1 || v < 1 || u > 1000 || v > 1000)
          badArgument("grid", "U and V must be 1 to 1000");
        py::gil_scoped_release release;
        return frameModel(gridLayout(disk, {u, v}, source), source);
      },
      py::arg("mesh"), py::arg("u"), py::arg("v"), py::arg("source"),
      "A U x V grid of frames laid on a disk-like mesh. Raises LayoutError.");
  m.def(
      "quad_layout",
      [](const std::string& path) {
        py::gil_scoped_release release;
        return frameModel(quadLayout(readPolygonMesh(path), path), path);
      },
      py::arg("path"), "One frame per quad of a quad mesh file. Raises LayoutError.");
  m.def(
      "tube_layout",
      [](const Mesh& mesh, std::uint32_t rings, std::uint32_t sectors, const std::string& axis,
         const py::object& range, const py::object& near, bool track, const std::string& source) {
        if (rings < 1 || rings > 1000) badArgument("tube", "RINGS must be 1 to 1000");
        if (sectors < 3 || sectors > 1000)
          badArgument("tube", "SECTORS must be 3 to 1000 (two would join along both sides)");
        const SliceOptions slice = sliceOptions(axis, 2 * rings + 1, range, near, track);
        TubeLayout tube;
        {
          py::gil_scoped_release release;
          tube = tubeLayout(mesh, {rings, sectors, slice}, source);
        }
        return py::make_tuple(frameModel(std::move(tube.model), source),
                              std::make_shared<Mesh>(std::move(tube.part)));
      },
      py::arg("mesh"), py::arg("rings"), py::arg("sectors"), py::arg("axis"), py::arg("range"),
      py::arg("near"), py::arg("track"), py::arg("source"),
      "A tube of frames on a part of the mesh -> (layout, part). Raises LayoutError.");
  m.def(
      "auto_layout",
      [](const Mesh& mesh, std::uint32_t frames, double creaseAngle, const std::string& quads,
         const std::string& source) {
        const AutoLayoutOptions options = autoLayoutOptions(frames, creaseAngle, quads);
        py::gil_scoped_release release;
        return frameModel(autoLayout(mesh, options, source).model, source);
      },
      py::arg("mesh"), py::arg("frames"), py::arg("crease_angle"), py::arg("quads"),
      py::arg("source"),
      "The automatic layout of about `frames` frames on any mesh. Raises LayoutError.");
  m.def("search_target_rms", &searchTarget, py::arg("mesh"), py::arg("target"), py::arg("frames"),
        py::arg("crease_angle"), py::arg("quads"), py::arg("iterations"), py::arg("tolerance"),
        py::arg("smoothness"), py::arg("fit_samples"), py::arg("prevent_folds"),
        py::arg("fold_weight"), py::arg("fit_shape"), py::arg("resolution"), py::arg("name"),
        py::arg("source"),
        "The smallest automatic layout whose fitted model reaches `target` both ways ->\n"
        "(model, iterations, stop_reason, reached, trials). The GIL is released meanwhile.");
  m.def("fit", &fit, py::arg("start"), py::arg("mesh"), py::arg("iterations") = 30,
        py::arg("tolerance") = 1e-3, py::arg("smoothness") = 1e-5, py::arg("fit_samples") = 9,
        py::arg("prevent_folds") = false, py::arg("fold_weight") = FitOptions{}.conformalWeight,
        py::arg("fit_shape") = false, py::arg("progress") = py::none(),
        "Fits a layout's vertices (and with fit_shape its forces, a1, a2) to a mesh ->\n"
        "(model, iterations, stop_reason); progress(iteration) is called after each. The GIL\n"
        "is released meanwhile (taken again for progress).");
  m.def(
      "with_name",
      [](const Model& model, const std::string& name) {
        VertexFrameModel frames = framesOf(model, "model");
        frames.name = name;
        return frameModel(std::move(frames), model.source);
      },
      py::arg("model"), py::arg("name"), "A vertex-frame model with another name.");
  m.def(
      "storage_bytes",
      [](const py::object& value) -> std::size_t {
        if (py::isinstance<Mesh>(value)) return storageBytes(value.cast<const Mesh&>());
        const Model& model = value.cast<const Model&>();
        if (const auto* f = model.model->as<VertexFrameModel>()) return storageBytes(*f);
        if (const auto* c = model.model->as<CrossSectionModel>()) return storageBytes(*c);
        badArgument("model", "storage is counted for vertex-frames and cross-sections models");
      },
      py::arg("model"),
      "Storage under the seed's Table 1 convention (six significant digits as text) of a\n"
      "vertex-frames or cross-sections model, or a mesh.");
  m.def(
      "rebuild_sections",
      [](const Mesh& mesh, const std::string& axis, std::uint32_t count, const py::object& range,
         const py::object& near, bool track, std::uint32_t modes, std::uint32_t points, double a,
         const std::string& ends, bool exact, const std::string& name, const std::string& source) {
        if (count < 2) badArgument("count", "a chain needs at least 2 sections");
        return rebuildSections(mesh, sliceOptions(axis, count, range, near, track), modes, points,
                               a, ends, exact, name, source);
      },
      py::arg("mesh"), py::arg("axis"), py::arg("count"), py::arg("range"), py::arg("near"),
      py::arg("track"), py::arg("modes"), py::arg("points"), py::arg("a"), py::arg("ends"),
      py::arg("exact"), py::arg("name"), py::arg("source"),
      "The cross-section rebuild -> (model, part, measured surface mesh, sections,\n"
      "storage bytes).");
  m.def("export_cad", &exportCad, py::arg("surface"), py::arg("path"),
        py::arg("tolerance") = py::none(), py::arg("max_spans") = 512,
        "Writes STEP or IGES (by the extension) -> the export report (pdesurf.export wraps it).");
}

}  // namespace pdesurf::python
