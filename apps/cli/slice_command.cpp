// `pdesurf slice`: a mesh cut by planes, each plane's chosen loop as JSON (docs/mesh-tools.md).
#include <cstdint>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "pdesurf/atomic_file.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/mesh_slice.hpp"

namespace pdesurf::cli {

namespace {

/// What `pdesurf slice --help` says the command does.
constexpr const char* kSliceHelp =
    "Cut a mesh (OFF, OBJ, PLY, STL) by planes perpendicular to an axis; print each "
    "plane's largest closed loop (or the one --near / --track pick) as JSON";

/// `pdesurf slice`: each plane's largest closed loop, as JSON.
struct SliceCommand {
  std::string meshPath, outPath, axis;
  std::uint32_t count = 0;
  std::vector<double> range, near;
  bool track = false;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("slice", kSliceHelp);
    addMeshFile(cmd, meshPath);
    cmd->add_option("--axis", axis, "axis the planes are perpendicular to: x, y or z")
        ->required()
        ->check(CLI::IsMember({"x", "y", "z"}));
    cmd->add_option("--count", count, "number of planes K, evenly spaced")
        ->required()
        ->check(CLI::Range(1u, 100000u));
    cmd->add_option("--range", range,
                    "planes from a to b, both ends included (default: the mesh's extent cut "
                    "into K slabs, a plane in the middle of each)")
        ->expected(2);
    cmd->add_option("--near", near,
                    "keep on each plane the closed loop whose centroid is nearest to the point "
                    "X Y Z projected onto the plane (one part of a mesh that a plane cuts in "
                    "several loops, such as one leg)")
        ->expected(3);
    cmd->add_flag("--track", track,
                  "keep on each plane the loop nearest to the previous plane's loop (the first "
                  "plane: nearest to --near if given, else the largest), following a part "
                  "that moves across the planes");
    cmd->add_option("-o,--output", outPath, "write the JSON to this file (whole or not at all)");
    return cmd;
  }

  int run() const {
    const SliceOptions options = sliceOptionsFrom<UsageError>(axis, count, range, near, track);
    const Mesh mesh = readTriangles(meshPath);
    std::vector<MeshSection> sections;
    try {
      sections = sliceMesh(mesh, options);
    } catch (const MeshSliceError& e) {
      throw MeshIoError(meshPath, e.what());
    }
    Json planes = Json::array();
    for (const MeshSection& section : sections) {
      Json points = Json::array();
      for (const Vec3& p : section.points) points.push_back(pointJson(p));
      planes.push_back({{"index", section.index},
                        {"coordinate", section.coordinate},
                        {"points", std::move(points)},
                        {"length", section.length},
                        {"area", section.area}});
    }
    const std::string text =
        Json{{"axis", axisName(options.axis)}, {"planes", std::move(planes)}}.dump() + "\n";
    if (outPath.empty())
      std::cout << text;
    else
      writeFileAtomically(outPath, text);
    return 0;
  }
};

}  // namespace

Registered addSliceCommand(CLI::App& app) { return registerCommand<SliceCommand>(app); }

}  // namespace pdesurf::cli
