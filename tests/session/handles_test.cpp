// The handles each method exposes (SurfaceMethod::handles, method.hpp), which the studio's page
// draws and drags: checked against the model files themselves (their JSON read here, apart
// from the parsers): every curve point and given control point of the file is a handle at
// exactly its position, a curve's centre is its points' mean, a tangent's tip is its base plus
// kTangentDraw times the file's vector, and the spine points are spineHandles'.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"
#include "support/examples.hpp"

namespace pdesurf {
namespace {

using Json = nlohmann::json;

/// A bspline tangent's base lies on its side's polyline: within this of it, relative to the
/// model's size (rounding of the interpolation between two points).
constexpr double kOnPolyline = 1e-12;

Vec3 vec(const Json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }

/// The model files of the shape-edited methods: examples/ and docs/model-format/.
std::vector<std::string> shapeModelFiles() {
  std::vector<std::string> out;
  const std::filesystem::path root(PDESURF_SOURCE_DIR);
  for (const auto& dir : {root / "examples", root / "docs" / "model-format"})
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (entry.path().extension() != ".json") continue;
      std::ifstream in(entry.path());
      const Json file = Json::parse(in, nullptr, false);
      const std::string type = file.is_object() ? file.value("type", Json("")).dump() : "";
      if (type != "\"spectral\"" && type != "\"cross-sections\"" && type != "\"bspline-pde\"")
        continue;
      try {
        // The format's refusals (files that do not parse or solve) are no models.
        solve(loadModel(entry.path().string()), entry.path().string());
      } catch (const ModelError&) {
        continue;
      }
      out.push_back(entry.path().string());
    }
  std::sort(out.begin(), out.end());
  return out;
}

/// A curve's points in a file ("points" or "bspline"), or null (Fourier coefficients).
const Json* points(const Json& curve) {
  if (curve.contains("points")) return &curve["points"];
  if (curve.contains("bspline")) return &curve["bspline"];
  return nullptr;
}

/// The file's point list of curve `ref` that holds positions, or null (this reads the file
/// format: docs/model-format.md).
const Json* filePoints(const Json& file, const Json& ref) {
  const std::string type = file["type"];
  if (type == "spectral") {
    const Json& c = file["conditions"][ref.get<std::size_t>()];
    return c.value("derivative", 0) == 0 ? points(c["curve"]) : nullptr;
  }
  if (type == "cross-sections") return points(file["curves"][ref.get<std::size_t>()]);
  for (const char* part : {"boundary", "blend", "closed-blend"})
    if (file.contains(part) && file[part].contains(ref.get<std::string>()))
      return points(file[part][ref.get<std::string>()]);  // a tangent row: "tangent", null
  return nullptr;
}

TEST(Handles, AreTheModelFilesPoints) {
  const std::vector<std::string> files = shapeModelFiles();
  ASSERT_GE(files.size(), 12u);  // the shape examples above and the format's own
  std::size_t tangents = 0, spines = 0, controls = 0;
  for (const std::string& path : files) {
    SCOPED_TRACE(path);
    std::ifstream in(path);
    const Json file = Json::parse(in);
    const SolvedModel solved = solve(loadModel(path), path);
    const ModelHandles handles = solved.model().method().handles(solved);
    const auto refJson = [](const CurveRef& r) {
      return r.name.empty() ? Json(r.index) : Json(r.name);
    };
    // Every curve of the file that holds positions: each point a handle, exactly.
    std::map<std::string, std::set<std::uint32_t>> seen;  // curve → its point handles
    for (const ModelHandle& h : handles.points) {
      if (h.kind == ModelHandle::Kind::CurvePoint) {
        const Json* given = filePoints(file, refJson(h.curve));
        ASSERT_NE(given, nullptr) << refJson(h.curve);
        EXPECT_EQ(h.position, vec((*given)[h.index])) << refJson(h.curve) << " " << h.index;
        EXPECT_TRUE(seen[refJson(h.curve).dump()].insert(h.index).second);
      } else if (h.kind == ModelHandle::Kind::ControlPoint) {
        ++controls;
        EXPECT_EQ(h.position, vec(file["net"][h.index][h.column]));
      } else if (h.kind == ModelHandle::Kind::Tangent) {
        ++tangents;
        // The tip: its base plus kTangentDraw times the file's vector (a0 for the mean).
        const Json& curve = file["type"] == "spectral" ? file["conditions"][h.curve.index]["curve"]
                                                       : file["boundary"][h.curve.name]["tangent"];
        const Vec3 vector = h.mean ? vec(curve["fourier"]["a0"]) : vec((*points(curve))[h.index]);
        EXPECT_EQ(h.position, h.base + kTangentDraw * vector);
      } else {
        ++spines;
      }
    }
    // No point of a position curve is left out, and each curve's centre is its points' mean.
    for (const HandleCurve& c : handles.curves) {
      const Json* given = c.vectors ? nullptr : filePoints(file, refJson(c.ref));
      if (!given) continue;
      EXPECT_EQ(seen[refJson(c.ref).dump()].size(), given->size()) << refJson(c.ref);
      Vec3 sum = Vec3::Zero();
      for (const Json& p : *given) sum += vec(p);
      EXPECT_EQ(c.centre, sum / static_cast<double>(given->size())) << refJson(c.ref);
    }
    if (file["type"] == "bspline-pde" && file.contains("net")) {
      std::size_t given = 0;
      for (const Json& row : file["net"])
        for (const Json& p : row) given += !p.is_null();
      EXPECT_EQ(controls, given);
    }
    controls = 0;
  }
  EXPECT_GT(tangents, 0u);  // membrane, tube, bspline-dome have tangents
  EXPECT_GT(spines, 0u);
}

TEST(Handles, SpectralTangentsStartOnTheirPositionCurve) {
  // A ∂u condition given as points beside the position curve at the same u, or a Fourier one
  // drawn from that curve's centre.
  std::size_t count = 0;
  for (const std::string& path : shapeModelFiles()) {
    SCOPED_TRACE(path);
    std::ifstream in(path);
    const Json file = Json::parse(in);
    if (file["type"] != "spectral") continue;
    const SolvedModel solved = solve(loadModel(path), path);
    for (const ModelHandle& h : solved.model().method().handles(solved).points) {
      if (h.kind != ModelHandle::Kind::Tangent) continue;
      ++count;
      const Json& c = file["conditions"][h.curve.index];
      // The position condition at the same u.
      const Json* position = nullptr;
      for (const Json& p : file["conditions"])
        if (p.value("derivative", 0) == 0 && p.value("u", Json()) == c.value("u", Json())) {
          position = &p;
          break;
        }
      ASSERT_NE(position, nullptr);
      const Json& curve = (*position)["curve"];
      if (!h.mean) {
        EXPECT_EQ(h.base, vec(curve["points"][h.index]));
      } else if (curve.contains("fourier")) {
        EXPECT_EQ(h.base, vec(curve["fourier"]["a0"]));
      }
    }
  }
  EXPECT_GT(count, 0u);
}

TEST(Handles, BSplineTangentRowsStartOnTheirSide) {
  const std::string path = testing::example("bspline-dome.json");
  std::ifstream in(path);
  const Json file = Json::parse(in);
  const SolvedModel solved = solve(loadModel(path), path);
  std::size_t count = 0;
  for (const ModelHandle& h : solved.model().method().handles(solved).points) {
    if (h.kind != ModelHandle::Kind::Tangent) continue;
    ++count;
    const Json& side = file["boundary"][h.curve.name == "uMinSecond" ? "uMin" : "vMin"];
    const Json& sidePoints = *points(side);
    // The distance from the base to the side's polyline.
    double nearest = std::numeric_limits<double>::infinity(), size = 0.0;
    for (std::size_t k = 1; k < sidePoints.size(); ++k) {
      const Vec3 a = vec(sidePoints[k - 1]), b = vec(sidePoints[k]);
      const double t = std::clamp((h.base - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      nearest = std::min(nearest, (a + t * (b - a) - h.base).norm());
      size = std::max(size, a.norm());
    }
    EXPECT_LE(nearest, kOnPolyline * size) << h.curve.name << " " << h.index;
  }
  EXPECT_GT(count, 0u);
}

TEST(Handles, SpinePointsAreSpineHandles) {
  const std::string path = testing::example("shell.json");
  const SolvedModel solved = solve(loadModel(path), path);
  const SpineHandles spine = spineHandles(solved, 9);
  std::vector<Vec3> points;
  std::vector<double> u;
  for (const ModelHandle& h : solved.model().method().handles(solved).points)
    if (h.kind == ModelHandle::Kind::SpinePoint) {
      EXPECT_EQ(h.index, points.size());
      points.push_back(h.position);
      u.push_back(h.u);
    }
  EXPECT_EQ(points, spine.points);
  EXPECT_EQ(u, spine.u);
  EXPECT_EQ(points.size(), 9u);
}

TEST(Handles, VertexFramesHaveNoneOfTheirOwn) {
  // Their handles are their vertices, which the studio's frame tools edit.
  const std::string path = testing::example("mug.json");
  const SolvedModel solved = solve(loadModel(path), path);
  const ModelHandles handles = solved.model().method().handles(solved);
  EXPECT_TRUE(handles.points.empty());
  EXPECT_TRUE(handles.curves.empty());
}

}  // namespace
}  // namespace pdesurf
