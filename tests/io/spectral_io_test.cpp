// Spectral and cross-section model files: what parses, the defaults, and every refusal
// naming the JSON path (src/io/spectral_io.cpp, docs/model-format.md).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "pdesurf/spectral_io.hpp"

namespace pdesurf {
namespace {

/// A Fourier circle of radius r at height z: {"fourier": ...}.
std::string circle(double r, double z) {
  return fmt::format(R"({{"fourier": {{"a0": [0, 0, {}], "a": [[{}, 0, 0]], "b": [[0, {}, 0]]}}}})",
                     z, r, r);
}

/// A circle as `count` points (uniform in v) of radius r at height z.
std::string pointCircle(double r, double z, int count) {
  std::string pts;
  for (int j = 0; j < count; ++j) {
    const double v = 2 * std::numbers::pi * j / count;
    pts += fmt::format("{}[{}, {}, {}]", j ? ", " : "", r * std::cos(v), r * std::sin(v), z);
  }
  return fmt::format(R"({{"points": [{}]}})", pts);
}

std::string ugail4(const std::string& extra = "") {
  return fmt::format(R"({{"type": "spectral", "operator": "ugail", "N": 2{},
    "conditions": [
      {{"u": 0, "curve": {}}},
      {{"u": 0, "derivative": 1, "curve": {}}},
      {{"u": 1, "curve": {}}},
      {{"u": 1, "derivative": 1, "curve": {}}}]}})",
                     extra, circle(1, 0), circle(0, 1), circle(0.5, 1), circle(0, 1));
}

/// The message of the ModelError that parsing `text` throws ("" when it parses).
std::string refusal(const std::string& text) {
  try {
    parseModel(text, "m.json");
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

TEST(SpectralIo, ParsesAUgailModelWithItsDefaults) {
  const AnyModel any = parseModel(ugail4(), "m.json");
  const auto& m = any.get<SpectralModel>();
  EXPECT_EQ(m.op.kind, OperatorKind::Ugail);
  EXPECT_EQ(m.op.power, 2u);
  EXPECT_EQ(m.op.a, 2.0);  // Ugail's a defaults to N (seed 003 §3.0.2)
  EXPECT_EQ(m.options.modes, SpectralOptions{}.modes);
  EXPECT_EQ(m.options.placement, UPlacement::Given);  // every condition has its u
  EXPECT_TRUE(m.options.remainder);
  ASSERT_EQ(m.conditions.size(), 4u);
  EXPECT_EQ(m.conditions[1].derivative, 1u);
  EXPECT_EQ(*m.conditions[2].u, 1.0);
  const auto& c = std::get<FourierCurve>(m.conditions[2].curve);
  EXPECT_EQ(c.a0, Vec3(0, 0, 1));
  EXPECT_EQ(c.a[0], Vec3(0.5, 0, 0));
  EXPECT_EQ(c.b[0], Vec3(0, 0.5, 0));

  // The model solves: positions at u = 0 and 1 are the circles.
  const SpectralPatch p = *solve(m, "m.json").patch;
  for (double v : {0.0, 1.0, 2.5}) {
    EXPECT_LT((p.position(0, v) - Vec3(std::cos(v), std::sin(v), 0)).norm(), 1e-12);
    EXPECT_LT((p.position(1, v) - Vec3(0.5 * std::cos(v), 0.5 * std::sin(v), 1)).norm(), 1e-12);
  }
}

TEST(SpectralIo, ParsesFuCrossSectionsAndPointCurves) {
  const std::string text = fmt::format(
      R"({{"type": "cross-sections", "name": "c", "a": -0.5, "modes": 3, "method": "shared-curves",
          "parameterization": "uniform", "remainder": false,
          "curves": [{}, {}, {}, {}, {}, {}]}})",
      pointCircle(1, 0, 12), pointCircle(1.2, 1, 12), pointCircle(0.9, 2, 12),
      pointCircle(1.1, 3, 12), pointCircle(1, 4, 12), pointCircle(0.8, 5, 12));
  const auto m = parseModel(text, "c.json").get<CrossSectionModel>();
  EXPECT_EQ(m.name, "c");
  EXPECT_EQ(m.options.a, -0.5);
  EXPECT_EQ(m.options.modes, 3u);
  EXPECT_EQ(m.options.method, ChainMethod::SharedCurves);
  EXPECT_EQ(m.options.parameterization, VParameterization::Uniform);
  EXPECT_FALSE(m.options.remainder);
  ASSERT_EQ(m.curves.size(), 6u);
  EXPECT_EQ(std::get<SampledCurve>(m.curves[0]).points.size(), 12u);
  EXPECT_FALSE(solve(m, "c.json").chain->patches.empty());
}

TEST(SpectralIo, RefusesWithTheJsonPath) {
  const std::string c = circle(1, 0);
  const std::pair<std::string, std::string> cases[] = {
      {R"({"type": "spectral-ish"})", "$.type: unknown model type \"spectral-ish\""},
      {R"({"type": "spectral", "operator": "heat"})", "$.operator: unknown value \"heat\""},
      {R"({"type": "spectral", "operator": "ugail"})", "missing required field \"N\""},
      {R"({"type": "spectral", "operator": "ugail", "N": 0})", "$.N: 0 is out of range"},
      {R"({"type": "spectral", "operator": "ugail", "N": 1.5})", "$.N: expected an integer"},
      {R"({"type": "spectral", "operator": "ugail", "N": 1, "a": -1})",
       "$.a: Ugail's a must be positive"},
      {R"({"type": "spectral", "operator": "fu", "a": 0})", "$.a: a = 0"},
      {R"({"type": "spectral", "operator": "fu", "N": 3, "a": 1})", "$.N: \"N\" belongs to"},
      {R"({"type": "spectral", "operator": "ugail", "N": 1, "conditions": [{"curve": )" + c + "}]}",
       "$.conditions: an order-2 operator takes exactly 2 conditions, found 1"},
      {R"({"type": "spectral", "operator": "ugail", "N": 1, "modes": 65})",
       "$.modes: 65 is out of range"},
      {R"({"type": "spectral", "operator": "ugail", "N": 1, "colour": 1})",
       "$: unknown field \"colour\""},
      {ugail4(R"(, "placement": "sideways")"), "$.placement: unknown value \"sideways\""},
  };
  for (const auto& [text, expected] : cases) {
    const std::string message = refusal(text);
    EXPECT_NE(message.find("m.json: "), std::string::npos) << text;
    EXPECT_NE(message.find(expected), std::string::npos) << text << "\n -> " << message;
  }
}

TEST(SpectralIo, RefusesBadConditionsAndCurves) {
  auto model = [](const std::string& c0, const std::string& c1) {
    return fmt::format(
        R"({{"type": "spectral", "operator": "ugail", "N": 1, "modes": 2, "conditions": [{}, {}]}})",
        c0, c1);
  };
  const std::string good = fmt::format(R"({{"u": 1, "curve": {}}})", circle(1, 1));
  const std::pair<std::string, std::string> cases[] = {
      {model(fmt::format(R"({{"u": 0, "derivative": 2, "curve": {}}})", circle(1, 0)), good),
       "$.conditions[0].derivative: 2 is out of range"},
      {model(fmt::format(R"({{"u": 1, "curve": {}}})", circle(1, 0)), good),
       "$.conditions[1]: a second condition on the position at u = 1"},
      {model(fmt::format(R"({{"derivative": 1, "curve": {}}})", circle(1, 0)), good),
       "$.conditions[0]: a derivative condition without \"u\""},
      {model(R"({"u": 0, "curve": {"points": [[0,0,0],[1,0,0],[0,1,0]], "fourier": {}}})", good),
       "$.conditions[0].curve: a curve has either"},
      {model(R"({"u": 0, "curve": {"points": [[0,0,0],[1,0,0]]}})", good),
       "$.conditions[0].curve.points: expected at least 3 entries"},
      {model(R"({"u": 0, "curve": {"points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]]}})", good),
       "$.conditions[0].curve.points: 4 points cannot determine 2 Fourier modes"},
      {model(R"({"u": 0, "curve": {"points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0],[2,0,0]],
                                   "v": [0, 1, 1, 2, 3]}})",
             good),
       "$.conditions[0].curve.v[2]: v values must increase"},
      {model(R"({"u": 0, "curve": {"points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0],[2,0,0]],
                                   "v": [0, 1, 2, 3, 7]}})",
             good),
       "$.conditions[0].curve.v[4]: v = 7 lies outside [0, 2π)"},
      {model(R"({"u": 0, "curve": {"points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0],[2,0,0]],
                                   "v": [0, 1]}})",
             good),
       "$.conditions[0].curve.v: expected one v per point (5), found 2"},
      {model(R"({"u": 0, "curve": {"fourier": {"a0": [0, 0]}}})", good),
       "$.conditions[0].curve.fourier.a0: expected 3 numbers"},
  };
  for (const auto& [text, expected] : cases) {
    const std::string message = refusal(text);
    EXPECT_NE(message.find(expected), std::string::npos) << text << "\n -> " << message;
  }
  // Without a u, a position curve is placed (uniformly by default) unless "given" is asked.
  EXPECT_EQ(refusal(model(fmt::format(R"({{"curve": {}}})", circle(1, 0)), good)), "");
  EXPECT_NE(refusal(model(fmt::format(R"({{"curve": {}}})", circle(1, 0)), good)
                        .replace(1, 0, R"("placement": "given", )"))
                .find("$.conditions[0]: \"placement\": \"given\" needs a \"u\""),
            std::string::npos);
}

TEST(SpectralIo, RefusesBadSpineEditsAndShortChains) {
  EXPECT_NE(refusal(ugail4(R"(, "spine": [{"u": [0.2, 0.5], "moved": [[0, 0, 0]]}])"))
                .find("$.spine[0]: \"u\" has 2 values and \"moved\" 1 points"),
            std::string::npos);
  EXPECT_NE(refusal(ugail4(R"(, "spine": [{"u": [0.5, 0.2], "moved": [[0,0,0], [0,0,1]]}])"))
                .find("$.spine[0].u[1]: u values must increase"),
            std::string::npos);
  const std::string three =
      fmt::format(R"({{"type": "cross-sections", "method": "c2", "curves": [{}, {}, {}]}})",
                  circle(1, 0), circle(1, 1), circle(1, 2));
  EXPECT_NE(refusal(three).find("$.curves: the \"c2\" method needs at least 4 curves, found 3"),
            std::string::npos);
  const std::string five = fmt::format(
      R"({{"type": "cross-sections", "method": "shared-curves", "curves": [{}, {}, {}, {}, {}]}})",
      circle(1, 0), circle(1, 1), circle(1, 2), circle(1, 3), circle(1, 4));
  EXPECT_NE(refusal(five).find("needs at least 6 curves, found 5"), std::string::npos);
  EXPECT_NE(refusal(R"({"type": "cross-sections", "a": 0, "curves": []})").find("$.a: a = 0"),
            std::string::npos);
}

TEST(SpectralIo, GlobalChainOptionsRoundTripAndAreChecked) {
  const std::string curves =
      fmt::format("[{}, {}, {}, {}]", circle(1, 0), circle(1.2, 1), circle(0.9, 3), circle(1, 4));
  const std::string text = fmt::format(
      R"({{"type": "cross-sections", "spacing": "mean-distance", "ends": "estimated",
           "u": [0, 1, 3, 4.5], "curves": {}}})",
      curves);
  const auto parsed = parseModel(text, "m.json").get<CrossSectionModel>();
  EXPECT_EQ(parsed.options.method, ChainMethod::Global);  // the default
  EXPECT_EQ(parsed.options.spacing, ChainSpacing::MeanDistance);
  EXPECT_EQ(parsed.options.ends, ChainEnds::Estimated);
  EXPECT_EQ(parsed.options.u, (std::vector<double>{0, 1, 3, 4.5}));
  const auto again = parseModel(serializeModel(parsed), "again.json").get<CrossSectionModel>();
  EXPECT_EQ(again.options.method, ChainMethod::Global);
  EXPECT_EQ(again.options.spacing, ChainSpacing::MeanDistance);
  EXPECT_EQ(again.options.ends, ChainEnds::Estimated);
  EXPECT_EQ(again.options.u, parsed.options.u);
  EXPECT_EQ(serializeModel(again), serializeModel(parsed));
  auto with = [&](const std::string& extra) {
    return fmt::format(R"({{"type": "cross-sections", {}, "curves": {}}})", extra, curves);
  };
  EXPECT_NE(refusal(with(R"("method": "c2", "u": [0, 1, 2, 3])"))
                .find(R"($.u: "u" belongs to the "global" method, not "c2")"),
            std::string::npos);
  EXPECT_NE(refusal(with(R"("u": [0, 1, 1, 3])")).find("$.u[2]: u values must increase"),
            std::string::npos);
  EXPECT_NE(refusal(with(R"("u": [0, 1, 3])")).find("$.u: expected one u per curve (4), found 3"),
            std::string::npos);
  EXPECT_NE(refusal(with(R"("spacing": "arc")")).find("$.spacing"), std::string::npos);
}

TEST(SpectralIo, SolverRefusalsNameTheFile) {
  // Two identical position curves placed by chord length land at the same u: the file
  // parses, the solver refuses, and the error names the file.
  const std::string text = fmt::format(
      R"({{"type": "spectral", "operator": "ugail", "N": 1, "placement": "chord-length",
          "modes": 1, "conditions": [{{"curve": {}}}, {{"curve": {}}}]}})",
      circle(1, 0), circle(1, 0));
  const auto m = parseModel(text, "p.json").get<SpectralModel>();
  try {
    solve(m, "p.json");
    FAIL() << "solved a patch through two coinciding curves";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.file(), "p.json");
    EXPECT_NE(e.problem().find("coincide"), std::string::npos) << e.what();
  }
}

TEST(SpectralIo, VertexFrameFilesStillParseThroughParseModel) {
  const std::string text = R"({"type": "vertex-frames",
    "vertices": [[0,0,0],[1,0,0],[2,0,0],[2,1,0],[2,2,0],[1,2,0],[0,2,0],[0,1,0]],
    "frames": [{"vertices": [0,1,2,3,4,5,6,7]}]})";
  EXPECT_TRUE(parseModel(text, "v.json").is<VertexFrameModel>());
  EXPECT_NE(refusal(R"({"type": 3})").find("$.type: expected a string"), std::string::npos);
}

}  // namespace
}  // namespace pdesurf
