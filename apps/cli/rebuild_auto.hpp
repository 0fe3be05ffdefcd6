// `pdesurf rebuild --as vertex-frames` without --layout, --grid or --tube: the automatic
// layout, of about --frames N frames or the smallest that reaches --target-rms X
// (docs/rebuild.md, "The automatic layout").
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "pdesurf/auto_layout.hpp"
#include "pdesurf/mesh.hpp"
#include "pdesurf/rebuild.hpp"

namespace pdesurf::cli {

/// The automatic layout when no frames are given.
inline constexpr std::uint32_t kDefaultAutoFrames = 200;

struct AutoLayoutArgs {
  std::uint32_t frames = 0;   ///< --frames N (0: not given)
  std::string targetRms;      ///< --target-rms X, as given ("0.002" or "0.2%"; empty: not given)
  std::string quads;          ///< --quads pair|split (empty: not given, pair)
  double creaseAngle = -1.0;  ///< --crease-angle (negative: not given, 60°)

  void add(CLI::App* cmd);
  /// An option of the automatic layout given (--frames, --target-rms, --quads,
  /// --crease-angle).
  bool given() const {
    return frames != 0 || !targetRms.empty() || !quads.empty() || creaseAngle >= 0.0;
  }
  /// Throws UsageError for --frames with --target-rms.
  void check() const;
  /// The layout's options, with --frames (or the default).
  AutoLayoutOptions options() const;
  /// --target-rms as a fraction of the diagonal; throws UsageError unless it is a number in
  /// (0, 1) (a percentage in (0 %, 100 %)).
  double target() const;
};

/// The automatic layout of about --frames frames; prints what it made unless `quiet`.
VertexFrameModel automaticLayout(const AutoLayoutArgs& args, const Mesh& mesh,
                                 const std::string& meshPath, bool quiet);

/// The smallest automatic layout whose fitted model reaches --target-rms both ways (measured
/// at `resolution`), each trial printed unless `quiet`, then whether it reached it. Sets
/// `layout` to that layout and returns its fit.
FitResult searchAutomaticLayout(const AutoLayoutArgs& args, const Mesh& mesh,
                                const std::string& meshPath, const FitOptions& fit,
                                std::uint32_t resolution, bool quiet, VertexFrameModel& layout);

/// "mesh storage" beside the model's (storageBytes of both, as docs/accuracy-storage.md
/// counts them).
void printStorageAgainstMesh(const VertexFrameModel& model, const Mesh& mesh);

}  // namespace pdesurf::cli
