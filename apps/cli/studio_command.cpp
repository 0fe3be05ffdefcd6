// `pdesurf studio`: the studio server (apps/studio) until Ctrl-C.
#include <string>

#include <CLI/CLI.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "server.hpp"

namespace pdesurf::cli {

namespace {

/// `pdesurf studio`: the studio server until Ctrl-C.
struct StudioCommand {
  std::string modelPath;
  pdesurf::studio::StudioOptions options;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand(
        "studio", "Serve a model for interactive editing in a browser (until Ctrl-C)");
    addModelFile(cmd, modelPath);
    cmd->add_option("--root", options.root,
                    "folder the studio may open and write in (default: the model's folder)");
    cmd->add_option("--port", options.port, "port to listen on (0: any free port)")
        ->check(CLI::Range(0, 65535))
        ->capture_default_str();
    cmd->add_option("--host", options.host, "address to listen on")->capture_default_str();
    cmd->add_flag_callback(
        "--no-token", [this] { options.requireToken = false; },
        "UNSAFE, for tests only: serve the API without the per-launch token of the printed URL "
        "(any program of any local user may then read and change the models)");
    return cmd;
  }

  int run() const { return pdesurf::studio::runStudio(modelPath, options); }
};

}  // namespace

Registered addStudioCommand(CLI::App& app) { return registerCommand<StudioCommand>(app); }

}  // namespace pdesurf::cli
