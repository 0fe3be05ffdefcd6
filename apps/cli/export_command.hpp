// `pdesurf export`: a model's patches as B-spline faces in a STEP or IGES file, through Open
// CASCADE (docs/nurbs-export.md).
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "pdesurf/nurbs.hpp"

namespace pdesurf::cli {

struct ExportCommand {
  std::string modelPath, outPath;
  double tolerance = 0.0;
  std::uint32_t maxSpans = NurbsExportOptions{}.maxSpans;
  bool json = false, quiet = false;
  CLI::Option* toleranceOption = nullptr;

  /// Registers the subcommand on `app`.
  CLI::App* add(CLI::App& app);
  /// Runs it: 0 on success, 2 for a usage error (after printing it); an invalid model file
  /// or a failed write throws, for main's handlers (exit 1). No output file is left behind
  /// on any failure.
  int run() const;
};

}  // namespace pdesurf::cli
