#include "rebuild_command.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "pdesurf/analysis.hpp"
#include "pdesurf/atomic_file.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/occt_loft.hpp"
#include "pdesurf/section_rebuild.hpp"
#include "pdesurf/spectral_io.hpp"

namespace pdesurf::cli {

namespace {

using Json = nlohmann::ordered_json;

/// A well-formed argument that cannot be used (exit 2).
struct RebuildUsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Rows per patch and columns around v for measuring a chain against its mesh: about 256
/// rows over the chain and 256 columns, so that the tessellation's own chord error (below
/// 1e-4 of a section's radius for 8 modes) stays far below the distances measured.
SpectralTessellateOptions measureOptions(std::size_t patches) {
  SpectralTessellateOptions o;
  o.uResolution =
      static_cast<std::uint32_t>(std::max<std::size_t>(3, (256 + patches - 1) / patches + 1));
  o.vResolution = 256;
  return o;
}

/// The loft's triangulation lies within this fraction of the part's diagonal of the loft
/// surface: 0.01 %, a tenth of the smallest distances compared (0.1 % and up).
constexpr double kLoftDeflection = 1e-4;

Json oneWay(const OneWayDistance& d) {
  return {{"rms", d.rms},   {"rms_relative", d.rmsRelative},
          {"mean", d.mean}, {"mean_relative", d.meanRelative},
          {"max", d.max},   {"max_relative", d.maxRelative}};
}

}  // namespace

CLI::App* RebuildCommand::add(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "rebuild",
      "Rebuild a mesh as a PDE model (cross-sections: slice it, align and fit the sections, "
      "join them by the global C4 chain); print its distance to the mesh and its storage");
  cmd->add_option("mesh", meshPath, "mesh file: .off .obj .ply .stl")->required();
  cmd->add_option("--as", as, "the kind of model to build")
      ->required()
      ->check(CLI::IsMember({"cross-sections"}));
  cmd->add_option("-o,--output", outPath, "model file to write (JSON; whole or not at all)");
  cmd->add_option("--axis", axis, "cross-sections: axis the slicing planes are perpendicular to")
      ->check(CLI::IsMember({"x", "y", "z"}))
      ->capture_default_str();
  cmd->add_option("--count", count, "cross-sections: number of sections K")
      ->check(CLI::Range(2u, 100000u))
      ->capture_default_str();
  cmd->add_option("--range", range,
                  "cross-sections: sections from a to b, both ends included (default: the "
                  "mesh's extent cut into K slabs, a plane in the middle of each)")
      ->expected(2);
  cmd->add_option("--near", near,
                  "cross-sections: on each plane the loop whose centroid is nearest to X Y Z "
                  "(needed where a plane cuts several parts)")
      ->expected(3);
  cmd->add_flag("--track", track,
                "cross-sections: follow the part from plane to plane (each plane: the loop "
                "nearest to the previous plane's)");
  cmd->add_option("--modes", modes, "Fourier modes per section")
      ->check(CLI::Range(1u, 256u))
      ->capture_default_str();
  cmd->add_option("--points", points, "points per section after arc-length resampling")
      ->check(CLI::Range(8u, 100000u))
      ->capture_default_str();
  cmd->add_option("--a", a, "the sixth-order operator's a (chain parameter u in [0, 1])")
      ->capture_default_str();
  cmd->add_option("--ends", ends,
                  "conditions at the end sections: natural (third and fourth u-derivatives "
                  "zero) or estimated (first and second from the end sections)")
      ->check(CLI::IsMember({"natural", "estimated"}))
      ->capture_default_str();
  cmd->add_option("--name", name, "the model's name (default: the mesh file's name)");
  cmd->add_option("--part", partPath,
                  "also write the part of the mesh the model rebuilds (.obj .ply .stl .off)");
  cmd->add_option("--samples", samples, "face samples on each mesh for the distances")
      ->check(CLI::Range(std::size_t{1}, std::size_t{100000000}))
      ->capture_default_str();
  cmd->add_flag("--exact", exact,
                "cross-sections: pass through every prepared point of every section (the "
                "model keeps the points and the remainder; more storage) instead of their "
                "smooth M-mode fits");
  cmd->add_flag("--loft", loft,
                "also loft the same prepared sections with Open CASCADE "
                "(BRepOffsetAPI_ThruSections through periodic interpolating B-splines) and "
                "measure it the same way: the peer a CAD user would reach for");
  cmd->add_flag("--json", json, "print JSON");
  return cmd;
}

int RebuildCommand::run() const {
  try {
    if (!std::isfinite(a) || a == 0.0)
      throw RebuildUsageError(fmt::format("--a {}: a must be finite and non-zero", a));
    if (points < 2 * modes + 1)
      throw RebuildUsageError(
          fmt::format("--points {} cannot determine --modes {}: give at least {} points", points,
                      modes, 2 * modes + 1));
    if (!outPath.empty() && !outPath.ends_with(".json"))
      throw RebuildUsageError(fmt::format("-o {}: a model file ends in .json", outPath));
    SectionRebuildOptions options;
    options.slice.axis = *parseAxis(axis);
    options.slice.count = count;
    if (!range.empty()) {
      options.slice.range = {range[0], range[1]};
      try {
        slicePlanes(options.slice, 0.0, 1.0);  // the range's own checks, before any work
      } catch (const std::invalid_argument& e) {
        throw RebuildUsageError(fmt::format("--range: {}", e.what()));
      }
    }
    if (!near.empty()) {
      options.slice.near = Vec3(near[0], near[1], near[2]);
      if (!options.slice.near->allFinite())
        throw RebuildUsageError(
            fmt::format("--near: {} {} {} is not a finite point", near[0], near[1], near[2]));
    }
    options.slice.track = track;
    options.modes = modes;
    options.exact = exact;
    options.prep.points = points;
    options.a = a;
    options.ends = ends == "natural" ? ChainEnds::Natural : ChainEnds::Estimated;
    options.name = name.empty() ? modelName("", meshPath) : name;
    auto t0 = Clock::now();
    const Mesh mesh = readMesh(meshPath);
    if (mesh.triangleCount() == 0) throw MeshIoError(meshPath + ": the mesh has no triangles");
    const double readMs = msSince(t0);
    t0 = Clock::now();
    SectionRebuild rebuilt;
    try {
      rebuilt = rebuildFromSections(mesh, options);
    } catch (const std::exception& e) {
      throw MeshIoError(fmt::format("{}: {}", meshPath, e.what()));
    }
    const double rebuildMs = msSince(t0);
    const auto& sections = rebuilt.sections;
    rebuilt.model.description =
        fmt::format("{} rebuilt by pdesurf rebuild from {} sections along {} in [{}, {}]", meshPath,
                    sections.size(), axis, sections.front().coordinate, sections.back().coordinate);
    t0 = Clock::now();
    const Mesh part = sectionedPart(mesh, options.slice.axis, sections);
    const Mesh surface = tessellate(rebuilt.chain, measureOptions(rebuilt.chain.patches.size()));
    DistanceOptions distanceOptions;
    distanceOptions.samples = samples;
    MeshDistance d;
    try {
      d = meshDistance(surface, part, distanceOptions);
    } catch (const std::invalid_argument& e) {
      throw MeshIoError(fmt::format("{}: the rebuilt part: {}", meshPath, e.what()));
    }
    const double measureMs = msSince(t0);
    // The peer: Open CASCADE's loft through the same sections, measured the same way.
    std::optional<MeshDistance> loftDistance;
    std::string loftFailure;
    if (loft) {
      try {
        const Mesh lofted = occtLoft(rebuilt.prepared, kLoftDeflection * d.diagonal);
        loftDistance = meshDistance(lofted, part, distanceOptions);
      } catch (const std::exception& e) {
        loftFailure = e.what();
      }
    }
    if (!partPath.empty()) writeMesh(part, partPath);
    if (!outPath.empty()) writeFileAtomically(outPath, serializeModel(rebuilt.model));
    const std::size_t modelBytes = storageBytes(rebuilt.model), partBytes = storageBytes(part);
    if (json) {
      Json j = {{"mesh", meshPath},
                {"as", as},
                {"output", outPath},
                {"axis", axis},
                {"sections", sections.size()},
                {"from", sections.front().coordinate},
                {"to", sections.back().coordinate},
                {"modes", modes},
                {"exact", exact},
                {"a", a},
                {"ends", ends},
                {"diagonal", d.diagonal},
                {"model_to_part", oneWay(d.aToB)},
                {"part_to_model", oneWay(d.bToA)},
                {"model_storage_bytes", modelBytes},
                {"part_storage_bytes", partBytes},
                {"part_triangles", part.triangleCount()},
                {"part_vertices", part.vertexCount()},
                {"ms", {{"read", readMs}, {"rebuild", rebuildMs}, {"measure", measureMs}}}};
      if (loftDistance)
        j["loft"] = {{"model_to_part", oneWay(loftDistance->aToB)},
                     {"part_to_model", oneWay(loftDistance->bToA)}};
      else if (loft)
        j["loft"] = {{"failed", loftFailure}};
      std::cout << j.dump(2) << '\n';
      return 0;
    }
    auto percent = [](double relative) { return fmt::format("{:.3g}%", 100.0 * relative); };
    fmt::print(
        "{}: {} sections along {} from {} to {}, {} modes{}, global C4 chain (a = {}, {} "
        "ends){}\n",
        options.name, sections.size(), axis, sections.front().coordinate,
        sections.back().coordinate, modes, exact ? " + exact remainder" : "", a, ends,
        outPath.empty() ? "" : " -> " + outPath);
    fmt::print("part of the mesh: {}, {}, diagonal {:.6g}\n",
               cli::count(part.vertexCount(), "vertex"),
               cli::count(part.triangleCount(), "triangle"), d.diagonal);
    for (const auto& [label, w] :
         {std::pair{"model -> part", &d.aToB}, std::pair{"part -> model", &d.bToA}})
      fmt::print("{}  RMS {:.4g} ({})  mean {:.4g} ({})  max {:.4g} ({})\n", label, w->rms,
                 percent(w->rmsRelative), w->mean, percent(w->meanRelative), w->max,
                 percent(w->maxRelative));
    if (loftDistance)
      for (const auto& [label, w] : {std::pair{"OCCT loft -> part", &loftDistance->aToB},
                                     std::pair{"part -> OCCT loft", &loftDistance->bToA}})
        fmt::print("{}  RMS {:.4g} ({})  mean {:.4g} ({})  max {:.4g} ({})\n", label, w->rms,
                   percent(w->rmsRelative), w->mean, percent(w->meanRelative), w->max,
                   percent(w->maxRelative));
    else if (loft)
      fmt::print("OCCT loft: failed ({})\n", loftFailure);
    fmt::print(
        "storage: model {} bytes, part of the mesh {} bytes ({:.3g}x; numbers to six "
        "significant digits)\n",
        modelBytes, partBytes, double(modelBytes) / double(partBytes));
    fmt::print("(read {:.1f} ms, slice + prepare + fit + solve {:.1f} ms, measure {:.1f} ms)\n",
               readMs, rebuildMs, measureMs);
    return 0;
  } catch (const RebuildUsageError& e) {
    fmt::print(stderr, "pdesurf: {}\n", e.what());
    return kExitUsage;
  }
}

}  // namespace pdesurf::cli
