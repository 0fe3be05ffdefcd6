// Models of many patches: exact C0 on every topology, strips, the two solvers.
#include <gtest/gtest.h>

#include <random>

#include "pdesurf/analysis.hpp"
#include "pdesurf/vertex_frames.hpp"
#include "support/models.hpp"

namespace pdesurf {
namespace {

using testing::latticeModel;
using testing::LatticeOptions;

double relativeGap(const VertexFrameSurface& s) {
  return measureC0Gap(s).maxGap / surfaceBounds(s).diagonal();
}

void addRandomForces(VertexFrameModel& m, std::mt19937& rng) {
  std::uniform_real_distribution<double> f(-3, 3), lo(0.0, 0.4), len(0.1, 0.6);
  for (std::size_t k = 0; k < m.frames.size(); k += 2) {
    const double u0 = lo(rng), v0 = lo(rng);
    m.frames[k].forces.push_back(
        {Vec3(f(rng), f(rng), f(rng)), Region{u0, u0 + len(rng), v0, v0 + len(rng)}});
  }
  m.forces.push_back({Vec3(f(rng), f(rng), f(rng)), {0}});
}

void expectExactC0(const VertexFrameModel& m, const std::string& what) {
  for (Solver solver : {Solver::Global, Solver::Local}) {
    const VertexFrameSurface s = solve(m, {solver, 0});
    EXPECT_LT(relativeGap(s), kC0RelativeTolerance)
        << what << (solver == Solver::Global ? " (global)" : " (local)");
  }
}

TEST(Continuity, ExactOnRandomGridsWithFramesInAllEightOrientations) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> size(1, 6);
  for (int trial = 0; trial < 60; ++trial) {
    LatticeOptions o;
    o.rows = size(rng);
    o.cols = size(rng);
    o.randomOrientation = true;
    o.noise = 0.15;
    o.randomParameters = true;
    VertexFrameModel m = latticeModel(o, rng);
    addRandomForces(m, rng);
    expectExactC0(m, "grid trial " + std::to_string(trial));
    // Strips do not depend on orientation: one per row and one per column.
    EXPECT_EQ(buildTopology(m).stripCount, static_cast<std::uint32_t>(o.rows + o.cols));
  }
}

TEST(Continuity, ExactOnClosedStripsAndTori) {
  std::mt19937 rng(12);
  for (int trial = 0; trial < 20; ++trial) {
    LatticeOptions o;
    // A closed loop needs 3 frames at least: with 2, two different edges would join the
    // same two corners, which a model may not have (their middles would differ).
    o.closedV = trial % 2 == 1;
    o.rows = o.closedV ? 3 + trial % 3 : 1 + trial % 4;
    o.cols = 3 + trial % 5;
    o.closedU = true;
    o.randomOrientation = true;
    o.noise = 0.1;
    o.randomParameters = true;
    VertexFrameModel m = latticeModel(o, rng);
    addRandomForces(m, rng);
    expectExactC0(m, o.closedV ? "torus" : "cylinder");
    const FrameTopology t = buildTopology(m);
    EXPECT_EQ(t.error.kind, TopologyError::Kind::None);
    EXPECT_EQ(t.stripCount, static_cast<std::uint32_t>(o.rows + o.cols));
    EXPECT_TRUE(t.orientable);
  }
}

TEST(Continuity, ExactOnABranchOfThreeFramesSharingAnEdge) {
  std::mt19937 rng(13);
  for (int trial = 0; trial < 16; ++trial) {
    VertexFrameModel m = testing::branchModel(rng, true);
    addRandomForces(m, rng);
    expectExactC0(m, "branch");
    const FrameTopology t = buildTopology(m);
    // One edge is run by all three frames, and it ties their cubics into one strip.
    std::size_t triple = 0;
    for (std::uint32_t e = 0; e < t.edges.size(); ++e)
      if (t.sides(e).size() == 3) {
        ++triple;
        const FrameSide first = t.sides(e)[0];
        const std::uint32_t strip = t.strip[first.frame][sideDirection(first.side)];
        for (const FrameSide& fs : t.sides(e))
          EXPECT_EQ(t.strip[fs.frame][sideDirection(fs.side)], strip);
      }
    EXPECT_EQ(triple, 1u);
  }
}

TEST(Continuity, CollapsedEdgesStayAPoint) {
  std::mt19937 rng(14);
  for (int sectors : {3, 4, 6, 8}) {
    VertexFrameModel m = testing::poleModel(sectors, true, rng);
    m.frames[0].a1 = {3, 0.5, 2};  // unequal parameters would bend a free pole strip
    expectExactC0(m, "pole");
    const VertexFrameSurface s = solve(m);
    for (std::uint32_t k = 0; k < m.frames.size(); ++k)
      for (int side = 0; side < 4; ++side) {
        const ModelEdge& e = s.topology->edges[s.topology->edgeOf[k][side]];
        if (!e.collapsed()) continue;
        for (double t : {0.1, 0.25, 0.5, 0.9}) {
          const auto [u, v] = sideParam(static_cast<Side>(side), t);
          EXPECT_LT((s.patches[k].position(u, v) - m.vertices[0]).norm(), 1e-14);
        }
      }
  }
}

TEST(Continuity, MobiusBandPinsItsTwistedStripAndStaysContinuous) {
  for (int segments : {3, 4, 7}) {
    const VertexFrameModel m = testing::mobiusModel(segments);
    const FrameTopology t = buildTopology(m);
    EXPECT_FALSE(t.orientable);
    // The strip across the band's width is glued to itself reversed: pinned.
    std::size_t pinned = 0;
    for (auto p : t.stripPinned) pinned += p;
    EXPECT_GE(pinned, 1u);
    expectExactC0(m, "mobius");
  }
}

/// Σ over patches, components and a uniform grid of (a1 S_uu + a2 S_vv)² of the
/// homogeneous parts: the quantity the global solver minimises.
double summedResidual(const VertexFrameModel& m, const std::vector<VertexFramePatch>& patches) {
  double sum = 0;
  const int n = 5;
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const auto& c = patches[k].c;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double u = i / (n - 1.0), v = j / (n - 1.0);
        const Vec3 suu = 2 * c[2] + 6 * u * c[3] + 2 * v * c[8];
        const Vec3 svv = 2 * c[5] + 6 * v * c[6] + 2 * u * c[9];
        sum += (m.frames[k].a1.array() * suu.array() + m.frames[k].a2.array() * svv.array())
                   .matrix()
                   .squaredNorm();
      }
  }
  return sum;
}

TEST(GlobalSolver, IsAMinimumOfTheSummedResidual) {
  std::mt19937 rng(15);
  for (int trial = 0; trial < 10; ++trial) {
    LatticeOptions o;
    o.rows = 2 + trial % 3;
    o.cols = 3;
    o.closedU = trial % 2 == 0;
    o.randomOrientation = true;
    o.noise = 0.3;
    o.randomParameters = true;
    const VertexFrameModel m = latticeModel(o, rng);
    const VertexFrameSurface s = solve(m);
    const double best = summedResidual(m, s.patches);
    const FrameTopology& t = *s.topology;
    for (std::uint32_t strip = 0; strip < t.stripCount; ++strip)
      for (int comp = 0; comp < 3; ++comp)
        for (double delta : {-1e-3, 1e-3}) {
          std::vector<VertexFramePatch> moved = s.patches;
          for (std::uint32_t k = 0; k < m.frames.size(); ++k) {
            std::array<Vec3, 8> p;
            for (int i = 0; i < 8; ++i) p[i] = m.vertices[m.frames[k].vertices[i]];
            Vec3 c3 = s.patches[k].c[3], c6 = s.patches[k].c[6];
            if (t.strip[k][0] == strip) c3[comp] += t.parity[k][0] * delta;
            if (t.strip[k][1] == strip) c6[comp] += t.parity[k][1] * delta;
            moved[k].c = patchCoefficients(p, c3, c6);
          }
          EXPECT_GT(summedResidual(m, moved), best) << "strip " << strip << " comp " << comp;
        }
  }
}

TEST(GlobalSolver, DoesNotDependOnFrameOrder) {
  std::mt19937 rng(16);
  LatticeOptions o;
  o.rows = 4;
  o.cols = 5;
  o.randomOrientation = true;
  o.noise = 0.2;
  o.randomParameters = true;
  VertexFrameModel m = latticeModel(o, rng);
  VertexFrameModel r = m;
  std::reverse(r.frames.begin(), r.frames.end());
  const VertexFrameSurface a = solve(m), b = solve(r);
  const std::size_t n = m.frames.size();
  for (std::size_t k = 0; k < n; ++k)
    for (int i = 0; i < 10; ++i)
      EXPECT_LT((a.patches[k].c[i] - b.patches[n - 1 - k].c[i]).norm(), 1e-12);
}

/// Scaling a1 and a2 together does not change the PDE's solution; the solvers must not
/// overflow or underflow on the way (a1 = a2 = 1e155 squared is infinite, 1e-170 is 0).
TEST(Solvers, AreInvariantToScalingA1AndA2TogetherOverTheWholeDoubleRange) {
  std::mt19937 rng(19);
  LatticeOptions o;
  o.rows = 3;
  o.cols = 4;
  o.closedU = true;
  o.randomOrientation = true;
  o.noise = 0.2;
  o.randomParameters = true;
  const VertexFrameModel m = latticeModel(o, rng);
  for (Solver solver : {Solver::Global, Solver::Local}) {
    const VertexFrameSurface reference = solve(m, {solver, 0});
    for (double scale : {1e155, 1e-170, 1e300, 1e-300}) {
      VertexFrameModel scaled = m;
      for (Frame& f : scaled.frames) {
        f.a1 *= scale;
        f.a2 *= scale;
      }
      const VertexFrameSurface s = solve(scaled, {solver, 0});
      EXPECT_TRUE(s.notes.empty()) << scale;
      for (std::size_t k = 0; k < m.frames.size(); ++k)
        for (int i = 0; i < 10; ++i)
          EXPECT_LT((s.patches[k].c[i] - reference.patches[k].c[i]).norm(), 1e-12)
              << "scale " << scale << " frame " << k;
    }
  }
}

/// The seed's patch generation rule (§3.2.1) on a 3×3 model: the centre patch solves its
/// own least squares; each edge patch inherits one cubic from the centre and solves the
/// other; the corner patches solve nothing and inherit both from the edge patches.
TEST(LocalSolver, ReproducesTheSeedsCentreEdgeCornerRule) {
  std::mt19937 rng(17);
  LatticeOptions o;
  o.noise = 0.3;
  o.randomParameters = true;
  const VertexFrameModel m = latticeModel(o, rng);  // frame (r, c) = 3r + c, u along c
  const VertexFrameSurface s = solve(m, {Solver::Local, 4});
  auto single = [&](int k) {
    std::array<Vec3, 8> p;
    for (int i = 0; i < 8; ++i) p[i] = m.vertices[m.frames[k].vertices[i]];
    return singlePatchCubics(p, m.frames[k].a1, m.frames[k].a2);
  };
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int k = 3 * r + c;
      // C3 runs along columns (shared across the u-edges α/β), decided by row 1;
      // C6 runs along rows, decided by column 1.
      EXPECT_LT((s.patches[k].c[3] - single(3 + c)[0]).norm(), 1e-13) << "frame " << k;
      EXPECT_LT((s.patches[k].c[6] - single(3 * r + 1)[1]).norm(), 1e-13) << "frame " << k;
    }
  // And it differs from the global solution (which averages over each strip).
  const VertexFrameSurface g = solve(m);
  EXPECT_GT((g.patches[0].c[3] - s.patches[0].c[3]).norm(), 1e-6);
}

TEST(LocalSolver, SeedFrameDecidesItsOwnStrips) {
  std::mt19937 rng(18);
  LatticeOptions o;
  o.rows = 4;
  o.cols = 4;
  o.randomOrientation = true;
  o.noise = 0.3;
  o.randomParameters = true;
  const VertexFrameModel m = latticeModel(o, rng);
  for (std::uint32_t seed : {0u, 5u, 15u}) {
    const VertexFrameSurface s = solve(m, {Solver::Local, seed});
    std::array<Vec3, 8> p;
    for (int i = 0; i < 8; ++i) p[i] = m.vertices[m.frames[seed].vertices[i]];
    const auto own = singlePatchCubics(p, m.frames[seed].a1, m.frames[seed].a2);
    EXPECT_LT((s.patches[seed].c[3] - own[0]).norm(), 1e-13);
    EXPECT_LT((s.patches[seed].c[6] - own[1]).norm(), 1e-13);
  }
}

}  // namespace
}  // namespace pdesurf
