// Layouts: a quad mesh's topology reproduced by its frames; a U × V grid on a disk.
#include <gtest/gtest.h>
#include <algorithm>

#include <map>
#include <set>

#include "pdesurf/analysis.hpp"
#include "pdesurf/mesh_io.hpp"
#include "pdesurf/rebuild.hpp"
#include "support/cgal_data.hpp"

namespace pdesurf {
namespace {

using Edge = std::pair<std::uint32_t, std::uint32_t>;
Edge undirected(std::uint32_t a, std::uint32_t b) { return {std::min(a, b), std::max(a, b)}; }

/// The faces on each edge of a polygon mesh.
std::map<Edge, std::set<std::uint32_t>> edgeFaces(const PolygonMesh& mesh) {
  std::map<Edge, std::set<std::uint32_t>> out;
  for (std::uint32_t f = 0; f < mesh.faces.size(); ++f)
    for (std::size_t i = 0; i < mesh.faces[f].size(); ++i)
      out[undirected(mesh.faces[f][i], mesh.faces[f][(i + 1) % mesh.faces[f].size()])].insert(f);
  return out;
}

TEST(QuadLayout, ReproducesTheTopologyOfCgalsQuadMeshes) {
  for (const char* name : {"torus_quad.off", "cube_quad.off", "cross_quad.off"}) {
    SCOPED_TRACE(name);
    const PolygonMesh quads = readPolygonMesh(testing::cgalData(name));
    const VertexFrameModel model = quadLayout(quads, name);
    const auto edges = edgeFaces(quads);
    std::set<std::uint32_t> usedPoints;
    for (const auto& f : quads.faces) usedPoints.insert(f.begin(), f.end());

    ASSERT_EQ(model.frames.size(), quads.faces.size());
    EXPECT_EQ(model.vertices.size(), usedPoints.size() + edges.size());  // V + E

    // Every quad edge is one model edge, run by the frames of the quads on it; the corners
    // are the quad's vertices (renumbered in file order, so the order is kept).
    std::vector<std::uint32_t> index(quads.points.size(), 0);
    std::uint32_t next = 0;
    for (std::uint32_t v = 0; v < quads.points.size(); ++v)
      if (usedPoints.count(v)) index[v] = next++;
    const FrameTopology topo = buildTopology(model);
    EXPECT_EQ(topo.error.kind, TopologyError::Kind::None);
    ASSERT_EQ(topo.edges.size(), edges.size());
    std::map<Edge, std::set<std::uint32_t>> modelEdges;
    for (std::uint32_t e = 0; e < topo.edges.size(); ++e) {
      std::set<std::uint32_t> frames;
      for (const FrameSide& s : topo.sides(e)) frames.insert(s.frame);
      modelEdges[undirected(topo.edges[e].vertices[0], topo.edges[e].vertices[2])] = frames;
      // The midpoint is a vertex of no quad, used by this edge alone.
      EXPECT_GE(topo.edges[e].vertices[1], usedPoints.size());
    }
    for (const auto& [edge, faces] : edges)
      EXPECT_EQ(modelEdges[undirected(index[edge.first], index[edge.second])], faces)
          << "quad edge " << edge.first << "-" << edge.second;
    // Consistently oriented quads give consistently oriented frames, joined exactly.
    EXPECT_TRUE(topo.orientable);
    const VertexFrameSurface surface = solve(model);
    EXPECT_LT(measureC0Gap(surface).maxGap,
              kC0RelativeTolerance * surfaceBounds(surface).diagonal());
    // Each frame's normal at its centre turns as its quad does (corners a b c d).
    for (std::uint32_t f = 0; f < quads.faces.size(); ++f) {
      const auto& q = quads.faces[f];
      const Vec3 quadNormal =
          (quads.points[q[2]] - quads.points[q[0]]).cross(quads.points[q[3]] - quads.points[q[1]]);
      const SurfacePoint sp = surface.patches[f].evaluate(0.5, 0.5);
      EXPECT_GT(sp.du.cross(sp.dv).dot(quadNormal), 0.0) << "face " << f;
    }
  }
}

PolygonMesh twoQuads() {
  PolygonMesh m;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) m.points.emplace_back(i, j, 0.0);
  m.faces = {{0, 1, 4, 3}, {1, 2, 5, 4}};
  return m;
}

TEST(QuadLayout, ATriangleIsRejectedByItsFaceNumber) {
  PolygonMesh m = twoQuads();
  m.faces.push_back({2, 5, 1});
  try {
    quadLayout(m, "cage.obj");
    FAIL() << "a triangle was accepted";
  } catch (const LayoutError& e) {
    EXPECT_NE(std::string(e.what()).find("cage.obj: face 2 has 3 corners"), std::string::npos)
        << e.what();
  }
}

TEST(QuadLayout, AnEdgeOfThreeFacesIsRejectedNamingTheFaceAndEdge) {
  PolygonMesh m = twoQuads();
  m.points.emplace_back(1.0, 0.0, 1.0);
  m.points.emplace_back(1.0, 1.0, 1.0);
  m.faces.push_back({1, 4, 7, 6});  // a fin on the edge 1-4, shared by faces 0 and 1
  try {
    quadLayout(m, "cage.obj");
    FAIL() << "a non-manifold edge was accepted";
  } catch (const LayoutError& e) {
    EXPECT_NE(std::string(e.what()).find("face 2: its edge 1-4 is shared by 3 faces"),
              std::string::npos)
        << e.what();
  }
}

TEST(QuadLayout, AFaceRepeatingACornerIsRejected) {
  PolygonMesh m = twoQuads();
  m.faces[1] = {1, 2, 2, 4};
  EXPECT_THROW(quadLayout(m, "cage.obj"), LayoutError);
}

TEST(GridLayout, LaysAUByVGridOnADiskWithItsVerticesOnTheMesh) {
  const std::string path = testing::cgalData("three_peaks.off");
  const Mesh disk = readMesh(path);
  const VertexFrameModel model = gridLayout(disk, {5, 3}, path);
  EXPECT_EQ(model.frames.size(), 15u);
  EXPECT_EQ(model.vertices.size(), 11u * 7u - 15u);  // the lattice but the frames' centres
  std::vector<int> uses(model.vertices.size(), 0);
  for (const Frame& f : model.frames)
    for (const std::uint32_t v : f.vertices) ++uses[v];
  EXPECT_EQ(std::count(uses.begin(), uses.end(), 0), 0);  // every vertex is a frame's
  const FrameTopology topo = buildTopology(model);
  // A grid: 2UV + U + V edges, interior ones shared by two frames.
  EXPECT_EQ(topo.edges.size(), 2u * 15u + 5u + 3u);
  EXPECT_TRUE(topo.orientable);
  // Every vertex lies on the mesh (interpolated in one of its triangles), and the four
  // corners of the grid lie on the mesh's boundary... checked through distances: each
  // vertex's nearest mesh vertex is within the longest edge of the mesh.
  double longest = 0.0;
  auto p = [&](std::uint32_t v) {
    return Vec3(disk.positions[3 * v], disk.positions[3 * v + 1], disk.positions[3 * v + 2]);
  };
  for (std::size_t t = 0; t < disk.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k)
      longest = std::max(
          longest, (p(disk.indices[3 * t + k]) - p(disk.indices[3 * t + (k + 1) % 3])).norm());
  for (const Vec3& x : model.vertices) {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::uint32_t v = 0; v < disk.vertexCount(); ++v)
      nearest = std::min(nearest, (p(v) - x).norm());
    EXPECT_LE(nearest, longest);
  }
  // Frames face the way the mesh does: the mean frame normal agrees with the mean
  // (area-weighted) triangle normal.
  Vec3 meshNormal = Vec3::Zero(), frameNormal = Vec3::Zero();
  for (std::size_t t = 0; t < disk.triangleCount(); ++t) {
    const std::uint32_t* i = &disk.indices[3 * t];
    meshNormal += (p(i[1]) - p(i[0])).cross(p(i[2]) - p(i[0]));
  }
  const VertexFrameSurface surface = solve(model);
  for (const VertexFramePatch& patch : surface.patches) {
    const SurfacePoint sp = patch.evaluate(0.5, 0.5);
    frameNormal += sp.du.cross(sp.dv);
  }
  EXPECT_GT(meshNormal.dot(frameNormal), 0.0);
}

TEST(GridLayout, AClosedMeshIsRejectedAsNoDisk) {
  const std::string path = testing::cgalData("cube.off");
  try {
    gridLayout(readMesh(path), {2, 2}, path);
    FAIL() << "a closed mesh was accepted";
  } catch (const LayoutError& e) {
    EXPECT_NE(std::string(e.what()).find("0 boundary loops"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pdesurf
