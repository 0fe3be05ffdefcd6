// Edits stay local and bounded (issue 27): on every model in examples/, each kind of handle
// the studio drags is moved by a small d and the solved surface is sampled densely before and
// after. The surface may move by no more than a small multiple of d, and less far from the
// handle than near it. Models whose method cannot promise that (the seed's marching chains,
// a high-order spectral patch through many curves) are flagged before a drag (dragAdvice), and
// a point drag that would throw the surface far away is refused with the reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "methods/shape_edits/shape_edits.hpp"
#include "pdesurf/analysis.hpp"
#include "pdesurf/edit_io.hpp"
#include "pdesurf/mesh_distance.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"
#include "support/examples.hpp"

namespace pdesurf {
namespace {

/// The drag, as a fraction of the model's bounding-box diagonal: a few pixels of a drag.
constexpr double kDragFraction = 0.003;
/// Samples of each surface for the distances (Metro sampling, mesh_distance.hpp).
constexpr std::size_t kSamples = 20000;
/// Samples per patch side of the meshes compared.
constexpr std::uint32_t kResolution = 17;
/// "Far from the handle": beyond this fraction of the diagonal (two sections away and more
/// on the chains of examples/, several frames away on the vertex-frame models). Checked on
/// models of several patches (within one patch its PDE couples every point).
constexpr double kFarFraction = 0.3;
/// A point of a curve or a vertex moved by d moves the surface by at most this many times d
/// (the issue's aim for a point on a section is 2; a section's point is interpolated, so 1 is
/// the least any method can reach, and the bump's overshoot is a few per cent).
constexpr double kPointRatio = 2.0;
/// A whole curve (a section, a condition, a boundary curve) moved by d: the surface near it
/// moves by d; between curves a spline can overshoot a little.
constexpr double kCurveRatio = 1.5;
/// Far from the handle the surface moves by at most this fraction of what it moves near it.
constexpr double kFarShare = 0.5;

/// A surface's mesh as the studio draws it.
Mesh meshOf(ModelSession& s) {
  return tessellate(s.solved(), TessellateOptions{.resolution = kResolution});
}

/// Vertex k of a mesh.
Vec3 at(const Mesh& mesh, std::size_t k) {
  return Vec3(mesh.positions[3 * k], mesh.positions[3 * k + 1], mesh.positions[3 * k + 2]);
}

/// The triangles of `mesh` whose corners all lie farther than `radius` from `centre`.
Mesh farPart(const Mesh& mesh, const Vec3& centre, double radius) {
  Mesh out = mesh;
  out.indices.clear();
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    bool far = true;
    for (std::size_t c = 0; c < 3; ++c)
      far = far && (at(mesh, mesh.indices[t + c]) - centre).norm() > radius;
    if (far)
      for (std::size_t c = 0; c < 3; ++c) out.indices.push_back(mesh.indices[t + c]);
  }
  return out;
}

/// How far a drag moved the surface, over d: everywhere (the Hausdorff distance between the
/// surfaces) and far from the handle (from the part of the old surface farther than
/// kFarFraction of the diagonal to the new surface).
struct Moved {
  double ratio = 0.0, farRatio = 0.0;
};

Moved measure(const Mesh& before, const Mesh& after, const Vec3& handle, double d,
              double diagonal) {
  const DistanceOptions options{.samples = kSamples};
  Moved out;
  out.ratio = meshDistance(after, before, options).hausdorff / d;
  const Mesh far = farPart(before, handle, kFarFraction * diagonal);
  if (!far.indices.empty()) out.farRatio = meshDistance(far, after, options).aToB.max / d;
  return out;
}

/// One drag of the studio: the edit, the handle's position and how far it moves.
struct Drag {
  std::string kind;  ///< what the handle is
  std::string json;  ///< the edit (one drag step, in a group)
  Vec3 handle;
  double limit;  ///< kPointRatio or kCurveRatio
};

/// Where the studio draws a curve's centre mark: the mean of its points, a Fourier curve's a0.
Vec3 curveCentre(const CurveInput& c) {
  if (const auto* f = std::get_if<FourierCurve>(&c)) return f->a0;
  const auto& points = std::get<SampledCurve>(c).points;
  Vec3 sum = Vec3::Zero();
  for (const Vec3& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

std::string vec(const Vec3& p) { return fmt::format("[{},{},{}]", p.x(), p.y(), p.z()); }

/// The drags of a model: one of each kind of handle the studio shows for its type.
std::vector<Drag> dragsOf(const AnyModel& model, const Vec3& step) {
  std::vector<Drag> out;
  if (const auto* m = model.as<VertexFrameModel>()) {
    const std::uint32_t v = m->frames[m->frames.size() / 2].vertices[1];
    out.push_back({"vertex",
                   fmt::format(R"({{"op":"move-vertex","vertex":{},"position":{}}})", v,
                               vec(m->vertices[v] + step)),
                   m->vertices[v], kPointRatio});
    return out;
  }
  AnyModel copy = model;
  // A closed curve given as points: its point 0 (with the studio's falloff), and the curve
  // moved whole.
  const auto closedCurve = [&](std::uint32_t index, const std::string& what) {
    const detail::CurveTarget t = detail::curveTarget(copy, CurveRef{index, ""}, "$.curve");
    if (const auto* sampled = std::get_if<SampledCurve>(t.input)) {
      const Vec3 p = sampled->points[0];
      out.push_back({what + " point",
                     fmt::format(R"({{"op":"move-curve-points","curve":{},"points":[0],)"
                                 R"("positions":[{}],"falloff":{}}})",
                                 index, vec(p + step), kStudioFalloff),
                     p, kPointRatio});
    }
    out.push_back(
        {what + " whole",
         fmt::format(R"({{"op":"transform-curve","curve":{},"translate":{}}})", index, vec(step)),
         curveCentre(*t.input), kCurveRatio});
  };
  if (const auto* m = model.as<CrossSectionModel>()) {
    closedCurve(static_cast<std::uint32_t>(m->curves.size() / 2), "section");
  } else if (const auto* m = model.as<SpectralModel>()) {
    std::vector<std::uint32_t> positions;  // the position conditions
    for (std::uint32_t i = 0; i < m->conditions.size(); ++i)
      if (m->conditions[i].derivative == 0) positions.push_back(i);
    closedCurve(positions[positions.size() / 2], "condition");
  } else {
    const auto& b = model.get<BSplinePdeModel>();
    if (b.form == BSplinePdeModel::Form::Net) {
      const std::uint32_t j = b.net.nv / 2;
      out.push_back({"control point",
                     fmt::format(R"({{"op":"move-control-points","points":[[0,{}]],)"
                                 R"("positions":[{}]}})",
                                 j, vec(b.net(0, j) + step)),
                     b.net(0, j), kPointRatio});
    } else {
      const std::string name = b.form == BSplinePdeModel::Form::ClosedBlend ? "start" : "vMin";
      const detail::CurveTarget t = detail::curveTarget(copy, CurveRef{0, name}, "$.curve");
      const std::uint32_t k = static_cast<std::uint32_t>(t.points->size() / 2);
      const Vec3 p = (*t.points)[k];
      out.push_back({"curve point",
                     fmt::format(R"({{"op":"move-curve-points","curve":"{}","points":[{}],)"
                                 R"("positions":[{}]}})",
                                 name, k, vec(p + step)),
                     p, kPointRatio});
    }
  }
  return out;
}

void apply(ModelSession& s, const std::string& json) {
  ModelEdit e = parseEdit(json, s.model());
  e.group = "drag";
  s.apply(e);
}

TEST(Locality, EveryHandleOfEveryExampleMovesTheSurfaceLocallyAndBoundedly) {
  for (const std::string& file : testing::exampleFiles()) {
    SCOPED_TRACE(file);
    ModelSession s(loadModel(file), file);
    const Mesh before = meshOf(s);
    Bounds box;
    for (std::size_t k = 0; k < before.vertexCount(); ++k) box.add(at(before, k));
    const double d = kDragFraction * box.diagonal();
    const Vec3 step = d * Vec3(1, 2, 3).normalized();
    const std::string advice = dragAdvice(s.model());
    const SolvedModel& solved = s.solved();
    const std::size_t patches = solved.frames() ? solved.frames()->patches.size()
                                : solved.spectral()
                                    ? solved.spectral()->patchCount()
                                    : solved.surface().get<SolvedBSplinePde>().pieces.size();
    for (const Drag& drag : dragsOf(s.model(), step)) {
      SCOPED_TRACE(drag.kind);
      if (!advice.empty()) {
        // Flagged before the drag: the drag may be refused as too far-reaching, never
        // taken silently far.
        try {
          apply(s, drag.json);
        } catch (const ModelError& e) {
          EXPECT_NE(std::string(e.what()).find("would move the surface"), std::string::npos)
              << e.what();
          std::printf("%s %s: refused (%s)\n", file.c_str(), drag.kind.c_str(), e.what());
          continue;
        }
        const Moved moved = measure(before, meshOf(s), drag.handle, d, box.diagonal());
        std::printf("%s %s: %.3g (far %.3g), flagged: %s\n", file.c_str(), drag.kind.c_str(),
                    moved.ratio, moved.farRatio, advice.c_str());
        EXPECT_LE(moved.ratio, kMaxReach * 2);  // checkReach bounds its box; a box is not all
        s.undo();
        continue;
      }
      apply(s, drag.json);
      const Moved moved = measure(before, meshOf(s), drag.handle, d, box.diagonal());
      ::testing::Test::RecordProperty(fmt::format("{} {}", file, drag.kind), moved.ratio);
      std::printf("%s %s: %.3g (far %.3g)\n", file.c_str(), drag.kind.c_str(), moved.ratio,
                  moved.farRatio);
      EXPECT_LE(moved.ratio, drag.limit);
      // Within one patch everything is coupled by its PDE (a spectral patch, a B-spline
      // surface, one frame); across patches the change must die down.
      if (patches > 1) EXPECT_LE(moved.farRatio, kFarShare * std::max(moved.ratio, 1.0));
      ASSERT_TRUE(s.undo());
    }
  }
}

}  // namespace
}  // namespace pdesurf
