// `pdesurf spine`: the spine A0(u) of a spectral or cross-sections model (docs/spectral.md).
#include <cstdint>
#include <iostream>
#include <string>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "pdesurf/model.hpp"
#include "pdesurf/model_io.hpp"
#include "spectral_commands.hpp"

namespace pdesurf::cli {

namespace {

/// `pdesurf spine`: A0(u) of a spectral or cross-sections model.
struct SpineCommand {
  std::string modelPath;
  std::uint32_t count = 33;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "spine", "Print the spine A0(u) of a spectral or cross-sections model as JSON polylines");
    addModelFile(cmd, modelPath);
    cmd->add_option("--count", count, "points per patch")
        ->check(CLI::Range(2u, 100000u))
        ->capture_default_str();
    return cmd;
  }

  int run() const {
    const SolvedModel solved = solve(loadModel(modelPath), modelPath);
    // A type branch kept: a spine (the curve of A0) is spectral patches' own.
    if (!solved.spectral())
      throw UsageError(fmt::format(
          "{}: only spectral and cross-sections models have a spine (this is a {} model)",
          modelPath, solved.type()));
    std::cout << spineJson(*solved.spectral(), count);
    return 0;
  }
};

}  // namespace

Registered addSpineCommand(CLI::App& app) { return registerCommand<SpineCommand>(app); }

}  // namespace pdesurf::cli
