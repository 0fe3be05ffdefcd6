#include "solve_args.hpp"

#include <cstdio>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/model_io.hpp"

namespace pdesurf::cli {

void SolveArgs::add(CLI::App* cmd) {
  cmd->add_option("--solver", solver,
                  "global: each strip minimises its patches' summed PDE "
                  "residual; local: the seed's patch generation rule")
      ->check(CLI::IsMember({"global", "local"}))
      ->capture_default_str();
  cmd->add_option("--seed-frame", seedFrame, "local solver: the frame generation starts from")
      ->capture_default_str();
}

SolveOptions SolveArgs::options(const AnyModel& model) const {
  SolveOptions options;
  options.vertexFrames = {solver == "local" ? Solver::Local : Solver::Global, seedFrame};
  try {
    checkSolveOptions(model, options);
  } catch (const InvalidArgument& e) {
    throw UsageError(fmt::format("--seed-frame {}: {}", seedFrame, e.what()));
  }
  return options;
}

void checkMeshExtension(const std::string& outPath) {
  try {
    meshFormatFromPath(outPath);
  } catch (const MeshIoError& e) {
    throw UsageError(e.what());
  }
}

SolvedModel solveWith(AnyModel any, const std::string& modelPath, const SolveArgs& args) {
  const SolveOptions options = args.options(any);
  SolvedModel solved = solve(std::move(any), modelPath, options);
  for (const std::string& note : solved.notes())
    fmt::print(stderr, "{}: note: {}\n", solved.source(), note);
  return solved;
}

SolvedModel loadSolved(const std::string& modelPath, const SolveArgs& args) {
  return solveWith(loadModel(modelPath), modelPath, args);
}

BuiltModel buildModel(const std::string& modelPath, std::uint32_t resolution,
                      const SolveArgs& args) {
  BuiltModel built;
  AnyModel any = loadModel(modelPath);
  auto t0 = Clock::now();
  const SolvedModel solved = solveWith(std::move(any), modelPath, args);
  built.solveMs = msSince(t0);
  built.name = solved.displayName();
  t0 = Clock::now();
  built.mesh = tessellate(solved, {resolution});
  built.tessMs = msSince(t0);
  built.report = report(solved);
  return built;
}

}  // namespace pdesurf::cli
