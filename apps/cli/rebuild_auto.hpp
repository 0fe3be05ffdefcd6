// `pdesurf rebuild --as vertex-frames` without --layout, --grid or --tube: the automatic
// layout, of about --frames N frames or the smallest that reaches --target-rms X
// (docs/rebuild.md, "The automatic layout"): its options, and the lines it prints.
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "pdesurf/mesh_rebuild.hpp"

namespace pdesurf::cli {

struct AutoLayoutArgs {
  std::uint32_t frames = 0;   ///< --frames N (0: not given)
  std::string targetRms;      ///< --target-rms X, as given ("0.002" or "0.2%"; empty: not given)
  std::string quads;          ///< --quads pair|split (empty: not given, pair)
  double creaseAngle = -1.0;  ///< --crease-angle (negative: not given, 60°)
  double maxNormalDeviation = kMaxNormalDeviation;  ///< --max-normal-deviation DEGREES
  CLI::Option* maxNormalDeviationOption = nullptr;  ///< ... and whether it was given

  void add(CLI::App* cmd);
  /// Sets the automatic layout's options that were given (--target-rms parsed: a bad one
  /// throws RebuildOptionError).
  void apply(RebuildOptions& options) const;
};

/// "automatic layout (about N asked for): ..." (before its fit).
void printAutomaticLayout(const AutoLayoutReport& layout);

/// One trial of the target search.
void printTrial(const RebuildOptions& options, std::uint32_t requested, const AutoFit& fit);

/// How the target search ended: the target reached (or not) and the layout it chose.
void printSearch(const RebuildOptions& options, const RebuildReport& report);

/// "mesh storage" beside the model's (storageBytes of both, as docs/accuracy-storage.md
/// counts them).
void printStorageAgainstMesh(const RebuildReport& report);

}  // namespace pdesurf::cli
