// pdesurf: the command line (apps/cli/cli.hpp). Thin: parse arguments, call the library,
// report. Each command is a small struct in its own file (apps/cli/commands.hpp lists them).
// Exit codes: 0 success, 1 bad input (model or mesh file), 2 usage error.
#include "cli.hpp"

#include <cstdio>
#include <exception>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "export_command.hpp"
#include "pdesurf/error.hpp"
#include "pdesurf/mesh_io.hpp"
#include "rebuild_command.hpp"

namespace pdesurf::cli {

int runCli(int argc, char** argv) {
  CLI::App app{
      "pdesurf: PDE-based surface modelling from vertex-frames.\n"
      "Exit status: 0 success, 1 invalid input file, 2 usage error."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "pdesurf 0.1.0");
  // Before or after the command's name: `pdesurf --threads 2 build …` or `pdesurf build … --threads
  // 2`.
  app.fallthrough();
  unsigned threads = 0;
  app.add_option("--threads", threads,
                 "threads for tessellation, evaluation, compare and slice (default 0: all cores); "
                 "the output is the same for any number")
      ->check(CLI::Range(0u, 4096u));

  // Every command, in the order --help lists them (a braced list runs in order), and what
  // runs the one given.
  const std::vector<Registered> registered = {addBuildCommand(app),
                                              addSampleCommand(app),
                                              addInfoCommand(app),
                                              addStudioCommand(app),
                                              addFitCommand(app),
                                              addSpineCommand(app),
                                              addCoonsCommand(app),
                                              addSliceCommand(app),
                                              addCompareCommand(app),
                                              registerCommand<ExportCommand>(app),
                                              registerCommand<RebuildCommand>(app)};

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitUsage;
  }

  // Every parallel loop (oneTBB) runs on at most this many threads.
  std::optional<tbb::global_control> threadLimit;
  if (threads > 0) threadLimit.emplace(tbb::global_control::max_allowed_parallelism, threads);

  try {
    for (const Registered& r : registered)
      if (*r.command) return r.run();
    return kExitUsage;  // require_subcommand(1): not reached
  } catch (const UsageError& e) {
    fmt::print(stderr, "pdesurf: {}\n", e.what());
    return kExitUsage;
  } catch (const Error& e) {  // bad input: a model, a mesh, an argument the library refuses
    fmt::print(stderr, "pdesurf: {}\n", e.what());
    return kExitInput;
  } catch (const std::exception& e) {
    fmt::print(stderr, "pdesurf: {}\n", e.what());
    return kExitInput;
  }
}

}  // namespace pdesurf::cli
