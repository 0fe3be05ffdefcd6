// `pdesurf info`: a model's counts, quality figures, bounding box and storage.
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "pdesurf/model.hpp"
#include "solve_args.hpp"

namespace pdesurf::cli {

namespace {

/// `pdesurf info`: counts, quality figures, bounding box, storage.
struct InfoCommand {
  std::string modelPath;
  bool json = false;
  SolveArgs solveArgs;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "info", "Counts, the largest C0 gap on shared edges, bounding box and storage size");
    addModelFile(cmd, modelPath);
    cmd->add_flag("--json", json, "print JSON");
    solveArgs.add(cmd);
    return cmd;
  }

  int run() const {
    std::cout << infoText(loadSolved(modelPath, solveArgs), json);
    return 0;
  }
};

}  // namespace

Registered addInfoCommand(CLI::App& app) { return registerCommand<InfoCommand>(app); }

}  // namespace pdesurf::cli
