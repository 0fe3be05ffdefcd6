// "bspline-pde" model files: the four forms, what they solve to, the tessellation of blends,
// and every refusal naming the JSON path (src/io/bspline_pde_io.cpp, docs/model-format.md).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "pdesurf/bspline_pde_io.hpp"
#include "pdesurf/spectral_io.hpp"
#include "support/mesh_checks.hpp"

namespace pdesurf {
namespace {

/// A solved surface's PDE residual is rounding (docs/bspline-pde.md §Accuracy).
constexpr double kResidualTolerance = 1e-12;

std::string point(const Vec3& p) { return fmt::format("[{}, {}, {}]", p.x(), p.y(), p.z()); }

/// A net document of last indices nu × nv: given points from f, inner points null.
template <typename F>
std::string netModel(std::uint32_t nu, std::uint32_t nv, F f, const std::string& knots) {
  ControlNet shape(nu, nv);
  std::string rows;
  for (std::uint32_t i = 0; i <= nu; ++i) {
    std::string row;
    for (std::uint32_t j = 0; j <= nv; ++j)
      row += (j ? ", " : "") + (shape.given(i, j) ? point(f(i, j)) : std::string("null"));
    rows += fmt::format("{}[{}]", i ? ", " : "", row);
  }
  return fmt::format(R"({{"type": "bspline-pde", "knots": {}, "net": [{}]}})", knots, rows);
}

std::string refusal(const std::string& text) {
  try {
    const AnyModel any = parseModel(text, "m.json");
    solve(any.get<BSplinePdeModel>(), "m.json");
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

/// A bicubic polynomial without a u³v³ term solves the PDE: given its rows, the solve must
/// reproduce it (docs/bspline-pde.md). Clamped knots, uniform parameters.
Vec3 polynomial(double u, double v) {
  return {u + 0.3 * v * v, v - 0.2 * u * u * v, 0.5 * u * u * u * v * v + 0.1 * u * v};
}

TEST(BSplinePdeIo, NetFormSolvesAndKeepsTheGivenPoints) {
  const auto f = [](std::uint32_t i, std::uint32_t j) {
    return Vec3(i, j, std::sin(1.3 * i) * std::cos(0.9 * j));
  };
  for (const char* knots :
       {R"("uniform")", R"("clamped")", R"({"u": "uniform", "v": "clamped"})"}) {
    const AnyModel any = parseModel(netModel(6, 4, f, knots), "m.json");
    const auto& m = any.get<BSplinePdeModel>();
    EXPECT_EQ(m.form, BSplinePdeModel::Form::Net);
    EXPECT_EQ(m.net.nu, 6u);
    EXPECT_EQ(m.net.nv, 4u);
    const SolvedBSplinePde s = solve(m, "m.json");
    ASSERT_EQ(s.pieces.size(), 1u);
    EXPECT_FALSE(s.c1Gap.has_value());
    EXPECT_LT(pdeResidual(s.pieces[0]), kResidualTolerance) << knots;
    for (std::uint32_t i = 0; i <= 6; ++i)
      for (std::uint32_t j = 0; j <= 4; ++j)
        if (m.net.given(i, j)) EXPECT_EQ(s.pieces[0].net()(i, j), f(i, j));
  }
  const BSplinePdeModel mixed =
      (parseModel(netModel(3, 3, f, R"({"u": "uniform", "v": "clamped"})"), "m.json"))
          .get<BSplinePdeModel>();
  EXPECT_EQ(mixed.knots.uKnots, KnotType::Uniform);
  EXPECT_EQ(mixed.knots.vKnots, KnotType::Clamped);
}

TEST(BSplinePdeIo, BoundaryFormReproducesABicubicFromCurvesAndTangents) {
  // Sampled boundary curves and tangents of a polynomial that lies in the spline space.
  std::string doc = R"({"type": "bspline-pde", "boundary": {"nu": 7, "nv": 5)";
  const auto samples = [](auto f) {
    std::string pts, ts;
    for (int k = 0; k <= 40; ++k) {
      const double t = k / 40.0;
      pts += (k ? ", " : "") + point(f(t));
      ts += fmt::format("{}{}", k ? ", " : "", t);
    }
    return fmt::format(R"({{"points": [{}], "t": [{}]}})", pts, ts);
  };
  const double h = 1e-6;
  const auto du = [&](double u, double v) {
    return Vec3((polynomial(u + h, v) - polynomial(u - h, v)) / (2 * h));
  };
  const auto dv = [&](double u, double v) {
    return Vec3((polynomial(u, v + h) - polynomial(u, v - h)) / (2 * h));
  };
  doc += R"(, "uMin": )" + samples([](double t) { return polynomial(0, t); });
  doc += R"(, "uMax": )" + samples([](double t) { return polynomial(1, t); });
  doc += R"(, "vMin": )" + samples([](double t) { return polynomial(t, 0); });
  doc += R"(, "vMax": )" + samples([](double t) { return polynomial(t, 1); });
  doc += R"(, "uMinSecond": {"tangent": )" + samples([&](double t) { return du(0, t); }) + "}";
  doc += R"(, "vMinSecond": {"tangent": )" + samples([&](double t) { return dv(t, 0); }) + "}}}";
  const AnyModel any = parseModel(doc, "m.json");
  const SolvedBSplinePde s = solve(any.get<BSplinePdeModel>(), "m.json");
  ASSERT_EQ(s.pieces.size(), 1u);
  // Tangent samples are linear between 41 points: the second rows are that close (λ/3 · h²).
  for (double u = 0; u <= 1.0; u += 0.125)
    for (double v = 0; v <= 1.0; v += 0.125)
      EXPECT_LT((s.pieces[0].position(u, v) - polynomial(u, v)).norm(), 1e-3) << u << " " << v;
  for (double t = 0; t <= 1.0; t += 0.0625)  // the fitted boundary is exact: a cubic in t
    EXPECT_LT((s.pieces[0].position(0, t) - polynomial(0, t)).norm(), 1e-12) << t;
}

TEST(BSplinePdeIo, BlendsTessellateIntoOneWatertightMesh) {
  const auto curve = [](auto f) {
    std::string pts;
    for (int k = 0; k < 7; ++k) pts += (k ? ", " : "") + point(f(k / 6.0));
    return fmt::format(R"({{"bspline": [{}]}})", pts);
  };
  const std::string four = fmt::format(
      R"({{"type": "bspline-pde", "blend": {{"n": 5, "uMin": {}, "uMax": {}, "vMin": {}, "vMax": {}}}}})",
      curve([](double t) { return Vec3(0, 2 * t, std::sin(3 * t)); }),
      curve([](double t) { return Vec3(2, 2 * t, 0); }),
      curve([](double t) { return Vec3(2 * t, 0, 0); }),
      curve([](double t) { return Vec3(2 * t, 2, std::sin(3.0) * (1 - t)); }));
  const auto ring = [](double r, double z) {
    return [=](double t) {
      const double a = 2 * std::numbers::pi * t;
      return Vec3(r * std::cos(a), r * std::sin(a), z);
    };
  };
  const std::string closed = fmt::format(
      R"({{"type": "bspline-pde", "closed-blend": {{"n": 5, "start": {}, "end": {}}}}})",
      curve(ring(1, 0)), curve(ring(0.5, 1)));
  for (const auto& [doc, pieces, closedV] :
       {std::tuple{four, 4u, false}, std::tuple{closed, 2u, true}}) {
    const SolvedBSplinePde s = solve(parseModel(doc, "m.json").get<BSplinePdeModel>(), "m.json");
    ASSERT_EQ(s.pieces.size(), pieces);
    EXPECT_EQ(s.closedV, closedV);
    ASSERT_TRUE(s.c1Gap.has_value());
    EXPECT_LT(*s.c1Gap, 1e-9);
    for (const BSplineSurface& p : s.pieces) EXPECT_LT(pdeResidual(p), kResidualTolerance);
    const std::uint32_t samples = 9;  // 3 spans per piece: 3 segments per span
    const Mesh mesh = tessellate(s, {samples});
    const std::uint32_t side = 3 * 3;
    const std::size_t expectedVertices =
        closedV ? (side + 1) * (2 * side) : (2 * side + 1) * (2 * side + 1);
    EXPECT_EQ(mesh.vertexCount(), expectedVertices);
    const auto stats = testing::edgeStats(mesh);
    EXPECT_EQ(stats.inconsistentlyOrientedEdges, 0u);
    EXPECT_EQ(stats.nonManifoldEdges, 0u);
    // Open only along the region's border (the two end rings for the tube).
    EXPECT_EQ(stats.boundaryEdges, closedV ? 2u * 2 * side : 4u * 2 * side);
    std::set<std::uint32_t> ids(mesh.patchIds.begin(), mesh.patchIds.end());
    EXPECT_EQ(ids.size(), pieces);
  }
}

// serializeModel writes a file that parses back to the same model, for every form (the
// examples cover all four), and the same text again.
TEST(BSplinePdeIo, SerializedModelsReadBackTheSame) {
  for (const auto& entry : std::filesystem::directory_iterator(
           std::filesystem::path(PDESURF_SOURCE_DIR) / "examples")) {
    const std::string path = entry.path().string();
    if (path.find("bspline-") == std::string::npos) continue;
    const BSplinePdeModel model = loadModel(path).get<BSplinePdeModel>();
    const std::string text = serializeModel(model);
    const AnyModel again = parseModel(text, "again.json");
    const auto& back = again.get<BSplinePdeModel>();
    EXPECT_EQ(serializeModel(back), text) << path;
    EXPECT_EQ(back.form, model.form) << path;
    const SolvedBSplinePde a = solve(model, path), b = solve(back, path);
    ASSERT_EQ(a.pieces.size(), b.pieces.size());
    for (std::size_t k = 0; k < a.pieces.size(); ++k)
      for (double u : {0.0, 0.3, 1.0})
        for (double v : {0.0, 0.6, 1.0})
          EXPECT_EQ(a.pieces[k].position(u, v), b.pieces[k].position(u, v)) << path;
  }
}

TEST(BSplinePdeIo, RefusesWithTheJsonPath) {
  const auto f = [](std::uint32_t i, std::uint32_t j) { return Vec3(i, j, 0); };
  const std::string good = netModel(4, 4, f, R"("clamped")");
  std::string nullGiven = good;
  nullGiven.replace(nullGiven.find("[0, 2, 0]"), 9, "null");
  std::string shortRow = good;
  shortRow.replace(shortRow.find(", [0, 4, 0]"), 11, "");
  const std::string bline = R"({"bspline": [[0,0,0],[1,0,0],[2,0,0],[3,0,0]]})";
  const std::pair<std::string, std::string> cases[] = {
      {R"({"type": "bspline-pde"})", "$: a bspline-pde model needs one of \"net\""},
      {R"({"type": "bspline-pde", "net": [], "blend": {}})", "has only one of"},
      {R"({"type": "bspline-pde", "net": [[[0,0,0]]]})", "$.net: expected at least 4 entries"},
      {nullGiven, "$.net[0][2]: P[0][2] is in row 0, 1, 4"},
      {shortRow, "$.net[1]: row 1 has 5 points, row 0 has 4: a net is rectangular"},
      {netModel(3, 3, f, R"("bent")"), "$.knots: unknown value \"bent\""},
      {R"({"type": "bspline-pde", "knots": "uniform", "blend": {}})",
       "$.knots: blends are made of clamped pieces"},
      {R"({"type": "bspline-pde", "blend": {"n": 2}})", "$.blend.n: 2 is out of range"},
      {R"({"type": "bspline-pde", "blend": {"n": 4, "uMin": {"points": [[0,0,0]]}}})",
       "$.blend.uMin: blend curves are B-spline curves"},
      {R"({"type": "bspline-pde", "closed-blend": {"n": 4, "start": )" + bline + R"(, "end": )" +
           bline + "}}",
       "$[\"closed-blend\"]: blendClosedCurves: curve start is not closed"},
      {R"({"type": "bspline-pde", "boundary": {"nu": 2}})", "$.boundary.nu: 2 is out of range"},
      {R"({"type": "bspline-pde", "boundary": {"nu": 4, "nv": 4, "uMin": {"bspline": [[0,0,0]]}}})",
       "$.boundary.uMin.bspline: expected at least 4 entries"},
      {R"({"type": "bspline-pde", "boundary": {"nu": 4, "nv": 4, "uMin": {"points": [[0,0,0],[1,0,0]], "t": [0, 0.5]}}})",
       "$.boundary.uMin.t: t ends at 1, found 0.5"},
      {R"({"type": "bspline-pde", "net": [], "colour": 1})", "$: unknown field \"colour\""},
  };
  for (const auto& [text, expected] : cases) {
    const std::string message = refusal(text);
    EXPECT_NE(message.find("m.json: "), std::string::npos) << text << "\n -> " << message;
    EXPECT_NE(message.find(expected), std::string::npos) << text << "\n -> " << message;
  }
  // The boundary's corners must meet: the engine's refusal names the form.
  const std::string corners = R"({"type": "bspline-pde", "boundary": {"nu": 4, "nv": 4,
    "uMin": {"bspline": [[0,0,0],[0,1,0],[0,2,0],[0,3,0],[0,4,0]]},
    "uMax": {"bspline": [[4,0,0],[4,1,0],[4,2,0],[4,3,0],[4,4,0]]},
    "vMin": {"bspline": [[0,0,1],[1,0,0],[2,0,0],[3,0,0],[4,0,0]]},
    "vMax": {"bspline": [[0,4,0],[1,4,0],[2,4,0],[3,4,0],[4,4,0]]},
    "uMinSecond": {"points": [[1,0,0],[1,1,0],[1,2,0],[1,3,0],[1,4,0]]},
    "vMinSecond": {"points": [[0,1,0],[1,1,0],[2,1,0],[3,1,0],[4,1,0]]}}})";
  const std::string message = refusal(corners);
  EXPECT_NE(message.find("m.json: $.boundary: "), std::string::npos) << message;
  EXPECT_NE(message.find("uMin"), std::string::npos) << message;
}

}  // namespace
}  // namespace pdesurf
