// Tests of mesh file IO: round trips through every format, error messages, atomic writes.
#include "pdesurf/mesh_io.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <tiny_gltf.h>

#include <array>
#include <bit>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace pdesurf {
namespace {

namespace fs = std::filesystem;

/// A fresh directory, removed with everything in it at the end of the test.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "pdesurf-mesh-io-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const fs::path& path() const { return path_; }

  /// The names of the entries in the directory.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path_))
      names.push_back(entry.path().filename().string());
    return names;
  }

 private:
  fs::path path_;
};

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

/// A closed, consistently oriented sphere-like mesh: the surface of an n×n×n grid cube with
/// shared vertices, pushed out to a sphere (so coordinates need all of a float's digits),
/// with the outward unit normals.
Mesh makeCubeSphere(int n) {
  Mesh mesh;
  std::map<std::array<int, 3>, std::uint32_t> vertexAt;
  const auto vertex = [&](std::array<int, 3> lattice) {
    const auto [it, inserted] =
        vertexAt.try_emplace(lattice, static_cast<std::uint32_t>(mesh.vertexCount()));
    if (inserted) {
      double p[3], length = 0;
      for (int k = 0; k < 3; ++k) {
        p[k] = 2.0 * lattice[k] / n - 1.0;
        length += p[k] * p[k];
      }
      length = std::sqrt(length);
      for (int k = 0; k < 3; ++k) {
        mesh.normals.push_back(static_cast<float>(p[k] / length));
        mesh.positions.push_back(static_cast<float>(1.7 * p[k] / length + 0.1 * (k + 1)));
      }
    }
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side <= n; side += n) {
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          std::array<std::uint32_t, 4> quad;
          const int corners[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
          for (int c = 0; c < 4; ++c) {
            std::array<int, 3> lattice{};
            lattice[axis] = side;
            lattice[u] = corners[c][0];
            lattice[v] = corners[c][1];
            quad[c] = vertex(lattice);
          }
          // Counter-clockwise seen from outside: (u, v) turns towards +axis.
          if (side == 0) std::swap(quad[1], quad[3]);
          mesh.indices.insert(mesh.indices.end(), {quad[0], quad[1], quad[2]});
          mesh.indices.insert(mesh.indices.end(), {quad[0], quad[2], quad[3]});
        }
      }
    }
  }
  return mesh;
}

/// Whether every undirected edge is used by exactly two triangles, once in each direction.
bool isWatertightAndOriented(const Mesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) ++directed[{mesh.indices[t + k], mesh.indices[t + (k + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    if (count != 1) return false;
    const auto twin = directed.find({edge.second, edge.first});
    if (twin == directed.end() || twin->second != 1) return false;
  }
  return !directed.empty();
}

/// Float buffers equal bit for bit (so -0 differs from 0).
::testing::AssertionResult bitsEqual(const MeshBuffer<float>& expected,
                                     const MeshBuffer<float>& actual) {
  if (expected.size() != actual.size())
    return ::testing::AssertionFailure()
           << "sizes differ: " << expected.size() << " vs " << actual.size();
  for (std::size_t i = 0; i < expected.size(); ++i)
    if (std::bit_cast<std::uint32_t>(expected[i]) != std::bit_cast<std::uint32_t>(actual[i]))
      return ::testing::AssertionFailure()
             << "value " << i << " differs: " << expected[i] << " vs " << actual[i];
  return ::testing::AssertionSuccess();
}

/// Triangle t's corner positions, corner by corner.
std::array<float, 9> trianglePositions(const Mesh& mesh, std::size_t t) {
  std::array<float, 9> corners;
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t k = 0; k < 3; ++k)
      corners[3 * c + k] = mesh.positions[3 * std::size_t{mesh.indices[3 * t + c]} + k];
  return corners;
}

template <typename Function>
std::string errorOf(Function&& function) {
  try {
    function();
  } catch (const MeshIoError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no MeshIoError";
  return {};
}

/// Whether `text` contains `part`, printing both when not.
::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

// ---------------------------------------------------------------------------------------------

TEST(MeshIoFormat, RecognisesExtensionsIgnoringCase) {
  EXPECT_EQ(meshFormatFromPath("a/b.obj"), MeshFormat::Obj);
  EXPECT_EQ(meshFormatFromPath("B.PLY"), MeshFormat::Ply);
  EXPECT_EQ(meshFormatFromPath("dir.x/c.Stl"), MeshFormat::Stl);
  EXPECT_EQ(meshFormatFromPath("c.glB"), MeshFormat::Glb);
  EXPECT_EQ(meshFormatFromPath("./d.off"), MeshFormat::Off);
}

TEST(MeshIoFormat, UnknownExtensionNamesPathAndExtension) {
  const std::string message = errorOf([] { meshFormatFromPath("out/mesh.xyz"); });
  EXPECT_TRUE(contains(message, "out/mesh.xyz"));
  EXPECT_TRUE(contains(message, "unknown mesh format '.xyz'"));
  EXPECT_TRUE(contains(message, ".obj, .ply, .stl, .glb or .off"));
  EXPECT_TRUE(contains(errorOf([] { meshFormatFromPath("dir.obj/mesh"); }), "dir.obj/mesh"));
  EXPECT_THROW(writeMesh(makeCubeSphere(1), "mesh.gltf"), MeshIoError);
  EXPECT_THROW(readMesh("mesh.txt"), MeshIoError);
}

// The formats that keep everything: positions and normals bit for bit, indices as they are.
class MeshIoExactRoundTrip : public ::testing::TestWithParam<std::tuple<std::string, bool>> {};

TEST_P(MeshIoExactRoundTrip, PreservesPositionsNormalsAndIndices) {
  const auto& [extension, withNormals] = GetParam();
  Mesh mesh = makeCubeSphere(24);
  if (!withNormals) mesh.normals.clear();
  ASSERT_TRUE(isWatertightAndOriented(mesh));
  TempDir dir;
  const std::string path = dir.file("mesh" + extension);
  writeMesh(mesh, path);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"mesh" + extension});
  const Mesh read = readMesh(path);
  EXPECT_EQ(read.vertexCount(), mesh.vertexCount());
  EXPECT_EQ(read.triangleCount(), mesh.triangleCount());
  EXPECT_TRUE(bitsEqual(mesh.positions, read.positions));
  EXPECT_TRUE(bitsEqual(mesh.normals, read.normals));
  EXPECT_EQ(read.indices, mesh.indices);
  EXPECT_TRUE(isWatertightAndOriented(read));
}

INSTANTIATE_TEST_SUITE_P(MeshIo, MeshIoExactRoundTrip,
                         ::testing::Combine(::testing::Values(".obj", ".ply", ".glb", ".OBJ"),
                                            ::testing::Bool()),
                         [](const auto& info) {
                           std::string name = std::get<0>(info.param).substr(1);
                           return name + (std::get<1>(info.param) ? "WithNormals" : "");
                         });

TEST(MeshIoRoundTrip, OffKeepsPositionsAndIndices) {
  const Mesh mesh = makeCubeSphere(8);
  TempDir dir;
  writeMesh(mesh, dir.file("mesh.off"));
  const Mesh read = readMesh(dir.file("mesh.off"));
  EXPECT_TRUE(bitsEqual(mesh.positions, read.positions));
  EXPECT_TRUE(read.normals.empty());
  EXPECT_EQ(read.indices, mesh.indices);
  EXPECT_TRUE(isWatertightAndOriented(read));
}

TEST(MeshIoRoundTrip, StlMergesCornersBackIntoTheSameMesh) {
  const Mesh mesh = makeCubeSphere(12);
  TempDir dir;
  writeMesh(mesh, dir.file("mesh.stl"));
  EXPECT_EQ(fs::file_size(dir.file("mesh.stl")), 84 + 50 * mesh.triangleCount());
  const Mesh read = readMesh(dir.file("mesh.stl"));
  EXPECT_EQ(read.vertexCount(), mesh.vertexCount());
  ASSERT_EQ(read.triangleCount(), mesh.triangleCount());
  EXPECT_TRUE(read.normals.empty());
  // Vertices are renumbered, but each triangle keeps its corners' positions, in order.
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    ASSERT_EQ(trianglePositions(read, t), trianglePositions(mesh, t)) << "triangle " << t;
  EXPECT_TRUE(isWatertightAndOriented(read));
}

TEST(MeshIoRoundTrip, ExtremeFloatsSurviveTheTextFormats) {
  Mesh mesh;
  mesh.positions = {1e-45f,      -0.0f, 3.4028235e38f, 1.0f / 3.0f, -1.17549435e-38f,
                    16777217.0f, 0.1f,  -2.5f,         1e-7f};
  mesh.normals = {0.0f, 0.0f, 1.0f, 0.6f, 0.8f, 0.0f, -0.0f, -1.0f, 0.0f};
  mesh.indices = {0, 1, 2};
  TempDir dir;
  for (const std::string name : {"m.obj", "m.ply", "m.glb", "m.off"}) {
    writeMesh(mesh, dir.file(name));
    const Mesh read = readMesh(dir.file(name));
    EXPECT_TRUE(bitsEqual(mesh.positions, read.positions)) << name;
    if (name != "m.off") {
      EXPECT_TRUE(bitsEqual(mesh.normals, read.normals)) << name;
    }
    EXPECT_EQ(read.indices, mesh.indices) << name;
  }
}

TEST(MeshIoRoundTrip, EmptyMeshesAndMeshesWithoutTriangles) {
  Mesh points;
  points.positions = {0, 0, 0, 1, 2, 3};
  TempDir dir;
  for (const std::string name : {"p.obj", "p.ply", "p.glb", "p.off"}) {
    writeMesh(Mesh{}, dir.file("empty-" + name));
    const Mesh empty = readMesh(dir.file("empty-" + name));
    EXPECT_EQ(empty.vertexCount(), 0u) << name;
    EXPECT_EQ(empty.triangleCount(), 0u) << name;
    writeMesh(points, dir.file(name));
    const Mesh read = readMesh(dir.file(name));
    EXPECT_TRUE(bitsEqual(points.positions, read.positions)) << name;
    EXPECT_EQ(read.triangleCount(), 0u) << name;
  }
  writeMesh(points, dir.file("p.stl"));
  EXPECT_EQ(readMesh(dir.file("p.stl")).vertexCount(), 0u);
}

// ---------------------------------------------------------------------------------------------

TEST(MeshIoWrite, StlCarriesUnitFacetNormals) {
  Mesh mesh;
  mesh.positions = {0, 0, 0, 2, 0, 0, 0, 3, 0, 1, 1, 1};
  mesh.indices = {0, 1, 2, 0, 0, 3};  // the second triangle is degenerate
  TempDir dir;
  writeMesh(mesh, dir.file("t.stl"));
  const std::string bytes = readBytes(dir.file("t.stl"));
  ASSERT_EQ(bytes.size(), 84u + 2 * 50u);
  EXPECT_EQ(bytes.substr(0, 7), "pdesurf");
  std::uint32_t count;
  std::memcpy(&count, bytes.data() + 80, 4);
  EXPECT_EQ(count, 2u);
  std::array<float, 12> first, second;
  std::memcpy(first.data(), bytes.data() + 84, sizeof(first));
  std::memcpy(second.data(), bytes.data() + 84 + 50, sizeof(second));
  EXPECT_EQ((std::array<float, 3>{first[0], first[1], first[2]}), (std::array<float, 3>{0, 0, 1}));
  EXPECT_EQ((std::array<float, 3>{second[0], second[1], second[2]}),
            (std::array<float, 3>{0, 0, 0}));
  EXPECT_EQ((std::array<float, 3>{first[6], first[7], first[8]}), (std::array<float, 3>{2, 0, 0}));
}

TEST(MeshIoWrite, GlbIsValidGltfWithPositionBounds) {
  const Mesh mesh = makeCubeSphere(4);
  TempDir dir;
  writeMesh(mesh, dir.file("m.glb"));
  EXPECT_EQ(readBytes(dir.file("m.glb")).substr(0, 4), "glTF");
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, dir.file("m.glb"))) << error;
  ASSERT_EQ(model.meshes.size(), 1u);
  ASSERT_EQ(model.meshes[0].primitives.size(), 1u);
  const tinygltf::Primitive& primitive = model.meshes[0].primitives[0];
  EXPECT_EQ(primitive.mode, TINYGLTF_MODE_TRIANGLES);
  const tinygltf::Accessor& positions = model.accessors.at(primitive.attributes.at("POSITION"));
  std::vector<double> min(3, INFINITY), max(3, -INFINITY);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    min[i % 3] = std::min<double>(min[i % 3], mesh.positions[i]);
    max[i % 3] = std::max<double>(max[i % 3], mesh.positions[i]);
  }
  EXPECT_EQ(positions.minValues, min);
  EXPECT_EQ(positions.maxValues, max);
  EXPECT_EQ(model.accessors.at(primitive.indices).componentType,
            TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  EXPECT_EQ(model.scenes.size(), 1u);
  EXPECT_EQ(model.nodes.size(), 1u);
}

TEST(MeshIoWrite, MissingDirectoryThrowsAndLeavesNothing) {
  TempDir dir;
  const std::string path = dir.file("missing/mesh.obj");
  const std::string message = errorOf([&] { writeMesh(makeCubeSphere(2), path); });
  EXPECT_TRUE(contains(message, path));
  EXPECT_TRUE(contains(message, "No such file or directory"));
  EXPECT_TRUE(dir.entries().empty());
}

TEST(MeshIoWrite, ReplacesAnExistingFileAndLeavesNoTemporary) {
  TempDir dir;
  for (const std::string name : {"m.obj", "m.ply", "m.stl", "m.glb", "m.off"}) {
    writeText(dir.file(name), "old contents");
    writeMesh(makeCubeSphere(3), dir.file(name));
    EXPECT_EQ(readMesh(dir.file(name)).triangleCount(), makeCubeSphere(3).triangleCount());
  }
  EXPECT_EQ(dir.entries().size(), 5u);
}

TEST(MeshIoWrite, InvalidMeshThrowsAndLeavesNothing) {
  Mesh mesh = makeCubeSphere(2);
  mesh.indices.back() = static_cast<std::uint32_t>(mesh.vertexCount());
  TempDir dir;
  EXPECT_TRUE(contains(errorOf([&] { writeMesh(mesh, dir.file("bad.ply")); }), "refers to vertex"));
  mesh = makeCubeSphere(2);
  mesh.normals.pop_back();
  EXPECT_TRUE(contains(errorOf([&] { writeMesh(mesh, dir.file("bad.obj")); }), "bad.obj"));
  mesh = makeCubeSphere(2);
  mesh.positions[4] = std::numeric_limits<float>::infinity();  // vertex 1, y
  EXPECT_TRUE(contains(errorOf([&] { writeMesh(mesh, dir.file("inf.glb")); }),
                       "vertex 1 has a non-finite position"));
  mesh = makeCubeSphere(2);
  mesh.normals[0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(
      contains(errorOf([&] { writeMesh(mesh, dir.file("nan.stl")); }), "non-finite normal"));
  EXPECT_TRUE(dir.entries().empty());
}

TEST(MeshIoWrite, FailedWriteThrowsAndLeavesNothing) {
  // A file size limit makes write(2) fail with EFBIG part way through.
  TempDir dir;
  rlimit saved{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  const auto savedHandler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit limited = saved;
  limited.rlim_cur = 100000;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &limited), 0);
  std::vector<std::string> messages;
  for (const std::string name : {"big.obj", "big.ply", "big.stl", "big.glb", "big.off"})
    messages.push_back(errorOf([&] { writeMesh(makeCubeSphere(40), dir.file(name)); }));
  ::setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, savedHandler);
  for (const std::string& message : messages) {
    EXPECT_TRUE(contains(message, "big."));
    EXPECT_TRUE(contains(message, "File too large"));
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(MeshIoWrite, RenameOntoADirectoryFailsAndRemovesTheTemporary) {
  TempDir dir;
  fs::create_directory(dir.file("taken.obj"));
  fs::create_directory(dir.file("taken.obj/inside"));
  EXPECT_TRUE(
      contains(errorOf([&] { writeMesh(makeCubeSphere(2), dir.file("taken.obj")); }), "taken.obj"));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"taken.obj"});
}

// ---------------------------------------------------------------------------------------------

TEST(MeshIoRead, MissingFileNamesThePath) {
  TempDir dir;
  const std::string message = errorOf([&] { readMesh(dir.file("nothing.ply")); });
  EXPECT_TRUE(contains(message, "nothing.ply"));
  EXPECT_TRUE(contains(message, "No such file or directory"));
  fs::create_directory(dir.file("folder.obj"));
  EXPECT_TRUE(contains(errorOf([&] { readMesh(dir.file("folder.obj")); }), "folder.obj: "));
}

TEST(MeshIoRead, TruncatedBinaryPlyNamesTheFile) {
  TempDir dir;
  const std::string path = dir.file("cut.ply");
  writeMesh(makeCubeSphere(4), path);
  fs::resize_file(path, fs::file_size(path) - 5);
  const std::string message = errorOf([&] { readMesh(path); });
  EXPECT_TRUE(contains(message, "cut.ply"));
  EXPECT_TRUE(contains(message, "unexpected end of file in face"));
  fs::resize_file(path, 100);  // inside the header
  EXPECT_TRUE(contains(errorOf([&] { readMesh(path); }), "cut.ply"));
}

TEST(MeshIoRead, TruncatedOrMalformedOffNamesTheFileAndTheLine) {
  TempDir dir;
  const std::string path = dir.file("cut.off");
  // Too short for the header's counts: refused before CGAL sizes anything by them.
  writeText(path, "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(path); }),
                       "cut.off: the file is too short for the counts in its header (4 vertices, "
                       "4 faces"));
  writeText(path, "OFF\n400000000 1 0\n0 0 0\n");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(path); }), "cut.off: the file is too short"));
  // Long enough, but the lines run out.
  writeText(path, "OFF\n3 1 0\n0 0 0 \n1 0 0 \n0 1 0 \n\n\n\n\n\n\n\n");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(path); }),
                       "cut.off: unexpected end of file: the header announces 3 vertices and 1 "
                       "faces, the file has 3 lines of them"));
  // A malformed line: the file, the line and its text.
  writeText(path, "OFF\n3 1 0\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(path); }),
                       "cut.off: line 4: '1 zero 0' is not a list of numbers"));
  writeText(path, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1\n3 0 1 2\n\n\n");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(path); }),
                       "cut.off: line 5: '0 1' is not a valid OFF vertex line"));
  writeText(path, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n\n\n\n");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(path); }), "cut.off: face 0 has 2 corners"));
}

TEST(MeshIoRead, CoordinatesBeyondSinglePrecisionNameTheVertex) {
  TempDir dir;
  writeText(dir.file("big.off"), "OFF\n3 1 0\n0 0 0\n1e39 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(dir.file("big.off")); }),
                       "big.off: vertex 1 has a non-finite coordinate (inf)"));
  writeText(dir.file("big.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
            "property double z\nend_header\n0 0 0\n0 -1e300 0\n0 1 0\n");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(dir.file("big.ply")); }),
                       "big.ply: vertex 1 has a non-finite coordinate (-inf)"));
}

TEST(MeshIoRead, OutOfRangeIndicesNameTheFile) {
  TempDir dir;
  writeText(dir.file("bad.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 9\n");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(dir.file("bad.ply")); }),
                       "bad.ply: face 1 refers to vertex 9 but the file has 3 vertices"));
  writeText(dir.file("bad.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(dir.file("bad.off")); }),
                       "bad.off: line 6: face 0 refers to a vertex the file does not have (it has "
                       "3 vertices)"));
  writeText(dir.file("bad.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 -4\n");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(dir.file("bad.obj")); }),
                       "bad.obj: line 5: face 1 refers to vertex -4"));
  writeText(dir.file("zero.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(dir.file("zero.obj")); }), "zero.obj: line 4"));

  // A binary PLY with one index patched out of range.
  Mesh mesh;
  mesh.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  mesh.indices = {0, 1, 2};
  writeMesh(mesh, dir.file("patched.ply"));
  std::string bytes = readBytes(dir.file("patched.ply"));
  const std::int32_t large = 800;
  std::memcpy(bytes.data() + bytes.size() - 4, &large, 4);
  writeText(dir.file("patched.ply"), bytes);
  EXPECT_TRUE(contains(errorOf([&] { readMesh(dir.file("patched.ply")); }),
                       "patched.ply: face 0 refers to vertex 800 but the file has 3 vertices"));
}

TEST(MeshIoRead, OffWithCommentsAndAQuad) {
  TempDir dir;
  // A square pyramid: one quad base, four triangles.
  writeText(dir.file("pyramid.off"),
            "OFF\n"
            "# a square pyramid\n"
            "5 5 8\n"
            "0 0 0\n1 0 0\n1 1 0\n0 1 0  # the last base corner\n"
            "0.5 0.5 1\n"
            "4 0 3 2 1\n"
            "3 0 1 4\n3 1 2 4\n3 2 3 4 255 0 0\n3 3 0 4\n");
  const Mesh mesh = readMesh(dir.file("pyramid.off"));
  EXPECT_EQ(mesh.vertexCount(), 5u);
  EXPECT_EQ(mesh.triangleCount(), 6u);
  EXPECT_EQ(std::vector<std::uint32_t>(mesh.indices.begin(), mesh.indices.begin() + 6),
            (std::vector<std::uint32_t>{0, 3, 2, 0, 2, 1}));
  EXPECT_EQ(mesh.positions[12], 0.5f);
  EXPECT_TRUE(isWatertightAndOriented(mesh));

  writeText(dir.file("inline.off"), "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(readMesh(dir.file("inline.off")).triangleCount(), 1u);
  writeText(dir.file("normals.off"),
            "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n");
  EXPECT_EQ(readMesh(dir.file("normals.off")).normals,
            (MeshBuffer<float>{0, 0, 1, 0, 0, 1, 0, 0, 1}));
}

TEST(MeshIoRead, ObjCornerFormsNegativeIndicesAndPolygons) {
  TempDir dir;
  writeText(dir.file("quad.obj"),
            "# a quad\r\nmtllib none.mtl\r\no quad\r\n"
            "v 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0 1.0\r\n"
            "vt 0 0\r\nvn 0 0 1\r\nvn 0 0 1\r\nvn 0 0 1\r\nvn 0 0 -1\r\n"
            "g side\r\nusemtl red\r\ns off\r\n"
            "f 1/1/1 2//2 -2/1/-2 4//4\r\n");
  const Mesh quad = readMesh(dir.file("quad.obj"));
  EXPECT_EQ(quad.vertexCount(), 4u);
  EXPECT_EQ(quad.indices, (MeshBuffer<std::uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(quad.normals, (MeshBuffer<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, -1}));

  // Vertex 1 paired with two different normals: the normals are dropped.
  writeText(dir.file("mixed.obj"),
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nvn 0 0 -1\n"
            "f 1//1 2//1 3//1\nf 2//2 4//1 3//1\n");
  const Mesh mixed = readMesh(dir.file("mixed.obj"));
  EXPECT_EQ(mixed.triangleCount(), 2u);
  EXPECT_TRUE(mixed.normals.empty());

  writeText(dir.file("plain.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1 2 3\n");
  EXPECT_TRUE(readMesh(dir.file("plain.obj")).normals.empty());

  writeText(dir.file("broken.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2/x 3\n");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(dir.file("broken.obj")); }),
                       "broken.obj: line 4: malformed corner '2/x'"));
}

TEST(MeshIoRead, AsciiPlyWithDoublesAndOtherProperties) {
  TempDir dir;
  writeText(dir.file("a.ply"),
            "ply\nformat ascii 1.0\ncomment made by hand\n"
            "element vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
            "property uchar red\nproperty float nx\nproperty float ny\nproperty float nz\n"
            "element face 1\nproperty uint flags\nproperty list uint uint vertex_index\n"
            "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
            "0 0 0 255 0 0 1\n1 0 0 0 0 0 1\n1 1 0 0 0 0 1\n0 1 0 9 0 0 1\n"
            "7 4 0 1 2 3\n0 1\n");
  const Mesh mesh = readMesh(dir.file("a.ply"));
  EXPECT_EQ(mesh.positions, (MeshBuffer<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}));
  EXPECT_EQ(mesh.normals, (MeshBuffer<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}));
  EXPECT_EQ(mesh.indices, (MeshBuffer<std::uint32_t>{0, 1, 2, 0, 2, 3}));

  writeText(dir.file("noz.ply"),
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
            "end_header\n0 0\n");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(dir.file("noz.ply")); }),
                       "noz.ply: the vertex element has no property 'z'"));
}

// The PLY files CGAL 5.5's polygon-soup reader cannot take (it crashes on integer
// coordinates and refuses index lists of other than 32-bit integers): the reasons
// src/io/mesh_io.cpp gives for the project's own PLY reader.
TEST(MeshIoRead, PlyWithIntegerCoordinatesAndShortIndexLists) {
  TempDir dir;
  writeText(dir.file("int.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty int x\nproperty short y\n"
            "property uchar z\nelement face 1\nproperty list uchar ushort vertex_indices\n"
            "end_header\n-4 0 0\n7 -300 0\n0 12 255\n3 2 1 0\n");
  const Mesh mesh = readMesh(dir.file("int.ply"));
  EXPECT_EQ(mesh.positions, (MeshBuffer<float>{-4, 0, 0, 7, -300, 0, 0, 12, 255}));
  EXPECT_EQ(mesh.indices, (MeshBuffer<std::uint32_t>{2, 1, 0}));

  // The same as binary big-endian: int16 coordinates, a list of int8 counts and uint8 indices.
  std::string binary =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty int16 x\n"
      "property int16 y\nproperty int16 z\nelement face 1\n"
      "property list int8 uint8 vertex_indices\nend_header\n";
  for (const int value : {-4, 0, 0, 7, -300, 0, 0, 12, 255}) {
    const auto bits = static_cast<std::uint16_t>(static_cast<std::int16_t>(value));
    binary.push_back(static_cast<char>(bits >> 8));
    binary.push_back(static_cast<char>(bits & 0xff));
  }
  for (const char byte : {3, 2, 1, 0}) binary.push_back(byte);
  writeText(dir.file("int-be.ply"), binary);
  const Mesh fromBinary = readMesh(dir.file("int-be.ply"));
  EXPECT_EQ(fromBinary.positions, mesh.positions);
  EXPECT_EQ(fromBinary.indices, mesh.indices);
}

TEST(MeshIoRead, AsciiStlIsIndexed) {
  TempDir dir;
  std::string text = "solid tetra\n";
  const float corners[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  for (const auto& face : faces) {
    text += "  facet normal 0 0 0\n    outer loop\n";
    for (int c : face)
      text += "      vertex " + std::to_string(corners[c][0]) + " " +
              std::to_string(corners[c][1]) + " " + std::to_string(corners[c][2]) + "\n";
    text += "    endloop\n  endfacet\n";
  }
  text += "endsolid tetra\n";
  writeText(dir.file("tetra.stl"), text);
  const Mesh mesh = readMesh(dir.file("tetra.stl"));
  EXPECT_EQ(mesh.vertexCount(), 4u);
  EXPECT_EQ(mesh.triangleCount(), 4u);
  EXPECT_TRUE(isWatertightAndOriented(mesh));

  writeText(dir.file("short.stl"), "not an stl");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(dir.file("short.stl")); }), "short.stl"));
  // Cut short; when shorter than a binary header, CGAL's reader takes it for an empty file.
  writeText(dir.file("cut.stl"), text.substr(0, text.find("endloop")));
  const std::string cut = errorOf([&] { readMesh(dir.file("cut.stl")); });
  EXPECT_TRUE(contains(cut, "cut.stl: "));
  EXPECT_TRUE(contains(cut, "not valid ASCII STL"));
  writeText(dir.file("tiny.stl"), "solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\n");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(dir.file("tiny.stl")); }),
                       "tiny.stl: not valid ASCII STL: 0 of its 0 complete facets could be read, "
                       "and it has no 'endsolid'"));
  writeText(dir.file("bad.stl"), text.replace(text.find("vertex 0"), 8, "vertex x"));
  EXPECT_TRUE(contains(errorOf([&] { readMesh(dir.file("bad.stl")); }), "bad.stl: "));
}

TEST(MeshIoRead, CorruptGlbNamesTheFile) {
  TempDir dir;
  writeText(dir.file("bad.glb"), "glTF but not really");
  EXPECT_TRUE(contains(errorOf([&] { readMesh(dir.file("bad.glb")); }), "bad.glb: "));
}

}  // namespace
}  // namespace pdesurf
