// The CLI's commands, one file each (apps/cli/*_command.cpp), as main registers them: each
// is a small struct whose add() declares its subcommand and options and whose run() runs it.
#pragma once

#include <functional>
#include <memory>

#include <CLI/CLI.hpp>

namespace pdesurf::cli {

/// A command registered on the app: its subcommand, and what runs it when that subcommand
/// was given (0 on success; a bad input file or a usage error throws, for main's handlers).
struct Registered {
  CLI::App* command;
  std::function<int()> run;
};

/// Registers a command struct; the returned function keeps it (and the options CLI11 parses
/// into it) alive.
template <class Command>
Registered registerCommand(CLI::App& app) {
  auto command = std::make_shared<Command>();
  CLI::App* sub = command->add(app);
  return {sub, [command] { return command->run(); }};
}

Registered addBuildCommand(CLI::App& app);
Registered addSampleCommand(CLI::App& app);
Registered addInfoCommand(CLI::App& app);
Registered addStudioCommand(CLI::App& app);
Registered addFitCommand(CLI::App& app);
Registered addSpineCommand(CLI::App& app);
Registered addCoonsCommand(CLI::App& app);
Registered addSliceCommand(CLI::App& app);
Registered addCompareCommand(CLI::App& app);

}  // namespace pdesurf::cli
