// The model layer (include/pdesurf/model.hpp): solve, tessellate, sample, NURBS, overlay
// curves and transform checks of a model of any type. Every branch on the model's type in
// pdesurf is here or in src/model/report_*.cpp.
#include "pdesurf/model.hpp"

#include <algorithm>
#include <iterator>
#include <numbers>
#include <span>
#include <stdexcept>

#include <fmt/format.h>

#include "pdesurf/analysis.hpp"

namespace pdesurf {

namespace {

/// Calls f with the solved alternative; a short way to write "for each type".
template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};

}  // namespace

const char* modelTypeName(const AnyModel& model) {
  constexpr const char* kNames[] = {"vertex-frames", "spectral", "cross-sections", "bspline-pde"};
  static_assert(std::size(kNames) == std::variant_size_v<AnyModel>);
  return kNames[model.index()];
}

const std::string& modelNameOf(const AnyModel& model) {
  return std::visit([](const auto& m) -> const std::string& { return m.name; }, model);
}

std::optional<SolvedSpectral> solveIfSpectral(const AnyModel& model, const std::string& source) {
  if (const auto* m = std::get_if<SpectralModel>(&model)) return solveSpectralModel(*m, source);
  if (const auto* m = std::get_if<CrossSectionModel>(&model)) return solveSpectralModel(*m, source);
  return std::nullopt;
}

SolvedModel::SolvedModel(std::shared_ptr<const AnyModel> model, SolvedAlternative solved,
                         std::string source, SolveOptions options)
    : model_(std::move(model)),
      solved_(std::move(solved)),
      source_(std::move(source)),
      options_(options) {}

std::string modelDisplayName(const std::string& name, const std::string& path) {
  if (!name.empty()) return name;
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string SolvedModel::displayName() const {
  return modelDisplayName(modelNameOf(*model_), source_);
}

const std::vector<std::string>& SolvedModel::notes() const {
  static const std::vector<std::string> kNone;
  const auto* surface = frames();
  return surface ? surface->notes : kNone;
}

SolvedModel solveModel(std::shared_ptr<const AnyModel> model, const std::string& source,
                       const SolveOptions& options, std::shared_ptr<const FrameTopology> topology) {
  SolvedAlternative solved =
      std::visit(Overloaded{[&](const VertexFrameModel& m) -> SolvedAlternative {
                              return topology ? solve(m, topology, options) : solve(m, options);
                            },
                            [&](const SpectralModel& m) -> SolvedAlternative {
                              return solveSpectralModel(m, source);
                            },
                            [&](const CrossSectionModel& m) -> SolvedAlternative {
                              return solveSpectralModel(m, source);
                            },
                            [&](const BSplinePdeModel& m) -> SolvedAlternative {
                              return solveBSplineModel(m, source);
                            }},
                 *model);
  return SolvedModel(std::move(model), std::move(solved), source, options);
}

SolvedModel solveModel(AnyModel model, const std::string& source, const SolveOptions& options) {
  return solveModel(std::make_shared<const AnyModel>(std::move(model)), source, options);
}

void checkSolveOptions(const AnyModel& model, const SolveOptions& options) {
  const auto* frames = std::get_if<VertexFrameModel>(&model);
  if (!frames || options.seedFrame < frames->frames.size()) return;
  const std::size_t n = frames->frames.size();
  throw std::out_of_range(fmt::format("out of range, the model has {} frame{} (indices 0 to {})", n,
                                      n == 1 ? "" : "s", n - 1));
}

Mesh tessellate(const SolvedModel& solved, const TessellateOptions& options) {
  // The spectral and B-spline engines take the samples per patch side.
  return std::visit(
      Overloaded{[&](const VertexFrameSurface& s) { return tessellate(s, options); },
                 [&](const SolvedSpectral& s) { return tessellate(s, options.resolution); },
                 [&](const SolvedBSplinePde& s) { return tessellate(s, options.resolution); }},
      solved.solved());
}

const Mesh& ModelTessellator::tessellate(const SolvedModel& solved,
                                         const TessellateOptions& options) {
  if (const VertexFrameSurface* surface = solved.frames()) {
    const Mesh& mesh = frames_.tessellate(*surface, options);
    if (!lastWasFrames_ || frames_.layoutVersion() != framesLayout_) ++layoutVersion_;
    framesLayout_ = frames_.layoutVersion();
    lastWasFrames_ = true;
    return mesh;
  }
  Mesh mesh = pdesurf::tessellate(solved, options);
  const bool sameLayout = !lastWasFrames_ && mesh.positions.size() == mesh_.positions.size() &&
                          mesh.normals.size() == mesh_.normals.size() &&
                          mesh.indices == mesh_.indices;
  if (!sameLayout) ++layoutVersion_;
  lastWasFrames_ = false;
  mesh_ = std::move(mesh);
  return mesh_;
}

namespace {

/// points[j*grid+i] = f(i, j).
template <class F>
std::vector<Vec3> grid(std::uint32_t n, F&& f) {
  std::vector<Vec3> points;
  points.reserve(std::size_t{n} * n);
  for (std::uint32_t j = 0; j < n; ++j)
    for (std::uint32_t i = 0; i < n; ++i) points.push_back(f(i, j));
  return points;
}

/// i/(n−1): the unit-square samples of vertex frames and B-spline pieces.
double unit(std::uint32_t i, std::uint32_t n) { return static_cast<double>(i) / (n - 1); }

}  // namespace

std::vector<PatchSamples> sample(const SolvedModel& solved, std::uint32_t n) {
  std::vector<PatchSamples> out;
  std::visit(Overloaded{[&](const VertexFrameSurface& s) {
                          for (std::size_t k = 0; k < s.patches.size(); ++k)
                            out.push_back({"frame", k, n, std::nullopt, std::nullopt,
                                           grid(n, [&](std::uint32_t i, std::uint32_t j) {
                                             return s.patches[k].position(unit(i, n), unit(j, n));
                                           })});
                        },
                        [&](const SolvedSpectral& s) {
                          for (std::size_t k = 0; k < s.patchCount(); ++k) {
                            const auto [u0, u1] = s.range(k);
                            out.push_back({"patch", k, n, std::pair{u0, u1}, std::nullopt,
                                           grid(n, [&](std::uint32_t i, std::uint32_t j) {
                                             // As the CLI always sampled (same rounding).
                                             return s.patchAt(k).position(
                                                 u0 + (u1 - u0) * static_cast<double>(i) / (n - 1),
                                                 2.0 * std::numbers::pi * static_cast<double>(j) /
                                                     (n - 1));
                                           })});
                          }
                        },
                        [&](const SolvedBSplinePde& s) {
                          for (std::size_t k = 0; k < s.pieces.size(); ++k)
                            out.push_back({"patch", k, n, std::nullopt, s.origin[k],
                                           grid(n, [&](std::uint32_t i, std::uint32_t j) {
                                             return s.pieces[k].position(unit(i, n), unit(j, n));
                                           })});
                        }},
             solved.solved());
  return out;
}

double largestC0Gap(const SolvedModel& solved) {
  return std::visit(Overloaded{[](const VertexFrameSurface& s) { return measureC0Gap(s).maxGap; },
                               [](const SolvedSpectral& s) {
                                 double gap = 0.0;
                                 if (s.chain)
                                   for (const JointGap& g : measureJointGaps(*s.chain))
                                     gap = std::max(gap, g.c0);
                                 return gap;
                               },
                               [](const SolvedBSplinePde&) { return 0.0; }},
                    solved.solved());
}

NurbsModel toNurbs(const SolvedModel& solved, const NurbsExportOptions& options) {
  return std::visit(Overloaded{[&](const VertexFrameSurface& s) { return toNurbs(s, options); },
                               [&](const SolvedSpectral& s) { return toNurbs(s, options); },
                               [&](const SolvedBSplinePde& s) {
                                 return toNurbs(std::span<const BSplineSurface>(s.pieces), options);
                               }},
                    solved.solved());
}

ModelOverlay overlay(const SolvedModel& solved) {
  constexpr std::uint32_t kViewCurveSamples = 96, kViewSpineSamples = 65;
  // A condition at u within this of a patch's range belongs to it (its ends are computed).
  constexpr double kRangeSlack = 1e-12;
  ModelOverlay out;
  std::visit(
      Overloaded{[](const VertexFrameSurface&) {},
                 [&](const SolvedBSplinePde& b) {
                   // The control polygon of each piece: its rows and its columns.
                   for (const BSplineSurface& piece : b.pieces) {
                     const ControlNet& net = piece.net();
                     for (int direction = 0; direction < 2; ++direction) {
                       const std::uint32_t lines = direction == 0 ? net.nu : net.nv;
                       const std::uint32_t along = direction == 0 ? net.nv : net.nu;
                       for (std::uint32_t a = 0; a <= lines; ++a) {
                         std::vector<Vec3> line;
                         for (std::uint32_t k = 0; k <= along; ++k)
                           line.push_back(direction == 0 ? net(a, k) : net(k, a));
                         out.curves.push_back(std::move(line));
                       }
                     }
                   }
                 },
                 [&](const SolvedSpectral& s) {
                   // Each patch's position curves (closed, sampled at kViewCurveSamples v) and
                   // spine.
                   for (std::size_t k = 0; k < s.patchCount(); ++k) {
                     const SpectralPatch& p = s.patchAt(k);
                     const auto [u0, u1] = s.range(k);
                     for (const auto& c : p.conditions()) {
                       if (c.derivative != 0 || c.u < std::min(u0, u1) - kRangeSlack ||
                           c.u > std::max(u0, u1) + kRangeSlack)
                         continue;
                       std::vector<Vec3> line;
                       for (std::uint32_t j = 0; j < kViewCurveSamples; ++j)
                         line.push_back(
                             p.position(c.u, 2.0 * std::numbers::pi * j / kViewCurveSamples));
                       out.curves.push_back(std::move(line));
                     }
                     std::vector<Vec3> spine;
                     for (std::uint32_t i = 0; i < kViewSpineSamples; ++i)
                       spine.push_back(p.spine(u0 + (u1 - u0) * i / (kViewSpineSamples - 1.0)));
                     out.spines.push_back(std::move(spine));
                   }
                 }},
      solved.solved());
  return out;
}

bool hasEditableParts(const AnyModel& model) {
  return std::holds_alternative<VertexFrameModel>(model);
}

}  // namespace pdesurf
