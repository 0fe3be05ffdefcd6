// Tests of the `pdesurf` command: the real binary (PDESURF_CLI) run in a fresh directory,
// its exit status, standard output, standard error and the files it leaves behind.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pdesurf/mesh_io.hpp"
#include "pdesurf/vertex_frames.hpp"
#include "support/cli_run.hpp"

namespace pdesurf {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

using testing::CliRun;
using testing::readText;
using testing::TempDir;

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string quote(const std::string& s) { return testing::shellQuote(s); }

// ---------------------------------------------------------------------------------------
// Models, written as JSON text.

/// One flat frame over [0, 2]².
const char* kOneFrame = R"({"type": "vertex-frames",
  "vertices": [[0, 0, 0], [1, 0, 0], [2, 0, 0], [2, 1, 0], [2, 2, 0], [1, 2, 0], [0, 2, 0],
               [0, 1, 0]],
  "frames": [{"vertices": [0, 1, 2, 3, 4, 5, 6, 7]}]})";

/// Three bad models: the text, and the JSON path their error must name.
struct BadModel {
  const char* name;
  const char* text;
  const char* path;
};
const BadModel kBadModels[] = {
    {"malformed", R"({"type": "vertex-frames", "vertices": [[0, 0, 0], [1, 0, 0],, "frames": []})",
     "$.vertices[2]"},
    {"out-of-range", R"({"type": "vertex-frames",
      "vertices": [[0, 0, 0], [1, 0, 0], [2, 0, 0], [2, 1, 0], [2, 2, 0], [1, 2, 0], [0, 2, 0],
                   [0, 1, 0]],
      "frames": [{"vertices": [0, 1, 2, 3, 4, 5, 6, 8]}]})",
     "$.frames[0].vertices[7]"},
    {"middle-mismatch", R"({"type": "vertex-frames",
      "vertices": [[0, 0, 0], [1, 0, 0], [2, 0, 0], [2, 1, 0], [2, 2, 0], [1, 2, 0], [0, 2, 0],
                   [0, 1, 0], [3, 0, 0], [4, 0, 0], [4, 1, 0], [4, 2, 0], [3, 2, 0], [2, 1, 1]],
      "frames": [{"vertices": [0, 1, 2, 3, 4, 5, 6, 7]},
                 {"vertices": [2, 8, 9, 10, 11, 12, 4, 13]}]})",
     "$.frames[1].vertices"},
};

/// A rows × cols lattice of frames over a (2 cols + 1) × (2 rows + 1) grid of vertices,
/// every coordinate displaced by up to `noise`, with optional sculpting forces.
VertexFrameModel latticeModel(int rows, int cols, double noise, bool forces) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  VertexFrameModel m;
  m.name = "lattice";
  const int nu = 2 * cols + 1, nv = 2 * rows + 1;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      m.vertices.push_back(Vec3(0.5 * i, 0.5 * j, 0.2 * std::sin(i + 0.5 * j)) +
                           noise * Vec3(unit(rng), unit(rng), unit(rng)));
  auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * nu + i); };
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const int i = 2 * c, j = 2 * r;
      Frame f;
      f.vertices = {at(i, j),         at(i + 1, j),     at(i + 2, j), at(i + 2, j + 1),
                    at(i + 2, j + 2), at(i + 1, j + 2), at(i, j + 2), at(i, j + 1)};
      if (forces && (r + c) % 2 == 0) {
        f.a1 = {1.5, 1, 0.5};
        f.forces.push_back({{0, 0, 2}, {0.2, 0.7, 0.3, 0.9}});
      }
      m.frames.push_back(f);
    }
  if (forces) m.forces.push_back({{0, 0, -1}, {0, static_cast<std::uint32_t>(rows * cols - 1)}});
  return m;
}

/// The model as JSON text (nlohmann writes doubles shortest round-trip).
std::string modelJson(const VertexFrameModel& m) {
  auto vec = [](const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); };
  Json doc = {{"type", "vertex-frames"}, {"name", m.name}};
  doc["vertices"] = Json::array();
  for (const Vec3& v : m.vertices) doc["vertices"].push_back(vec(v));
  doc["frames"] = Json::array();
  for (const Frame& f : m.frames) {
    Json jf = {{"vertices", f.vertices}, {"a1", vec(f.a1)}, {"a2", vec(f.a2)}};
    jf["forces"] = Json::array();
    for (const FrameForce& force : f.forces)
      jf["forces"].push_back(
          {{"f0", vec(force.f0)},
           {"region", {force.region.u0, force.region.u1, force.region.v0, force.region.v1}}});
    doc["frames"].push_back(jf);
  }
  doc["forces"] = Json::array();
  for (const SharedForce& force : m.forces)
    doc["forces"].push_back({{"f0", vec(force.f0)}, {"frames", force.frames}});
  return doc.dump(1);
}

/// Every test: a work directory the CLI runs in (holding only the files the test puts
/// there and what the CLI writes) and a separate one for the captured output.
class CliFixture : public ::testing::Test {
 protected:
  /// Runs `pdesurf ARGS` (ARGS already shell words) from the work directory.
  CliRun run(const std::string& args) { return testing::runCli(work_, capture_, args); }
  /// Writes `text` to the work directory; returns its full path.
  std::string put(const std::string& name, const std::string& text) {
    writeText(work_.file(name), text);
    return work_.file(name);
  }
  std::string path(const std::string& name) const { return work_.file(name); }
  std::vector<std::string> entries() const { return work_.entries(); }

  TempDir work_, capture_;
};

// The suites: one fixture class each, so that every suite name starts with "Cli".
class CliHelp : public CliFixture {};
class CliUsage : public CliFixture {};
class CliInvalidInput : public CliFixture {};
class CliSample : public CliFixture {};
class CliInfo : public CliFixture {};
class CliBuild : public CliFixture {};

bool contains(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos;
}

// ---------------------------------------------------------------------------------------
// Help.

TEST_F(CliHelp, TopLevelHelpNamesTheSubcommandsAndExitStatus) {
  const CliRun r = run("--help");
  EXPECT_EQ(r.code, 0) << r.err;
  for (const char* word : {"build", "sample", "info", "--help", "--version", "Exit status"})
    EXPECT_TRUE(contains(r.out, word)) << word << "\n" << r.out;
}

TEST_F(CliHelp, BuildHelpNamesItsOptions) {
  const CliRun r = run("build --help");
  EXPECT_EQ(r.code, 0) << r.err;
  for (const char* word : {"model", "-o,--output", ".obj", ".ply", ".stl", ".glb", "--resolution",
                           "-q,--quiet", "--solver", "global", "local", "--seed-frame"})
    EXPECT_TRUE(contains(r.out, word)) << word << "\n" << r.out;
}

TEST_F(CliHelp, SampleHelpNamesItsOptions) {
  const CliRun r = run("sample --help");
  EXPECT_EQ(r.code, 0) << r.err;
  for (const char* word : {"model", "--grid", "points[j*N+i]", "--solver", "--seed-frame"})
    EXPECT_TRUE(contains(r.out, word)) << word << "\n" << r.out;
}

TEST_F(CliHelp, InfoHelpNamesItsOptions) {
  const CliRun r = run("info --help");
  EXPECT_EQ(r.code, 0) << r.err;
  for (const char* word : {"model", "--json", "--solver", "--seed-frame"})
    EXPECT_TRUE(contains(r.out, word)) << word << "\n" << r.out;
}

TEST_F(CliHelp, Version) {
  const CliRun r = run("--version");
  EXPECT_EQ(r.code, 0);
  EXPECT_TRUE(contains(r.out, "pdesurf 0.1.0")) << r.out;
}

// ---------------------------------------------------------------------------------------
// Usage errors: exit 2, a message on stderr, nothing written.

TEST_F(CliUsage, NoSubcommand) {
  const CliRun r = run("");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "subcommand")) << r.err;
}

TEST_F(CliUsage, UnknownSubcommand) {
  put("m.json", kOneFrame);
  const CliRun r = run("frobnicate m.json");
  EXPECT_EQ(r.code, 2);
  // CLI11 reports the missing subcommand rather than the unknown word.
  EXPECT_TRUE(contains(r.err, "subcommand")) << r.err;
}

TEST_F(CliUsage, UnknownOption) {
  put("m.json", kOneFrame);
  for (const char* args :
       {"build m.json -o out.obj --bogus", "sample m.json --grid 3 --bogus", "info m.json --bogus",
        "info m.json --resolution 5", "sample m.json --grid 3 --json"}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_FALSE(r.err.empty()) << args;
    EXPECT_EQ(r.out, "") << args;
  }
  EXPECT_EQ(entries(), std::vector<std::string>{"m.json"});
}

TEST_F(CliUsage, BuildWithoutOutput) {
  put("m.json", kOneFrame);
  const CliRun r = run("build m.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "--output")) << r.err;
}

TEST_F(CliUsage, MissingModelArgument) {
  for (const char* args : {"build -o out.obj", "sample --grid 3", "info"}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_TRUE(contains(r.err, "model")) << args << "\n" << r.err;
  }
}

TEST_F(CliUsage, ResolutionOutOfRange) {
  put("m.json", kOneFrame);
  for (const char* args :
       {"build m.json -o out.obj --resolution 1", "build m.json -o out.obj --resolution 4098",
        "build m.json -o out.obj --resolution -3", "build m.json -o out.obj --resolution many"}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_TRUE(contains(r.err, "--resolution")) << args << "\n" << r.err;
  }
  EXPECT_EQ(entries(), std::vector<std::string>{"m.json"});
}

TEST_F(CliUsage, SampleGridMissingOrOutOfRange) {
  put("m.json", kOneFrame);
  for (const char* args : {"sample m.json", "sample m.json --grid 1", "sample m.json --grid 0"}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_TRUE(contains(r.err, "--grid")) << args << "\n" << r.err;
    EXPECT_EQ(r.out, "") << args;
  }
}

TEST_F(CliUsage, UnknownSolver) {
  put("m.json", kOneFrame);
  for (const char* args : {"build m.json -o out.obj --solver foo",
                           "sample m.json --grid 3 --solver foo", "info m.json --solver foo"}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_TRUE(contains(r.err, "--solver")) << args << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, "foo")) << args << "\n" << r.err;
  }
  EXPECT_EQ(entries(), std::vector<std::string>{"m.json"});
}

TEST_F(CliUsage, SeedFrameBeyondTheFrameCount) {
  put("m.json", kOneFrame);
  for (const char* args :
       {"build m.json -o out.obj --solver local --seed-frame 1",
        "sample m.json --grid 3 --solver local --seed-frame 7", "info m.json --seed-frame 1"}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_TRUE(contains(r.err, "--seed-frame")) << args << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, "1 frame")) << args << "\n" << r.err;
    EXPECT_EQ(r.out, "") << args;
  }
  EXPECT_EQ(entries(), std::vector<std::string>{"m.json"});
}

TEST_F(CliUsage, UnknownOutputExtension) {
  put("m.json", kOneFrame);
  for (const char* out : {"out.xyz", "out", "out.obj.bak"}) {
    const CliRun r = run(std::string("build m.json -o ") + out);
    EXPECT_EQ(r.code, 2) << out;
    EXPECT_TRUE(contains(r.err, out)) << r.err;
    EXPECT_TRUE(contains(r.err, ".obj")) << r.err;
  }
  EXPECT_EQ(entries(), std::vector<std::string>{"m.json"});
}

// ---------------------------------------------------------------------------------------
// Invalid input: exit 1, the file and JSON path on stderr, no output file.

TEST_F(CliInvalidInput, BuildNamesFileAndPathAndWritesNothing) {
  for (const BadModel& bad : kBadModels) {
    const std::string model = put(std::string(bad.name) + ".json", bad.text);
    for (const char* ext : {".obj", ".glb"}) {
      const CliRun r =
          run("build " + quote(model) + " -o " + quote(path(std::string("out") + ext)));
      EXPECT_EQ(r.code, 1) << bad.name << "\n" << r.err;
      EXPECT_TRUE(contains(r.err, model + ": " + bad.path + ": ")) << bad.name << "\n" << r.err;
      EXPECT_EQ(r.out, "") << bad.name;
      EXPECT_FALSE(fs::exists(path(std::string("out") + ext))) << bad.name;
    }
  }
  // Only the models: no output, no temporary files.
  EXPECT_EQ(entries(), (std::vector<std::string>{"malformed.json", "middle-mismatch.json",
                                                 "out-of-range.json"}));
}

TEST_F(CliInvalidInput, SampleAndInfoNameFileAndPath) {
  for (const BadModel& bad : kBadModels) {
    const std::string model = put(std::string(bad.name) + ".json", bad.text);
    for (const std::string& args : {"sample " + quote(model) + " --grid 3", "info " + quote(model),
                                    "info " + quote(model) + " --json"}) {
      const CliRun r = run(args);
      EXPECT_EQ(r.code, 1) << args << "\n" << r.err;
      EXPECT_TRUE(contains(r.err, model + ": " + bad.path + ": ")) << args << "\n" << r.err;
      EXPECT_EQ(r.out, "") << args;
    }
  }
}

TEST_F(CliInvalidInput, MessagesSayWhatIsWrong) {
  const std::string words[] = {"malformed JSON", "vertex index 8 is out of range",
                               "middle vertex is 13"};
  for (std::size_t i = 0; i < std::size(kBadModels); ++i) {
    put("m.json", kBadModels[i].text);
    const CliRun r = run("info m.json");
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(contains(r.err, words[i])) << r.err;
    // One line: "pdesurf: FILE: PATH: PROBLEM".
    EXPECT_EQ(r.err.rfind("pdesurf: m.json: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

TEST_F(CliInvalidInput, ExistingOutputIsLeftUntouched) {
  const std::string original = "# an older mesh, not to be touched\nv 0 0 0\n";
  for (const BadModel& bad : kBadModels) {
    put("bad.json", bad.text);
    put("out.obj", original);
    const CliRun r = run("build bad.json -o out.obj");
    EXPECT_EQ(r.code, 1) << bad.name;
    EXPECT_EQ(readText(path("out.obj")), original) << bad.name;
    EXPECT_EQ(entries(), (std::vector<std::string>{"bad.json", "out.obj"})) << bad.name;
  }
}

TEST_F(CliInvalidInput, MissingModelFile) {
  const CliRun r = run("build missing.json -o out.obj");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "missing.json")) << r.err;
  EXPECT_TRUE(contains(r.err, "cannot open")) << r.err;
  EXPECT_TRUE(entries().empty());
}

TEST_F(CliInvalidInput, OutputIntoAMissingDirectory) {
  put("m.json", kOneFrame);
  const CliRun r = run("build m.json -o nowhere/out.obj");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_TRUE(contains(r.err, "nowhere/out.obj")) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_FALSE(fs::exists(path("nowhere")));
  EXPECT_EQ(entries(), std::vector<std::string>{"m.json"});
}

// ---------------------------------------------------------------------------------------
// sample.

/// The printed patches, checked for shape: frame k at index k, grid N, N² points of 3.
std::vector<std::vector<Vec3>> parseSample(const std::string& text, std::size_t frames,
                                           std::uint32_t grid) {
  const Json doc = Json::parse(text);
  EXPECT_TRUE(doc.is_object());
  EXPECT_EQ(doc.size(), 1u);
  const Json& patches = doc.at("patches");
  EXPECT_EQ(patches.size(), frames);
  std::vector<std::vector<Vec3>> out;
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const Json& p = patches[k];
    EXPECT_EQ(p.at("frame").get<std::size_t>(), k);
    EXPECT_EQ(p.at("grid").get<std::uint32_t>(), grid);
    const Json& points = p.at("points");
    EXPECT_EQ(points.size(), std::size_t{grid} * grid);
    std::vector<Vec3> pts;
    for (const Json& q : points) {
      EXPECT_EQ(q.size(), 3u);
      pts.emplace_back(q[0].get<double>(), q[1].get<double>(), q[2].get<double>());
    }
    out.push_back(std::move(pts));
  }
  return out;
}

/// Grid positions (i, j) of P1..P8 for N = 3.
constexpr int kVertexAt[8][2] = {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};

double scaleOf(const VertexFrameModel& m) {
  double s = 0.0;
  for (const Vec3& v : m.vertices) s = std::max(s, v.cwiseAbs().maxCoeff());
  return s;
}

TEST_F(CliSample, GridThreeHasTheFrameVerticesAtTheirPlaces) {
  const VertexFrameModel model = latticeModel(3, 3, 0.15, true);
  put("m.json", modelJson(model));
  const double tol = 1e-12 * scaleOf(model);
  for (const char* solver : {"global", "local"}) {
    const CliRun r = run(std::string("sample m.json --grid 3 --solver ") + solver);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1);
    const auto patches = parseSample(r.out, model.frames.size(), 3);
    ASSERT_EQ(patches.size(), model.frames.size());
    for (std::size_t k = 0; k < patches.size(); ++k)
      for (int s = 0; s < 8; ++s) {
        const Vec3& printed = patches[k][kVertexAt[s][1] * 3 + kVertexAt[s][0]];
        const Vec3& vertex = model.vertices[model.frames[k].vertices[s]];
        EXPECT_LE((printed - vertex).cwiseAbs().maxCoeff(), tol)
            << solver << " frame " << k << " P" << s + 1 << ": " << printed.transpose() << " vs "
            << vertex.transpose();
      }
  }
}

TEST_F(CliSample, PrintedNumbersAreTheSurfaceExactly) {
  // points[j*N+i] = S(i/(N-1), j/(N-1)), printed so that they read back bit for bit.
  const VertexFrameModel model = latticeModel(2, 3, 0.2, true);
  put("m.json", modelJson(model));
  for (const Solver solver : {Solver::Global, Solver::Local}) {
    const bool local = solver == Solver::Local;
    for (const std::uint32_t n : {2u, 4u, 7u}) {
      const CliRun r = run("sample m.json --grid " + std::to_string(n) +
                           (local ? " --solver local --seed-frame 4" : ""));
      ASSERT_EQ(r.code, 0) << r.err;
      const auto patches = parseSample(r.out, model.frames.size(), n);
      const VertexFrameSurface surface = solve(model, {solver, local ? 4u : 0u});
      for (std::size_t k = 0; k < patches.size(); ++k)
        for (std::uint32_t j = 0; j < n; ++j)
          for (std::uint32_t i = 0; i < n; ++i) {
            const double u = static_cast<double>(i) / (n - 1), v = static_cast<double>(j) / (n - 1);
            const Vec3 expected = surface.patches[k].position(u, v);
            const Vec3& printed = patches[k][j * n + i];
            EXPECT_EQ(printed.x(), expected.x()) << k << " " << i << " " << j;
            EXPECT_EQ(printed.y(), expected.y()) << k << " " << i << " " << j;
            EXPECT_EQ(printed.z(), expected.z()) << k << " " << i << " " << j;
          }
    }
  }
}

TEST_F(CliSample, LocalSolverDiffersFromGlobalButKeepsTheVertices) {
  const VertexFrameModel model = latticeModel(3, 3, 0.25, false);
  put("m.json", modelJson(model));
  const CliRun global = run("sample m.json --grid 5");
  const CliRun local = run("sample m.json --grid 5 --solver local");
  const CliRun seeded = run("sample m.json --grid 5 --solver local --seed-frame 8");
  ASSERT_EQ(global.code, 0) << global.err;
  ASSERT_EQ(local.code, 0) << local.err;
  ASSERT_EQ(seeded.code, 0) << seeded.err;
  const auto g = parseSample(global.out, 9, 5), l = parseSample(local.out, 9, 5),
             s = parseSample(seeded.out, 9, 5);
  const double tol = 1e-12 * scaleOf(model);
  double maxDiff = 0.0, maxSeedDiff = 0.0;
  for (std::size_t k = 0; k < 9; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) {
        const int at = j * 5 + i;
        const double d = (g[k][at] - l[k][at]).norm();
        maxDiff = std::max(maxDiff, d);
        maxSeedDiff = std::max(maxSeedDiff, (s[k][at] - l[k][at]).norm());
        if (i % 2 == 0 && j % 2 == 0 && (i == 2 ? j != 2 : true)) {  // P1..P8 at N = 5
          EXPECT_LE(d, tol) << "frame " << k << " (" << i << ", " << j << ")";
          EXPECT_LE((s[k][at] - g[k][at]).norm(), tol) << "frame " << k;
        }
      }
  EXPECT_GT(maxDiff, 1e-4) << "the local and global solvers agree everywhere";
  EXPECT_GT(maxSeedDiff, 1e-6) << "the seed frame changes nothing";
}

// ---------------------------------------------------------------------------------------
// info.

TEST_F(CliInfo, JsonReportsCountsGapBoundsAndStorage) {
  const VertexFrameModel model = latticeModel(3, 3, 0.2, true);
  put("m.json", modelJson(model));
  const CliRun r = run("info m.json --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j.at("model").get<std::string>(), "m.json");
  EXPECT_EQ(j.at("name").get<std::string>(), "lattice");
  EXPECT_EQ(j.at("vertices").get<std::size_t>(), 49u);
  EXPECT_EQ(j.at("frames").get<std::size_t>(), 9u);
  // One u-strip per column and one v-strip per row.
  EXPECT_EQ(j.at("strips").get<std::size_t>(), 6u);
  EXPECT_EQ(j.at("pinned_strips").get<std::size_t>(), 0u);
  EXPECT_EQ(j.at("edges").get<std::size_t>(), 24u);
  EXPECT_EQ(j.at("shared_edges").get<std::size_t>(), 12u);
  EXPECT_TRUE(j.at("orientable").get<bool>());
  EXPECT_EQ(j.at("solver").get<std::string>(), "global");
  const Vec3 lo(j["bbox"]["min"][0].get<double>(), j["bbox"]["min"][1].get<double>(),
                j["bbox"]["min"][2].get<double>());
  const Vec3 hi(j["bbox"]["max"][0].get<double>(), j["bbox"]["max"][1].get<double>(),
                j["bbox"]["max"][2].get<double>());
  const double diag = (hi - lo).norm();
  EXPECT_GT(diag, 1.0);
  const double gap = j.at("c0_gap").get<double>();
  EXPECT_GE(gap, 0.0);
  EXPECT_LT(gap, 1e-12 * diag);
  EXPECT_NEAR(j.at("c0_gap_relative").get<double>(), gap / diag, 1e-20);
  for (const Frame& f : model.frames)  // the surface runs through every frame vertex
    for (std::uint32_t index : f.vertices)
      for (int c = 0; c < 3; ++c) {
        const Vec3& v = model.vertices[index];
        EXPECT_LE(lo[c], v[c] + 1e-12 * diag);
        EXPECT_GE(hi[c], v[c] - 1e-12 * diag);
      }
  EXPECT_GT(j.at("storage_bytes").get<std::size_t>(), 0u);
}

TEST_F(CliInfo, JsonNamesTheSolver) {
  put("m.json", modelJson(latticeModel(2, 2, 0.1, false)));
  const CliRun r = run("info m.json --json --solver local --seed-frame 3");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(Json::parse(r.out).at("solver").get<std::string>(), "local");
}

/// The numbers on a line of plain `info` that starts with `label`.
std::vector<double> numbersOnLine(const std::string& text, const std::string& label) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(label, 0) == 0) {
      std::vector<double> out;
      static const std::regex number(R"([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)");
      const std::string rest = line.substr(label.size());
      for (std::sregex_iterator it(rest.begin(), rest.end(), number), end; it != end; ++it)
        out.push_back(std::stod(it->str()));
      return out;
    }
  ADD_FAILURE() << "no line starting with \"" << label << "\" in\n" << text;
  return {};
}

TEST_F(CliInfo, PlainTextPrintsTheSameNumbers) {
  put("m.json", modelJson(latticeModel(3, 3, 0.2, true)));
  const CliRun plain = run("info m.json");
  const CliRun json = run("info m.json --json");
  ASSERT_EQ(plain.code, 0) << plain.err;
  ASSERT_EQ(json.code, 0) << json.err;
  const Json j = Json::parse(json.out);
  EXPECT_TRUE(contains(plain.out, "m.json (lattice)")) << plain.out;
  EXPECT_EQ(numbersOnLine(plain.out, "vertices"), std::vector<double>{j["vertices"].get<double>()});
  EXPECT_EQ(numbersOnLine(plain.out, "frames"), std::vector<double>{j["frames"].get<double>()});
  EXPECT_EQ(numbersOnLine(plain.out, "strips"),
            (std::vector<double>{j["strips"].get<double>(), j["pinned_strips"].get<double>(), 0}));
  EXPECT_EQ(numbersOnLine(plain.out, "edges"),
            (std::vector<double>{j["edges"].get<double>(), j["shared_edges"].get<double>()}));
  EXPECT_EQ(numbersOnLine(plain.out, "C0 gap"),
            (std::vector<double>{j["c0_gap"].get<double>(), j["c0_gap_relative"].get<double>()}));
}

TEST_F(CliInfo, PlainTextShowsTheBoxAndStorage) {
  put("m.json", modelJson(latticeModel(3, 3, 0.2, true)));
  const CliRun plain = run("info m.json");
  const CliRun json = run("info m.json --json");
  ASSERT_EQ(plain.code, 0) << plain.err;
  const Json j = Json::parse(json.out);
  std::vector<double> box;
  for (const char* end : {"min", "max"})
    for (int c = 0; c < 3; ++c) box.push_back(j["bbox"][end][c].get<double>());
  EXPECT_EQ(numbersOnLine(plain.out, "bbox"), box);
  EXPECT_EQ(numbersOnLine(plain.out, "storage"),
            std::vector<double>{j["storage_bytes"].get<double>()});
}

// ---------------------------------------------------------------------------------------
// build.

TEST_F(CliBuild, WritesEveryFormatWithTheCountsItPrints) {
  const VertexFrameModel model = latticeModel(3, 3, 0.2, true);
  put("m.json", modelJson(model));
  const std::size_t side = 3 * (5 - 1) + 1;  // resolution 5: 13 × 13 shared vertices
  std::vector<std::string> expected = {"m.json"};
  for (const char* ext : {".obj", ".ply", ".stl", ".glb"}) {
    const std::string out = std::string("out") + ext;
    const CliRun r = run("build m.json -o " + out + " --resolution 5");
    ASSERT_EQ(r.code, 0) << ext << "\n" << r.err;
    EXPECT_EQ(r.err, "") << ext;
    // One summary line: "NAME: F frames, S strips, V vertices, T triangles, C0 gap G -> OUT (...)".
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.out, m,
                                  std::regex(R"(^lattice: 9 frames, 6 strips, (\d+) vertices, )"
                                             R"((\d+) triangles, C0 gap \S+ -> (\S+) )")))
        << r.out;
    EXPECT_EQ(m[3].str(), out);
    const std::size_t vertices = std::stoul(m[1].str()), triangles = std::stoul(m[2].str());
    EXPECT_EQ(vertices, side * side) << ext;
    EXPECT_EQ(triangles, 9u * 4 * 4 * 2) << ext;
    const Mesh mesh = readMesh(path(out));
    EXPECT_EQ(mesh.vertexCount(), vertices) << ext;
    EXPECT_EQ(mesh.triangleCount(), triangles) << ext;
    expected.push_back(out);
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(entries(), expected) << "temporary files left behind?";
  }
}

TEST_F(CliBuild, ThreadsChangeNoByteOfTheMesh) {
  // Enough frames (a 12 × 12 sheet at resolution 33) that the work is split between threads.
  put("m.json", modelJson(latticeModel(12, 12, 0.2, true)));
  for (const char* args : {"build m.json -o one.ply --resolution 33 --threads 1",
                           "--threads 2 build m.json -o two.ply --resolution 33",
                           "build m.json -o all.ply --resolution 33"}) {
    const CliRun r = run(args);
    ASSERT_EQ(r.code, 0) << args << "\n" << r.err;
  }
  const std::string one = readText(path("one.ply"));
  EXPECT_GT(one.size(), 100000u);
  EXPECT_EQ(readText(path("two.ply")), one);
  EXPECT_EQ(readText(path("all.ply")), one);
}

TEST_F(CliUsage, ThreadsMustBeACount) {
  put("m.json", kOneFrame);
  for (const char* args :
       {"build m.json -o out.obj --threads -1", "build m.json -o out.obj --threads x",
        "--threads 5000 build m.json -o out.obj"}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_TRUE(contains(r.err, "--threads")) << args << "\n" << r.err;
  }
  EXPECT_EQ(entries(), std::vector<std::string>{"m.json"});
}

TEST_F(CliBuild, QuietPrintsNothing) {
  put("m.json", kOneFrame);
  const CliRun r = run("build m.json -o out.ply -q --resolution 3");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "");
  const Mesh mesh = readMesh(path("out.ply"));
  EXPECT_EQ(mesh.vertexCount(), 9u);
  EXPECT_EQ(mesh.triangleCount(), 8u);
}

TEST_F(CliBuild, ReplacesAnExistingOutput) {
  put("m.json", kOneFrame);
  put("out.obj", "not a mesh\n");
  const CliRun r = run("build m.json -o out.obj --resolution 4 --solver local");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "-> out.obj")) << r.out;
  EXPECT_EQ(readMesh(path("out.obj")).vertexCount(), 16u);
  EXPECT_EQ(entries(), (std::vector<std::string>{"m.json", "out.obj"}));
}

TEST_F(CliBuild, SummaryUsesTheFileNameWithoutAModelName) {
  const std::string model = put("flat.json", kOneFrame);
  const CliRun r = run("build " + quote(model) + " -o " + quote(path("flat.stl")));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(
      r.out.rfind("flat.json: 1 frame, 2 strips, 289 vertices, 512 triangles, C0 gap 0 -> ", 0), 0u)
      << r.out;
}

}  // namespace
}  // namespace pdesurf
