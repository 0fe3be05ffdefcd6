// `pdesurf fit`: Fourier fits of the closed curves of a curves file (docs/spectral.md).
#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "spectral_commands.hpp"

namespace pdesurf::cli {

namespace {

/// `pdesurf fit`: Fourier fits of the closed curves of a curves file.
struct FitCommand {
  std::string curvesPath;
  std::vector<std::uint32_t> terms;
  bool uniform = false, json = false;

  static constexpr const char* kHelp =
      "Fit each closed curve of a curves file (a cross-sections model or {\"curves\": [...]}) by "
      "a Fourier series; print the largest and mean distance of the points per number of terms";

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("fit", kHelp);
    cmd->add_option("curves", curvesPath, "curves file (JSON)")->required();
    cmd->add_option("--terms", terms, "numbers of Fourier terms N (one or more)")
        ->required()
        ->check(CLI::Range(0u, 512u));
    cmd->add_flag("--uniform", uniform,
                  "give points uniform v (default: chord length, as the seeds)");
    cmd->add_flag("--json", json, "print JSON");
    return cmd;
  }

  int run() const {
    std::cout << fitReport(curvesPath, terms, !uniform, json);
    return 0;
  }
};

}  // namespace

Registered addFitCommand(CLI::App& app) { return registerCommand<FitCommand>(app); }

}  // namespace pdesurf::cli
