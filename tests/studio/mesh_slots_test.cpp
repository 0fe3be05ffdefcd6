// Tests of the studio's mesh slots without HTTP (apps/studio/mesh_slots.hpp): the mesh they
// lend to the routes that describe the page's mesh (GET /api/patch-ids, /api/curvature) is
// the one a fresh tessellation gives, and only for the revision, solver and resolution it was
// sent for.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "mesh_slots.hpp"
#include "pdesurf/model_io.hpp"
#include "support/cli_run.hpp"

namespace pdesurf::studio {
namespace {

/// The same mesh to the byte: positions, normals, triangles and their patches.
void expectSameMesh(const Mesh& a, const Mesh& b) {
  auto same = [](const auto& x, const auto& y) {
    return x.size() == y.size() &&
           std::memcmp(x.data(), y.data(), x.size() * sizeof(*x.data())) == 0;
  };
  EXPECT_TRUE(same(a.positions, b.positions));
  EXPECT_TRUE(same(a.normals, b.normals));
  EXPECT_TRUE(same(a.indices, b.indices));
  EXPECT_TRUE(same(a.patchIds, b.patchIds));
}

ModelSession exampleSession(const std::string& name) {
  const std::string path = std::string(PDESURF_SOURCE_DIR) + "/examples/" + name;
  return ModelSession(parseModel(testing::readText(path), name), name);
}

TEST(MeshSlots, LendTheSentMeshOnlyForItsRevisionSolverAndResolution) {
  ModelSession session = exampleSession("mug.json");
  MeshSlots slots;
  const SolveOptions global;
  const std::uint32_t resolution = 12;
  EXPECT_EQ(slots.sent(resolution, 1, global), nullptr);  // nothing sent yet

  const MeshAnswer first = slots.mesh(session, 1, resolution, 0, global);
  const Mesh* sent = slots.sent(resolution, 1, global);
  ASSERT_NE(sent, nullptr);
  expectSameMesh(*sent, tessellate(session.solved(global), {resolution}));
  EXPECT_EQ(slots.sent(resolution, 2, global), nullptr);      // another revision
  EXPECT_EQ(slots.sent(resolution + 1, 1, global), nullptr);  // another resolution
  SolveOptions local;
  local.vertexFrames.solver = Solver::Local;
  EXPECT_EQ(slots.sent(resolution, 1, local), nullptr);  // solved another way
  local.vertexFrames.solver = Solver::Global;
  local.vertexFrames.seedFrame = 1;
  EXPECT_EQ(slots.sent(resolution, 1, local), nullptr);

  // An edit, and the next mesh sent as a delta against the first: the slot now lends the
  // edited surface, tessellated in place, equal to a fresh tessellation of it.
  const VertexFrameModel& before = *session.frames();
  const std::uint32_t vertex = before.frames[0].vertices[2];
  session.apply(MoveVertex{vertex, before.vertices[vertex] + Vec3(0.05, -0.1, 0.2)});
  const MeshAnswer delta = slots.mesh(session, 2, resolution, first.id, global);
  EXPECT_EQ(delta.base, first.id);  // a delta: the slot's tessellator moved its mesh in place
  EXPECT_EQ(slots.sent(resolution, 1, global), nullptr);
  const Mesh* edited = slots.sent(resolution, 2, global);
  ASSERT_NE(edited, nullptr);
  expectSameMesh(*edited, tessellate(session.solved(global), {resolution}));
}

}  // namespace
}  // namespace pdesurf::studio
