// Triangle meshes with known geometry for the mesh-analysis tests: cylinders, spheres, boxes,
// all closed ones oriented outwards (counter-clockwise seen from outside).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "pdesurf/mesh.hpp"

namespace pdesurf::testing {

/// Builds a Mesh from double positions (stored as float, as every Mesh is).
class MeshBuilder {
 public:
  std::uint32_t vertex(double x, double y, double z) {
    mesh_.positions.insert(mesh_.positions.end(),
                           {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)});
    return static_cast<std::uint32_t>(mesh_.vertexCount() - 1);
  }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    mesh_.indices.insert(mesh_.indices.end(), {a, b, c});
  }
  /// Two triangles over the quad a b c d (counter-clockwise).
  void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    triangle(a, b, c);
    triangle(a, c, d);
  }
  Mesh mesh() const { return mesh_; }

 private:
  Mesh mesh_;
};

struct CylinderOptions {
  double radius = 1.0, height = 2.0;
  int segments = 64;     ///< vertices per ring, the first at angle 0
  int rings = 4;         ///< bands between z = 0 and z = height (rings + 1 vertex rings)
  bool caps = true;      ///< close the ends with fans round a centre vertex
  int slitSegments = 0;  ///< leave out this many bands of quads (an open, slit tube)
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
};

/// A cylinder round the z axis (shifted by `offset`), its side made of planar quads.
inline Mesh cylinderMesh(const CylinderOptions& o) {
  MeshBuilder b;
  const int n = o.segments;
  std::vector<std::uint32_t> ring((o.rings + 1) * n);
  for (int i = 0; i <= o.rings; ++i)
    for (int j = 0; j < n; ++j) {
      const double a = 2 * M_PI * j / n;
      ring[i * n + j] =
          b.vertex(o.offset.x() + o.radius * std::cos(a), o.offset.y() + o.radius * std::sin(a),
                   o.offset.z() + o.height * i / o.rings);
    }
  for (int i = 0; i < o.rings; ++i)
    for (int j = 0; j + o.slitSegments < n; ++j) {
      const int k = (j + 1) % n;
      b.quad(ring[i * n + j], ring[i * n + k], ring[(i + 1) * n + k], ring[(i + 1) * n + j]);
    }
  if (o.caps) {
    const std::uint32_t bottom = b.vertex(o.offset.x(), o.offset.y(), o.offset.z());
    const std::uint32_t top = b.vertex(o.offset.x(), o.offset.y(), o.offset.z() + o.height);
    for (int j = 0; j < n; ++j) {
      const int k = (j + 1) % n;
      b.triangle(bottom, ring[k], ring[j]);
      b.triangle(top, ring[o.rings * n + j], ring[o.rings * n + k]);
    }
  }
  return b.mesh();
}

/// A latitude-longitude sphere of `radius` round the origin: poles on the z axis, `rings`
/// bands of latitude (an even count puts a ring on the equator), `segments` vertices per ring.
inline Mesh sphereMesh(double radius, int segments, int rings) {
  MeshBuilder b;
  const std::uint32_t south = b.vertex(0, 0, -radius);
  std::vector<std::uint32_t> ring((rings - 1) * segments);
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double phi = -M_PI / 2 + M_PI * i / rings, a = 2 * M_PI * j / segments;
      ring[(i - 1) * segments + j] =
          b.vertex(radius * std::cos(phi) * std::cos(a), radius * std::cos(phi) * std::sin(a),
                   radius * std::sin(phi));
    }
  const std::uint32_t north = b.vertex(0, 0, radius);
  for (int j = 0; j < segments; ++j) {
    const int k = (j + 1) % segments;
    b.triangle(south, ring[k], ring[j]);
    for (int i = 0; i + 2 < rings; ++i)
      b.quad(ring[i * segments + j], ring[i * segments + k], ring[(i + 1) * segments + k],
             ring[(i + 1) * segments + j]);
    b.triangle(north, ring[(rings - 2) * segments + j], ring[(rings - 2) * segments + k]);
  }
  return b.mesh();
}

/// The box [lo, hi], two triangles per face.
inline Mesh boxMesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  MeshBuilder b;
  std::uint32_t v[8];
  for (int i = 0; i < 8; ++i)
    v[i] = b.vertex(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  b.quad(v[0], v[2], v[3], v[1]);  // z = lo
  b.quad(v[4], v[5], v[7], v[6]);  // z = hi
  b.quad(v[0], v[1], v[5], v[4]);  // y = lo
  b.quad(v[2], v[6], v[7], v[3]);  // y = hi
  b.quad(v[0], v[4], v[6], v[2]);  // x = lo
  b.quad(v[1], v[3], v[7], v[5]);  // x = hi
  return b.mesh();
}

/// The cube [-1, 1]³ with its six faces bulging outwards by h (1 - s²)(1 - t²) (s, t the
/// face's other two coordinates), n × n quads a face, closed and welded: its faces are
/// smooth, its twelve edges creases where the faces' normals meet at 90° - 2 atan(2h (1 - t²))
/// (t along the edge: 90° at the corners).
inline Mesh pillowCubeMesh(int n, double h) {
  MeshBuilder b;
  std::vector<std::int64_t> index((n + 1) * (n + 1) * (n + 1), -1);
  auto vertex = [&](std::array<int, 3> g) {
    std::int64_t& v = index[(g[2] * (n + 1) + g[1]) * (n + 1) + g[0]];
    if (v < 0) {
      std::array<double, 3> p;
      for (int a = 0; a < 3; ++a) p[a] = -1.0 + 2.0 * g[a] / n;
      std::array<double, 3> q = p;
      // On an edge or a corner every bulge is 0: another coordinate is ±1 there.
      for (int a = 0; a < 3; ++a)
        if (g[a] == 0 || g[a] == n)
          q[a] += p[a] * h * (1 - p[(a + 1) % 3] * p[(a + 1) % 3]) *
                  (1 - p[(a + 2) % 3] * p[(a + 2) % 3]);
      v = b.vertex(q[0], q[1], q[2]);
    }
    return static_cast<std::uint32_t>(v);
  };
  for (int a = 0; a < 3; ++a)
    for (int side : {0, n}) {
      const int u = (a + 1) % 3, w = (a + 2) % 3;  // e_u × e_w = e_a
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          std::array<int, 3> g00{}, g10{}, g11{}, g01{};
          for (auto* g : {&g00, &g10, &g11, &g01}) (*g)[a] = side;
          g00[u] = i, g00[w] = j, g10[u] = i + 1, g10[w] = j;
          g11[u] = i + 1, g11[w] = j + 1, g01[u] = i, g01[w] = j + 1;
          if (side == n)  // counter-clockwise seen from outside
            b.quad(vertex(g00), vertex(g10), vertex(g11), vertex(g01));
          else
            b.quad(vertex(g00), vertex(g01), vertex(g11), vertex(g10));
        }
    }
  return b.mesh();
}

/// `mesh` with every position scaled by `s` about the origin.
inline Mesh scaled(Mesh mesh, double s) {
  for (float& x : mesh.positions) x = static_cast<float>(x * s);
  return mesh;
}

/// The two meshes as one (b's indices shifted past a's vertices).
inline Mesh merged(const Mesh& a, const Mesh& b) {
  Mesh m = a;
  m.normals.clear();
  m.patchIds.clear();
  const auto shift = static_cast<std::uint32_t>(a.vertexCount());
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  for (std::uint32_t i : b.indices) m.indices.push_back(i + shift);
  return m;
}

}  // namespace pdesurf::testing
