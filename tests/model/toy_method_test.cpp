// The proof that a surface method is one description (include/pdesurf/method.hpp): a toy
// fifth method, bilinear Coons patches (four corner points a patch), defined and registered
// here in the test tree only. Parse, solve, tessellate, sample, serialise, info, NURBS
// faces, a session's whole-model transform with undo, an edit of the toy's own kind through
// the session's one edit path (parsed from JSON, applied, undone), and the CLI's build, info,
// sample and export (run in-process) all work on it with no library or CLI file knowing it
// (NoFileOutsideTheTestTreeNamesIt).
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "pdesurf/edit_io.hpp"
#include "pdesurf/error.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/method.hpp"
#include "pdesurf/model_info.hpp"
#include "pdesurf/model_io.hpp"
#include "pdesurf/session.hpp"
#include "support/cli_run.hpp"

namespace pdesurf {
namespace {

/// Rounding of a few products of numbers of size 1: what evaluations of the same bilinear
/// patch by two routes (the toy's evaluate, the mesh's floats, the NURBS face) may differ by.
constexpr double kRounding = 1e-12;
/// The mesh stores positions as floats: their rounding at coordinates of size 1 or 2.
constexpr double kFloatRounding = 1e-6;

/// The toy method's model: patches of four corners each, P00, P10, P01, P11 (the corner at
/// u, v ∈ {0, 1}).
struct CoonsToyModel {
  std::string name;
  std::vector<std::array<Vec3, 4>> patches;
};

/// S(u, v) = (1−u)(1−v) P00 + u(1−v) P10 + (1−u)v P01 + uv P11, with S_u and S_v.
SurfacePoint bilinear(const std::array<Vec3, 4>& c, double u, double v) {
  return {(1 - u) * (1 - v) * c[0] + u * (1 - v) * c[1] + (1 - u) * v * c[2] + u * v * c[3],
          (1 - v) * (c[1] - c[0]) + v * (c[3] - c[2]), (1 - u) * (c[2] - c[0]) + u * (c[3] - c[1])};
}

class SolvedCoonsToy final : public SolvedSurfaceOf<CoonsToyModel> {
 public:
  using SolvedSurfaceOf::SolvedSurfaceOf;

  std::size_t patchCount() const override { return value_.patches.size(); }
  PatchDomain domain(std::size_t) const override { return {}; }
  SurfacePoint evaluate(std::size_t patch, double u, double v) const override {
    return bilinear(value_.patches[patch], u, v);
  }
  /// Each patch exactly: a degree-1 B-spline face whose poles are its corners.
  NurbsModel toNurbs(const NurbsExportOptions&) const override {
    NurbsModel out;
    for (std::size_t k = 0; k < value_.patches.size(); ++k) {
      const auto& c = value_.patches[k];
      NurbsSurface s;
      s.uDegree = s.vDegree = 1;
      s.uKnots = s.vKnots = {0, 0, 1, 1};
      s.uCount = s.vCount = 2;
      s.poles = {c[0], c[2], c[1], c[3]};  // poles[i * vCount + j], i along u
      out.faces.push_back({s, static_cast<std::uint32_t>(k), true, 0.0, true});
    }
    out.diagonal = 1.0;
    return out;
  }
  /// Patch edges are straight lines between corners: two patches meet exactly where they
  /// share both corners of an edge, and the toy joins patches no other way.
  double largestC0Gap() const override { return 0.0; }
};

/// The toy's one edit: {"op": "move-corner", "patch": k, "corner": c, "position": [x, y, z]}.
struct MoveCorner {
  std::size_t patch = 0, corner = 0;
  Vec3 position = Vec3::Zero();
};

class CoonsToyMethod final : public SurfaceMethod {
 public:
  const char* typeName() const override { return "bilinear-coons"; }
  std::type_index modelType() const override { return typeid(CoonsToyModel); }

  AnyModel parse(const nlohmann::json& doc, const std::string& source) const override {
    CoonsToyModel model;
    if (doc.contains("name")) model.name = doc.at("name").get<std::string>();
    const auto patches = doc.find("patches");
    if (patches == doc.end() || !patches->is_array() || patches->empty())
      throw ModelError(source, "$.patches", "expected an array of patches");
    for (std::size_t k = 0; k < patches->size(); ++k) {
      const nlohmann::json& corners = (*patches)[k];
      if (!corners.is_array() || corners.size() != 4)
        throw ModelError(source, "$.patches[" + std::to_string(k) + "]",
                         "a patch has 4 corner points");
      std::array<Vec3, 4> patch;
      for (std::size_t i = 0; i < 4; ++i) {
        const auto xyz = corners[i].get<std::array<double, 3>>();
        patch[i] = Vec3(xyz[0], xyz[1], xyz[2]);
      }
      model.patches.push_back(patch);
    }
    return model;
  }
  std::string serialize(const AnyModel& model) const override {
    const auto& m = model.get<CoonsToyModel>();
    nlohmann::ordered_json doc = {{"type", typeName()}};
    if (!m.name.empty()) doc["name"] = m.name;
    doc["patches"] = nlohmann::ordered_json::array();
    for (const auto& patch : m.patches) {
      nlohmann::ordered_json corners = nlohmann::ordered_json::array();
      for (const Vec3& p : patch) corners.push_back({p.x(), p.y(), p.z()});
      doc["patches"].push_back(std::move(corners));
    }
    return doc.dump(2) + "\n";
  }
  const std::string& name(const AnyModel& model) const override {
    return model.get<CoonsToyModel>().name;
  }
  std::shared_ptr<const SolvedSurface> solve(
      const AnyModel& model, const std::string&, const SolveOptions&,
      const std::shared_ptr<const FrameTopology>&) const override {
    return std::make_shared<const SolvedCoonsToy>(model.get<CoonsToyModel>());
  }
  AnyModel transform(const AnyModel& model, const AffineMap& map) const override {
    CoonsToyModel out = model.get<CoonsToyModel>();
    for (auto& patch : out.patches)
      for (Vec3& p : patch) p = map.point(p);
    return out;
  }
  ModelEdit parseEdit(std::string_view json, const AnyModel& model) const override {
    const auto doc = nlohmann::json::parse(json);
    if (doc.value("op", "") != "move-corner")
      throw ModelError("edit", "$.op", "the toy takes move-corner alone");
    MoveCorner e{doc.at("patch").get<std::size_t>(), doc.at("corner").get<std::size_t>()};
    if (e.patch >= model.get<CoonsToyModel>().patches.size() || e.corner >= 4)
      throw ModelError("edit", "$.patch", "no such corner");
    const auto xyz = doc.at("position").get<std::array<double, 3>>();
    e.position = Vec3(xyz[0], xyz[1], xyz[2]);
    return {e, doc.value("group", "")};
  }
  EditResult applyEdit(const EditContext& context, const ModelEdit& edit) const override {
    const auto& e = edit.as<MoveCorner>(typeName());
    CoonsToyModel next = context.current.model->get<CoonsToyModel>();
    next.patches[e.patch][e.corner] = e.position;
    return {{std::make_shared<const AnyModel>(std::move(next)), nullptr, nullptr}};
  }
};

/// Registers the toy method once in this process (ctest runs each test in its own).
void registerToy() {
  static const CoonsToyMethod method;
  if (!findMethod(method.typeName())) registerMethod(method);
}

/// Two unit squares side by side, the second one bent up at its far edge.
constexpr const char* kToyText = R"({
  "type": "bilinear-coons",
  "name": "toy",
  "patches": [
    [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]],
    [[1, 0, 0], [2, 0, 1], [1, 1, 0], [2, 1, 1]]
  ]
})";

TEST(ToyMethod, RegistryFindsItByTypeNameAndByModel) {
  registerToy();
  const SurfaceMethod* method = findMethod("bilinear-coons");
  ASSERT_NE(method, nullptr);
  EXPECT_EQ(surfaceMethods().back(), method);
  const AnyModel model = parseModel(kToyText, "toy.json");
  EXPECT_EQ(&model.method(), method);
  EXPECT_STREQ(modelTypeName(model), "bilinear-coons");
  EXPECT_EQ(modelNameOf(model), "toy");
  ASSERT_NE(model.as<CoonsToyModel>(), nullptr);
  EXPECT_EQ(model.as<VertexFrameModel>(), nullptr);
  EXPECT_FALSE(hasEditableParts(model));
  // A second method of the same type name or model type is refused.
  EXPECT_THROW(registerMethod(*method), InvalidArgument);
  // Unknown types name every registered one.
  const std::string refusal = [] {
    try {
      parseModel(R"({"type": "nope"})", "n.json");
    } catch (const ModelError& e) {
      return std::string(e.what());
    }
    return std::string("(parsed)");
  }();
  EXPECT_NE(refusal.find("\"bspline-pde\" or \"bilinear-coons\""), std::string::npos) << refusal;
}

TEST(ToyMethod, SolvesTessellatesSamplesAndWritesBack) {
  registerToy();
  const SolvedModel solved = solve(parseModel(kToyText, "toy.json"), "toy.json");
  const auto& corners = solved.model().get<CoonsToyModel>().patches;
  ASSERT_EQ(solved.surface().patchCount(), 2u);
  EXPECT_EQ(largestC0Gap(solved), 0.0);

  // Samples: the bilinear formula at i/(n−1), j/(n−1).
  constexpr std::uint32_t kGrid = 5;
  const std::vector<PatchSamples> samples = sample(solved, {kGrid});
  ASSERT_EQ(samples.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    ASSERT_EQ(samples[k].points.size(), kGrid * kGrid);
    for (std::uint32_t j = 0; j < kGrid; ++j)
      for (std::uint32_t i = 0; i < kGrid; ++i)
        EXPECT_LT((samples[k].points[j * kGrid + i] -
                   bilinear(corners[k], i / (kGrid - 1.0), j / (kGrid - 1.0)).p)
                      .norm(),
                  kRounding);
  }

  // The mesh: a resolution × resolution grid a patch, every vertex on the surface.
  constexpr std::uint32_t kResolution = 4;
  const Mesh mesh = tessellate(solved, {kResolution});
  EXPECT_EQ(mesh.vertexCount(), 2u * kResolution * kResolution);
  EXPECT_EQ(mesh.triangleCount(), 2u * 2 * (kResolution - 1) * (kResolution - 1));
  EXPECT_EQ(mesh.patchIds.size(), mesh.triangleCount());
  const Vec3 far(mesh.positions[3 * (2 * kResolution * kResolution - 1)],
                 mesh.positions[3 * (2 * kResolution * kResolution - 1) + 1],
                 mesh.positions[3 * (2 * kResolution * kResolution - 1) + 2]);
  EXPECT_LT((far - corners[1][3]).norm(), kFloatRounding);

  // NURBS faces reproduce the patches.
  const NurbsModel nurbs = toNurbs(solved);
  ASSERT_EQ(nurbs.faces.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k)
    EXPECT_LT((nurbs.faces[k].surface.position(0.3, 0.7) - bilinear(corners[k], 0.3, 0.7).p).norm(),
              kRounding);

  // Written and read back: the same model, the same text.
  const std::string text = serializeModel(solved.model());
  EXPECT_EQ(serializeModel(parseModel(text, "again.json")), text);

  // The default report and info (the method gives none of its own).
  EXPECT_EQ(report(solved).summary, "bilinear-coons, 2 patches");
  const ModelInfo info = modelInfo(solved);
  EXPECT_EQ(info.source, "toy.json");
  EXPECT_EQ(info.name, "toy");
  ASSERT_NE(info.find("patches"), nullptr);
  EXPECT_EQ(info.find("patches")->value, 2);
  ASSERT_NE(info.find("bbox"), nullptr);
  EXPECT_EQ(info.find("bbox")->value.at("max"), nlohmann::ordered_json::parse("[2.0, 1.0, 1.0]"));
}

TEST(ToyMethod, SessionTransformsAndUndoes) {
  registerToy();
  ModelSession session(parseModel(kToyText, "toy.json"), "toy.json");
  const Vec3 before = session.solved().surface().evaluate(1, 0.5, 0.5).p;
  const AffineMap shift = AffineMap::translationBy(Vec3(0, 0, 2));
  session.transform(shift);
  EXPECT_LT((session.model().get<CoonsToyModel>().patches[1][3] - Vec3(2, 1, 3)).norm(), kRounding);
  EXPECT_LT((session.solved().surface().evaluate(1, 0.5, 0.5).p - shift.point(before)).norm(),
            kRounding);
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(session.solved().surface().evaluate(1, 0.5, 0.5).p, before);
}

TEST(ToyMethod, SessionAppliesItsOwnEditAndUndoesIt) {
  registerToy();
  ModelSession session(parseModel(kToyText, "toy.json"), "toy.json");
  const std::string before = serializeModel(session.model());
  // A drag of the shared corner's copy in patch 1 in two steps of one group: one undo step.
  for (const char* z : {"0.5", "1"})
    session.apply(parseEdit(
        std::string(R"({"op": "move-corner", "patch": 1, "corner": 0, "position": [1, 0, )") + z +
            R"(], "group": "drag"})",
        session.model()));
  EXPECT_EQ(session.undoDepth(), 1u);
  // The session solved the edited model: patch 1's corner (u, v) = (0, 0) is where it went.
  EXPECT_LT((session.solved().surface().evaluate(1, 0.0, 0.0).p - Vec3(1, 0, 1)).norm(), kRounding);
  // Another method's edit and an unknown op are refused, the session unchanged.
  EXPECT_THROW(session.apply(MoveVertex{0, Vec3::Zero()}), std::logic_error);
  EXPECT_THROW(parseEdit(R"({"op": "move-vertex"})", session.model()), ModelError);
  EXPECT_EQ(session.undoDepth(), 1u);
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(serializeModel(session.model()), before);
  EXPECT_EQ(session.solved().surface().evaluate(1, 0.0, 0.0).p, Vec3(1, 0, 0));
  ASSERT_TRUE(session.redo());
  EXPECT_EQ(session.model().get<CoonsToyModel>().patches[1][0], Vec3(1, 0, 1));
}

/// Runs the CLI in-process; its standard output.
int runPdesurf(std::vector<std::string> args, std::string* out = nullptr) {
  args.insert(args.begin(), "pdesurf");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  if (out) ::testing::internal::CaptureStdout();
  const int code = cli::runCli(static_cast<int>(argv.size()), argv.data());
  std::fflush(stdout);
  if (out) *out = ::testing::internal::GetCapturedStdout();
  return code;
}

TEST(ToyMethod, CliBuildsInformsSamplesAndExports) {
  registerToy();
  const testing::TempDir work;
  const std::string model = work.file("toy.json");
  {
    std::FILE* f = std::fopen(model.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs(kToyText, f);
    std::fclose(f);
  }
  ASSERT_EQ(runPdesurf({"build", model, "-o", work.file("toy.obj"), "--resolution", "3", "-q"}), 0);
  EXPECT_EQ(readMesh(work.file("toy.obj")).vertexCount(), 2u * 3 * 3);

  std::string out;
  ASSERT_EQ(runPdesurf({"info", model, "--json"}, &out), 0);
  EXPECT_EQ(nlohmann::json::parse(out).at("type"), "bilinear-coons");
  ASSERT_EQ(runPdesurf({"info", model}, &out), 0);
  EXPECT_NE(out.find("\ntype       bilinear-coons\npatches    2\n"), std::string::npos) << out;

  ASSERT_EQ(runPdesurf({"sample", model, "--grid", "3"}, &out), 0);
  const auto sampled = nlohmann::json::parse(out).at("patches");
  ASSERT_EQ(sampled.size(), 2u);
  EXPECT_EQ(sampled[1].at("points")[8], nlohmann::json::parse("[2.0, 1.0, 1.0]"));

  ASSERT_EQ(runPdesurf({"export", model, "-o", work.file("toy.step"), "-q"}), 0);
  EXPECT_NE(testing::readText(work.file("toy.step")).find("B_SPLINE_SURFACE"), std::string::npos);
}

TEST(ToyMethod, NoFileOutsideTheTestTreeNamesIt) {
  // The proof holds only while the library, the apps and the Python package know nothing of
  // the toy: neither its type name nor its model's C++ name appears in their sources (a
  // comment may point at this file).
  const std::filesystem::path root(PDESURF_SOURCE_DIR);
  std::size_t read = 0;
  for (const char* folder : {"include", "src", "apps", "python/src", "python/pdesurf"})
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root / folder)) {
      if (!entry.is_regular_file()) continue;
      const std::string text = testing::readText(entry.path().string());
      ++read;
      for (const char* name : {"bilinear-coons", "CoonsToy"})
        EXPECT_EQ(text.find(name), std::string::npos) << entry.path() << " names " << name;
    }
  EXPECT_GT(read, 100u);  // the folders were found and read
}

}  // namespace
}  // namespace pdesurf
