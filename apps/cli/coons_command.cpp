// `pdesurf coons`: Coons patches on the boundaries of a vertex-frame model's patches
// (docs/coons.md).
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "pdesurf/coons.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/vertex_frames.hpp"
#include "solve_args.hpp"

namespace pdesurf::cli {

namespace {

/// What `pdesurf coons --help` says the command does.
constexpr const char* kCoonsHelp =
    "Coons patches on the boundary curves of a vertex-frame model's patches (the seed's "
    "baselines): bicubic with tangents w1 α(u), w2 β(u), w3 γ(v), w4 δ(v), or bilinear";

/// `pdesurf coons`: bilinear or bicubic Coons patches on the boundaries of a model's
/// vertex-frame patches (the seed 000 §4.2 baselines), written as a mesh.
struct CoonsCommand {
  std::string modelPath, outPath;
  std::vector<std::uint32_t> frames;
  std::vector<double> tangents;
  std::uint32_t resolution = 17;
  bool bilinear = false, own = false;
  SolveArgs solveArgs;

  CLI::App* add(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("coons", kCoonsHelp);
    addModelFile(cmd, modelPath, "vertex-frames model file (JSON)");
    addMeshOutput(cmd, outPath);
    cmd->add_option("--frame", frames, "the frames to fill (default: every frame)");
    cmd->add_option("--tangents", tangents,
                    "w1,w2,w3,w4 as 12 numbers w1x,w1y,w1z,...,w4z (default 0: flat tangents)")
        ->delimiter(',')
        ->expected(12);
    cmd->add_flag("--own-tangents", own,
                  "use each patch's own cross-boundary derivatives as tangents (then a patch "
                  "without forces is reproduced)");
    cmd->add_flag("--bilinear", bilinear, "bilinear Coons patches (no tangents)");
    addResolution(cmd, resolution);
    solveArgs.add(cmd);
    return cmd;
  }

  int run() const {
    if (bilinear + own + !tangents.empty() > 1)
      throw UsageError("coons: choose one of --bilinear, --tangents and --own-tangents");
    checkMeshExtension(outPath);
    AnyModel any = loadModel(modelPath);
    // A type branch kept: the Coons baselines interpolate vertex-frame patches' own boundary
    // curves and tangents, which no other method has.
    const auto* model = any.as<VertexFrameModel>();
    if (!model) throw UsageError(fmt::format("{}: coons takes a vertex-frames model", modelPath));
    const VertexFrameSurface surface = solve(*model, solveArgs.options(any).vertexFrames);
    std::vector<std::uint32_t> which = frames;
    if (which.empty())
      for (std::uint32_t k = 0; k < surface.patches.size(); ++k) which.push_back(k);
    std::array<Vec3, 4> w;  // Eigen vectors start uninitialised: zero them
    w.fill(Vec3::Zero());
    for (std::size_t i = 0; i < tangents.size(); ++i)
      w[i / 3][static_cast<int>(i % 3)] = tangents[i];
    std::vector<CoonsPatch> patches;
    for (std::uint32_t k : which) {
      if (k >= surface.patches.size())
        throw UsageError(fmt::format("--frame {}: out of range, the model has {} frame{}", k,
                                     surface.patches.size(),
                                     surface.patches.size() == 1 ? "" : "s"));
      const VertexFramePatch& patch = surface.patches[k];
      CoonsBoundary boundary = boundaryOf(patch);
      if (bilinear) {
        patches.push_back(CoonsPatch::bilinear(std::move(boundary)));
      } else {
        CoonsTangents t = own ? patchTangents(patch) : seedTangents(boundary, w);
        patches.push_back(CoonsPatch::bicubic(std::move(boundary), std::move(t)));
      }
    }
    const Mesh mesh = tessellate(patches, {resolution});
    writeMesh(mesh, outPath);
    fmt::print("{}: {} {} Coons patch{} -> {} ({}, {})\n", modelDisplayName(model->name, modelPath),
               patches.size(), bilinear ? "bilinear" : "bicubic", patches.size() == 1 ? "" : "es",
               outPath, count(mesh.vertexCount(), "vertex"),
               count(mesh.triangleCount(), "triangle"));
    return 0;
  }
};

}  // namespace

Registered addCoonsCommand(CLI::App& app) { return registerCommand<CoonsCommand>(app); }

}  // namespace pdesurf::cli
