// `pdesurf sample`: every patch of a model sampled on a grid, as JSON.
#include <cstdint>
#include <iostream>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "pdesurf/method.hpp"
#include "pdesurf/model.hpp"
#include "solve_args.hpp"

namespace pdesurf::cli {

namespace {

/// `pdesurf sample`: every patch on a grid, as JSON.
struct SampleCommand {
  std::string modelPath;
  std::uint32_t grid = 0;
  SolveArgs solveArgs;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "sample",
        "Print each patch sampled on a grid as JSON: points[j*N+i] = S(i/(N-1), j/(N-1))");
    addModelFile(cmd, modelPath);
    cmd->add_option("--grid", grid, "samples per patch side (N)")
        ->required()
        ->check(CLI::Range(2u, 4097u));
    solveArgs.add(cmd);
    return cmd;
  }

  int run() const {
    // Keys in the order written; doubles in their shortest round-trip form.
    nlohmann::ordered_json patches = nlohmann::ordered_json::array();
    const SolvedModel solved = loadSolved(modelPath, solveArgs);
    // Each patch's index under what its method calls a patch ("frame", "patch").
    const char* patchKey = solved.model().method().patchName();
    for (const PatchSamples& p : sample(solved, {grid})) {
      nlohmann::ordered_json points = nlohmann::ordered_json::array();
      for (const Vec3& q : p.points) points.push_back({q.x(), q.y(), q.z()});
      nlohmann::ordered_json patch = {{patchKey, p.index}, {"grid", p.grid}};
      if (p.u) patch["u"] = {p.u->first, p.u->second};
      if (p.origin) patch["origin"] = {(*p.origin)[0], (*p.origin)[1]};
      patch["points"] = std::move(points);
      patches.push_back(std::move(patch));
    }
    std::cout << nlohmann::ordered_json{{"patches", std::move(patches)}}.dump() << '\n';
    return 0;
  }
};

}  // namespace

Registered addSampleCommand(CLI::App& app) { return registerCommand<SampleCommand>(app); }

}  // namespace pdesurf::cli
