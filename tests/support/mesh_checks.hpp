// Structural checks of triangle meshes shared by the test suites.
#pragma once

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "pdesurf/mesh.hpp"

namespace pdesurf::testing {

struct EdgeStats {
  std::size_t edges = 0;                        ///< undirected edges
  std::size_t boundaryEdges = 0;                ///< used by one triangle
  std::size_t nonManifoldEdges = 0;             ///< used by three or more
  std::size_t inconsistentlyOrientedEdges = 0;  ///< two triangles run it the same way
};

inline EdgeStats edgeStats(const Mesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<int, int>> uses;  // forward, back
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t a = mesh.indices[3 * t + c], b = mesh.indices[3 * t + (c + 1) % 3];
      auto& u = uses[{std::min(a, b), std::max(a, b)}];
      (a < b ? u.first : u.second) += 1;
    }
  EdgeStats s;
  s.edges = uses.size();
  for (const auto& [e, u] : uses) {
    const int total = u.first + u.second;
    if (total == 1) ++s.boundaryEdges;
    if (total >= 3) ++s.nonManifoldEdges;
    if (total == 2 && u.first != 1) ++s.inconsistentlyOrientedEdges;
  }
  return s;
}

/// Vertices at exactly the same position as an earlier one (cracks in disguise).
inline std::size_t duplicatePositions(const Mesh& mesh) {
  std::set<std::tuple<float, float, float>> seen;
  std::size_t dup = 0;
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
    if (!seen.insert({mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]})
             .second)
      ++dup;
  return dup;
}

/// A lower bound for minCornerNormalAgreement that means "no normal points backwards": every
/// corner normal within 90° of its triangle's normal. Tighter bounds belong to tests of
/// surfaces known to be smooth. The examples' worst at 9 samples per patch side is 76°
/// (cosine 0.235): the mug, at a vertex where five patches meet across C0 creases and the
/// normal is their average (75° still at 33 samples); next the sculpt, 74° (cosine 0.269), on
/// the border of a force region, a kink inside one patch (53° at 17 samples).
inline constexpr double kNoBackwardNormals = 0.0;

/// The smallest cosine between a non-degenerate triangle's normal and its corners' normals.
inline double minCornerNormalAgreement(const Mesh& mesh) {
  double worst = 1.0;
  auto pos = [&](std::uint32_t v) {
    return Eigen::Vector3d(mesh.positions[3 * v], mesh.positions[3 * v + 1],
                           mesh.positions[3 * v + 2]);
  };
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const std::uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1],
                        c = mesh.indices[3 * t + 2];
    const Eigen::Vector3d fn = (pos(b) - pos(a)).cross(pos(c) - pos(a));
    if (fn.norm() < 1e-12) continue;
    for (std::uint32_t v : {a, b, c}) {
      const Eigen::Vector3d n(mesh.normals[3 * v], mesh.normals[3 * v + 1],
                              mesh.normals[3 * v + 2]);
      worst = std::min(worst, fn.normalized().dot(n));
    }
  }
  return worst;
}

}  // namespace pdesurf::testing
