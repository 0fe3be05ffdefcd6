// pdesurf._core's mesh tools: distances between meshes, slicing, the library's rebuild (the
// one `pdesurf rebuild` calls: include/pdesurf/mesh_rebuild.hpp) and STEP/IGES export.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include "core.hpp"
#include "pdesurf/analysis.hpp"
#include "pdesurf/cad_export.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/mesh_rebuild.hpp"
#include "pdesurf/mesh_slice.hpp"
#include "pdesurf/model_io.hpp"
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

/// Both ways, with the keys of `pdesurf compare --json`.
py::dict distanceDict(const MeshDistance& d) {
  using py::arg;
  return py::dict(arg("diagonal") = d.diagonal, arg("model_to_mesh") = oneWay(d.aToB),
                  arg("mesh_to_model") = oneWay(d.bToA), arg("hausdorff") = d.hausdorff,
                  arg("hausdorff_relative") = d.hausdorffRelative);
}

py::dict distance(const Mesh& a, const Mesh& b, std::size_t samples) {
  const DistanceOptions options = sampled(samples);
  MeshDistance d;
  {
    py::gil_scoped_release release;
    d = meshDistance(a, b, options);
  }
  return distanceDict(d);
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

/// A keyword of rebuild as T, None meaning `fallback`; a value of another type is a
/// ValueError naming the keyword.
template <class T>
T keyword(const py::dict& keywords, const char* name, T fallback) {
  if (!keywords.contains(name) || keywords[name].is_none()) return fallback;
  try {
    return keywords[name].cast<T>();
  } catch (const py::cast_error&) {
    badArgument(name, "expected a " +
                          std::string(std::is_same_v<T, bool>     ? "bool"
                                      : std::is_same_v<T, double> ? "number"
                                                                  : "string") +
                          ", got " + py::repr(keywords[name]).cast<std::string>());
  }
}

/// A count keyword: an integer in [0, 2^32).
std::uint32_t countKeyword(const py::dict& keywords, const char* name, std::uint32_t fallback) {
  if (!keywords.contains(name) || keywords[name].is_none()) return fallback;
  const py::object value = keywords[name];
  if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value))
    badArgument(name, "expected an integer, got " + py::repr(value).cast<std::string>());
  const long long n = value.cast<long long>();
  if (n < 0 || n > 0xffffffffLL) badArgument(name, "must be 0 or more, got " + std::to_string(n));
  return static_cast<std::uint32_t>(n);
}

/// (U, V) or (RINGS, SECTORS): two counts, or none.
std::optional<std::array<std::uint32_t, 2>> pairKeyword(const py::dict& keywords, const char* name,
                                                        const char* what) {
  if (!keywords.contains(name) || keywords[name].is_none()) return std::nullopt;
  const py::object value = keywords[name];
  const auto bad = [&] {
    badArgument(name,
                std::string("expected ") + what + ", got " + py::repr(value).cast<std::string>());
  };
  if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value) || py::len(value) != 2)
    bad();
  py::dict both;
  both["first"] = value[py::int_(0)];
  both["second"] = value[py::int_(1)];
  return std::array{countKeyword(both, "first", 0), countKeyword(both, "second", 0)};
}

/// rebuild's keywords (pdesurf.rebuild's, None: not given) as the library's options, checked
/// as the CLI checks them (checkRebuildOptions, the messages in the keywords' spelling).
RebuildOptions rebuildOptions(const py::dict& keywords, const std::string& source) {
  static constexpr const char* kKeywords[] = {
      "kind",        "grid",          "layout",
      "tube",        "iterations",    "tolerance",
      "smoothness",  "fit_samples",   "prevent_folds",
      "fold_weight", "normal_weight", "fit_shape",
      "frames",      "target_rms",    "max_normal_deviation",
      "quads",       "crease_angle",  "resolution",
      "samples",     "axis",          "count",
      "range",       "near",          "track",
      "modes",       "points",        "a",
      "ends",        "exact",         "name"};
  for (const auto& [key, value] : keywords) {
    const std::string k = py::str(key);
    if (std::find_if(std::begin(kKeywords), std::end(kKeywords),
                     [&](const char* known) { return k == known; }) == std::end(kKeywords))
      badArgument(k.c_str(), "not an option of rebuild");
  }
  RebuildOptions o;
  const std::string kind = keyword<std::string>(keywords, "kind", "vertex-frames");
  const auto parsedKind = parseRebuildKind(kind);
  if (!parsedKind)
    badArgument("kind", "'" + kind + "' is neither 'vertex-frames' nor 'cross-sections'");
  o.kind = *parsedKind;
  o.source = source;
  o.name = keyword<std::string>(keywords, "name", "");
  if (o.name.empty() && o.kind == RebuildKind::VertexFrames && source.starts_with("<"))
    o.name = "mesh (vertex frames)";  // arrays: no file stem to name the model after
  o.grid = pairKeyword(keywords, "grid", "(U, V)");
  o.tube = pairKeyword(keywords, "tube", "(RINGS, SECTORS)");
  if (keywords.contains("layout") && !keywords["layout"].is_none())
    o.quadsPath = py::module_::import("os").attr("fspath")(keywords["layout"]).cast<std::string>();
  o.frames = countKeyword(keywords, "frames", 0);
  if (o.frames == 0 && keywords.contains("frames") && !keywords["frames"].is_none())
    badArgument("frames", "must be 1 to 1000000");
  if (keywords.contains("target_rms") && !keywords["target_rms"].is_none()) {
    const py::object target = keywords["target_rms"];
    o.targetRms = py::isinstance<py::str>(target)
                      ? parseTargetRms(target.cast<std::string>(), RebuildOptionStyle::Python)
                      : keyword<double>(keywords, "target_rms", 0.0);
  }
  if (keywords.contains("quads") && !keywords["quads"].is_none()) {
    const std::string quads = keyword<std::string>(keywords, "quads", "pair");
    o.quads = parseQuadConstruction(quads);
    if (!o.quads) badArgument("quads", "'" + quads + "' is neither 'pair' nor 'split'");
  }
  if (keywords.contains("crease_angle") && !keywords["crease_angle"].is_none())
    o.creaseAngle = keyword<double>(keywords, "crease_angle", 60.0);
  if (keywords.contains("max_normal_deviation") && !keywords["max_normal_deviation"].is_none())
    o.maxNormalDeviation = keyword<double>(keywords, "max_normal_deviation", kMaxNormalDeviation);
  o.fit.maxIterations = countKeyword(keywords, "iterations", o.fit.maxIterations);
  o.fit.tolerance = keyword<double>(keywords, "tolerance", o.fit.tolerance);
  o.fit.smoothness = keyword<double>(keywords, "smoothness", o.fit.smoothness);
  o.fit.samplesPerSide = countKeyword(keywords, "fit_samples", o.fit.samplesPerSide);
  o.fit.preventFolds = keyword<bool>(keywords, "prevent_folds", o.fit.preventFolds);
  o.fit.conformalWeight = keyword<double>(keywords, "fold_weight", o.fit.conformalWeight);
  if (keywords.contains("normal_weight") && !keywords["normal_weight"].is_none())
    o.normalWeight = keyword<double>(keywords, "normal_weight", 0.0);
  o.fit.fitShape = keyword<bool>(keywords, "fit_shape", o.fit.fitShape);
  o.resolution = countKeyword(keywords, "resolution", o.resolution);
  const std::string axis = keyword<std::string>(keywords, "axis", "z");
  const std::optional<Axis> parsedAxis = parseAxis(axis);
  if (!parsedAxis) badArgument("axis", "'" + axis + "' is not x, y or z");
  o.slice.axis = *parsedAxis;
  o.slice.count = countKeyword(keywords, "count", o.slice.count);
  if (keywords.contains("range") && !keywords["range"].is_none()) {
    const auto r = floatRows(py::make_tuple(keywords["range"]), "range", 2);
    o.slice.range = std::pair{r.at(0, 0), r.at(0, 1)};
  }
  if (keywords.contains("near") && !keywords["near"].is_none())
    o.slice.near = points(floatRows(py::make_tuple(keywords["near"]), "near", 3))[0];
  o.slice.track = keyword<bool>(keywords, "track", o.slice.track);
  o.modes = countKeyword(keywords, "modes", o.modes);
  o.points = countKeyword(keywords, "points", o.points);
  o.a = keyword<double>(keywords, "a", o.a);
  const std::string ends = keyword<std::string>(keywords, "ends", "natural");
  const auto parsedEnds = parseChainEnds(ends);
  if (!parsedEnds) badArgument("ends", "'" + ends + "' is neither 'natural' nor 'estimated'");
  o.ends = *parsedEnds;
  o.exact = keyword<bool>(keywords, "exact", o.exact);
  if (keywords.contains("samples") && !keywords["samples"].is_none()) {
    const long long samples = keywords["samples"].cast<long long>();
    if (samples < 1) badArgument("samples", "must be at least 1");
    o.samples = static_cast<std::size_t>(samples);
  }
  checkRebuildOptions(o, RebuildOptionStyle::Python);
  return o;
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

/// Why the target search stopped growing its layouts, as the report's "search_stop" names it.
const char* searchStopName(TargetSearch::Stop stop) {
  switch (stop) {
    case TargetSearch::Stop::Reached:
      return "reached";
    case TargetSearch::Stop::LayoutStopped:
      return "layout stopped";
    case TargetSearch::Stop::GrowthLimit:
      return "growth limit";
    case TargetSearch::Stop::NormalsStalled:
      return "normals stalled";
    case TargetSearch::Stop::StorageLimit:
      return "storage limit";
  }
  return "unknown";
}

/// The library's report as pdesurf.rebuild's dict (docs/python.md).
py::dict reportDict(RebuildResult& result) {
  const RebuildReport& r = result.report;
  const MeshDistance& d = r.distance;
  py::dict report;
  report["kind"] = rebuildKindName(r.kind);
  report["rms"] = py::make_tuple(d.aToB.rmsRelative, d.bToA.rmsRelative);
  report["mean"] = py::make_tuple(d.aToB.meanRelative, d.bToA.meanRelative);
  report["max"] = py::make_tuple(d.aToB.maxRelative, d.bToA.maxRelative);
  report["distances"] = distanceDict(d);
  using py::arg;
  report["normals"] =
      py::dict(arg("folded_area") = r.normals.foldedArea, arg("rms_degrees") = r.normals.rmsDegrees,
               arg("reversed") = r.normals.reversed);
  report["storage_bytes"] = r.storageBytes;
  if (result.part) report["part"] = std::make_shared<Mesh>(std::move(*result.part));
  if (r.kind == RebuildKind::CrossSections) {
    report["sections"] = sectionList(result.sections);
    report["part_storage_bytes"] = r.referenceStorageBytes;
    return report;
  }
  py::list iterations;
  for (const FitIteration& it : r.iterations) iterations.append(iterationDict(it));
  report["iterations"] = iterations;
  report["stop_reason"] = r.stopReason;
  report["frames"] = r.frames;
  if (r.automatic) report["mesh_storage_bytes"] = r.referenceStorageBytes;
  if (r.search) {
    report["target_reached"] = r.search->reached;
    report["rms_reached"] = r.search->met.rms;
    report["folds_reached"] = r.search->met.folds;
    report["normals_reached"] = r.search->met.normals;
    report["trials"] = r.search->trials;
    report["search_stop"] = searchStopName(r.search->stop);
    report["grid"] = r.automatic ? r.automatic->grid : 0;
  }
  return report;
}

/// pdesurf.rebuild: the library's rebuild -> (model, report).
py::tuple rebuildMesh(const Mesh& mesh, const std::string& source, const py::object& progress,
                      const py::kwargs& keywords) {
  const RebuildOptions options = rebuildOptions(keywords, source);
  RebuildProgress calls;
  if (!progress.is_none())
    calls.onIteration = [&](const FitIteration& it) {
      py::gil_scoped_acquire gil;
      progress(iterationDict(it));
    };
  std::optional<RebuildResult> result;
  {
    py::gil_scoped_release release;
    result.emplace(rebuild(mesh, options, calls));
  }
  py::dict report = reportDict(*result);
  const Model model{std::make_shared<const AnyModel>(std::move(result->model)), source};
  return py::make_tuple(model, report);
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
  m.def("rebuild", &rebuildMesh, py::arg("mesh"), py::arg("source"), py::arg("progress"),
        "The library's rebuild of a mesh with pdesurf.rebuild's keywords -> (model, report).\n"
        "The GIL is released meanwhile (taken again for progress).");
  m.def(
      "check_rebuild_options",
      [](const py::kwargs& keywords) { rebuildOptions(keywords, "<options>"); },
      "Checks pdesurf.rebuild's keywords before any work; raises ValueError naming one.");
  m.def(
      "storage_bytes",
      [](const py::object& value) -> std::size_t {
        if (py::isinstance<Mesh>(value)) return storageBytes(value.cast<const Mesh&>());
        const Model& model = value.cast<const Model&>();
        // Type branches kept: only these two methods have a storage measure (storageBytes).
        if (const auto* f = model.model->as<VertexFrameModel>()) return storageBytes(*f);
        if (const auto* c = model.model->as<CrossSectionModel>()) return storageBytes(*c);
        badArgument("model", "storage is counted for vertex-frames and cross-sections models");
      },
      py::arg("model"),
      "Storage under the seed's Table 1 convention (six significant digits as text) of a\n"
      "vertex-frames or cross-sections model, or a mesh.");
  m.def("export_cad", &exportCad, py::arg("surface"), py::arg("path"),
        py::arg("tolerance") = py::none(), py::arg("max_spans") = 512,
        "Writes STEP or IGES (by the extension) -> the export report (pdesurf.export wraps it).");
}

}  // namespace pdesurf::python
