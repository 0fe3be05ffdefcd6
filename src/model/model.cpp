// The model layer (include/pdesurf/model.hpp): solve, tessellate, sample, NURBS, overlay
// and reports of a model of any method, each through the model's description (method.hpp)
// or its SolvedSurface; the SolvedSurface defaults (a patch grid, samples through evaluate).
// The methods themselves are in src/methods/.
#include "pdesurf/model.hpp"

#include <algorithm>
#include <iterator>
#include <numbers>
#include <span>
#include <stdexcept>

#include <fmt/format.h>

#include "pdesurf/error.hpp"
#include "pdesurf/method.hpp"

namespace pdesurf {

const char* modelTypeName(const AnyModel& model) { return model.method().typeName(); }

const std::string& modelNameOf(const AnyModel& model) { return model.method().name(model); }

SolvedModel::SolvedModel(std::shared_ptr<const AnyModel> model,
                         std::shared_ptr<const SolvedSurface> surface, std::string source,
                         SolveOptions options)
    : model_(std::move(model)),
      surface_(std::move(surface)),
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

const std::vector<std::string>& SolvedSurface::notes() const {
  static const std::vector<std::string> kNone;
  return kNone;
}

SolvedModel solve(std::shared_ptr<const AnyModel> model, const std::string& source,
                  const SolveOptions& options, std::shared_ptr<const FrameTopology> topology) {
  auto surface = model->method().solve(*model, source, options, topology);
  return SolvedModel(std::move(model), std::move(surface), source, options);
}

SolvedModel solve(AnyModel model, const std::string& source, const SolveOptions& options) {
  return solve(std::make_shared<const AnyModel>(std::move(model)), source, options);
}

void checkSolveOptions(const AnyModel& model, const SolveOptions& options) {
  model.method().checkSolveOptions(model, options);
}

void SurfaceMethod::checkSolveOptions(const AnyModel&, const SolveOptions&) const {}

void SurfaceMethod::checkTransform(const AnyModel&, const AffineMap&) const {}

ModelEdit SurfaceMethod::parseEdit(std::string_view, const AnyModel&) const {
  throw ModelError("edit", "$.op", fmt::format("{} models take no edits", typeName()));
}

EditResult SurfaceMethod::applyEdit(const EditContext&, const ModelEdit&) const {
  // Not a pdesurf::Error: the caller's slip (parseEdit refused every edit of this method).
  throw std::logic_error(
      fmt::format("SurfaceMethod::applyEdit: {} models take no edits", typeName()));
}

std::shared_ptr<const FrameTopology> SurfaceMethod::topology(const AnyModel&) const {
  return nullptr;
}

ModelHandles SurfaceMethod::handles(const SolvedModel&) const { return {}; }

ModelSettings SurfaceMethod::settings(const AnyModel&) const { return {}; }

Mesh tessellate(const SolvedModel& solved, const TessellateOptions& options) {
  return solved.surface().tessellate(options);
}

const Mesh& ModelTessellator::tessellate(const SolvedModel& solved,
                                         const TessellateOptions& options) {
  // A type branch: vertex frames re-tessellate in place (Tessellator), keeping the layout
  // while only positions move; every other method is tessellated afresh and compared.
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

Mesh SolvedSurface::tessellate(const TessellateOptions& options) const {
  checkTessellateOptions(options);
  const std::uint32_t n = options.resolution;
  Mesh mesh;
  for (std::size_t k = 0; k < patchCount(); ++k) {
    const PatchDomain d = domain(k);
    const auto base = static_cast<std::uint32_t>(mesh.vertexCount());
    for (std::uint32_t j = 0; j < n; ++j)
      for (std::uint32_t i = 0; i < n; ++i) {
        const double u = d.u0 + (d.u1 - d.u0) * static_cast<double>(i) / (n - 1);
        const double v = d.v0 + (d.v1 - d.v0) * static_cast<double>(j) / (n - 1);
        const SurfacePoint s = evaluate(k, u, v);
        const Vec3 normal = s.du.cross(s.dv).normalized();
        for (int c = 0; c < 3; ++c) {
          mesh.positions.push_back(static_cast<float>(s.p[c]));
          mesh.normals.push_back(static_cast<float>(normal[c]));
        }
      }
    for (std::uint32_t j = 0; j + 1 < n; ++j)
      for (std::uint32_t i = 0; i + 1 < n; ++i) {
        const std::uint32_t a = base + j * n + i, b = a + 1, c = a + n, e = c + 1;
        for (std::uint32_t index : {a, b, e, a, e, c}) mesh.indices.push_back(index);
        for (int t = 0; t < 2; ++t) mesh.patchIds.push_back(static_cast<std::uint32_t>(k));
      }
  }
  return mesh;
}

std::vector<PatchSamples> SolvedSurface::sample(const SampleOptions& options) const {
  const std::uint32_t n = options.grid;
  std::vector<PatchSamples> out;
  for (std::size_t k = 0; k < patchCount(); ++k) {
    const PatchDomain d = domain(k);
    PatchSamples samples{k, n, std::nullopt, std::nullopt, {}};
    for (std::uint32_t j = 0; j < n; ++j)
      for (std::uint32_t i = 0; i < n; ++i)
        samples.points.push_back(evaluate(k,
                                          d.u0 + (d.u1 - d.u0) * static_cast<double>(i) / (n - 1),
                                          d.v0 + (d.v1 - d.v0) * static_cast<double>(j) / (n - 1))
                                     .p);
    out.push_back(std::move(samples));
  }
  return out;
}

std::vector<PatchSamples> sample(const SolvedModel& solved, const SampleOptions& options) {
  return solved.surface().sample(options);
}

double largestC0Gap(const SolvedModel& solved) { return solved.surface().largestC0Gap(); }

NurbsModel toNurbs(const SolvedModel& solved, const NurbsExportOptions& options) {
  return solved.surface().toNurbs(options);
}

ModelOverlay overlay(const SolvedModel& solved) { return solved.surface().overlay(); }

bool hasEditableParts(const AnyModel& model) { return model.method().hasEditableParts(); }

}  // namespace pdesurf
