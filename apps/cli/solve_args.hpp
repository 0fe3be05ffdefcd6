// How the CLI's commands load and solve models: the solver options they share (--solver,
// --seed-frame), the solver's notes on stderr, and build's solve-and-tessellate.
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "pdesurf/mesh.hpp"
#include "pdesurf/model.hpp"

namespace pdesurf::cli {

/// --solver and --seed-frame (vertex-frame models).
struct SolveArgs {
  std::string solver = "global";
  std::uint32_t seedFrame = 0;

  void add(CLI::App* cmd);
  /// The options for `model`; a seed frame it does not have is a usage error.
  SolveOptions options(const AnyModel& model) const;
};

/// An output path pdesurf cannot write (by its extension) is a usage error, found before
/// any work.
void checkMeshExtension(const std::string& outPath);

/// Solves a model of any type with the command's solver options, printing the solver's notes.
SolvedModel solveWith(AnyModel any, const std::string& modelPath, const SolveArgs& args);

/// Loads and solves the model file at `modelPath`.
SolvedModel loadSolved(const std::string& modelPath, const SolveArgs& args);

/// A model of any type solved and tessellated: what `build` writes and `compare` measures.
struct BuiltModel {
  std::string name;
  ModelReport report;
  Mesh mesh;
  double solveMs = 0.0, tessMs = 0.0;
};

BuiltModel buildModel(const std::string& modelPath, std::uint32_t resolution,
                      const SolveArgs& args);

}  // namespace pdesurf::cli
