// Synthetic vertex-frame models for tests: grids, cylinders, tori, branches, poles, with
// frames in any of the 8 orientations of the square.
#pragma once

#include <random>

#include "pdesurf/vertex_frames.hpp"

namespace pdesurf::testing {

/// Re-lists a frame's ring of 8 slots in one of the 8 symmetries of the square:
/// `rotation` quarter turns (0..3), then a mirror (which swaps u and v) if `mirror`.
inline std::array<std::uint32_t, 8> reorient(const std::array<std::uint32_t, 8>& ring, int rotation,
                                             bool mirror) {
  std::array<std::uint32_t, 8> out{};
  for (int i = 0; i < 8; ++i) {
    const int from = mirror ? (8 - i) % 8 : i;
    out[i] = ring[(from + 2 * rotation) % 8];
  }
  return out;
}

struct LatticeOptions {
  int rows = 3, cols = 3;  ///< frames along v and along u
  bool closedU = false;    ///< wrap the columns (a cylinder)
  bool closedV = false;    ///< wrap the rows as well (a torus)
  bool randomOrientation = false;
  double noise = 0.0;             ///< random displacement of the vertices
  bool randomParameters = false;  ///< random a1, a2 per frame, positive
};

/// A (2 rows + 1) × (2 cols + 1) lattice of vertices on a plane, cylinder or torus,
/// frames over 2×2 blocks of it.
inline VertexFrameModel latticeModel(const LatticeOptions& o, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const int nu = 2 * o.cols + (o.closedU ? 0 : 1);
  const int nv = 2 * o.rows + (o.closedV ? 0 : 1);
  VertexFrameModel m;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double s = static_cast<double>(i) / (2 * o.cols);
      const double t = static_cast<double>(j) / (2 * o.rows);
      Vec3 p;
      if (o.closedV) {  // torus
        const double a = 2 * M_PI * s, b = 2 * M_PI * t;
        p = {(3 + std::cos(b)) * std::cos(a), (3 + std::cos(b)) * std::sin(a), std::sin(b)};
      } else if (o.closedU) {  // cylinder
        const double a = 2 * M_PI * s;
        p = {2 * std::cos(a), 2 * std::sin(a), 3 * t};
      } else {
        p = {3 * s, 3 * t, 0.3 * std::sin(3 * s) * std::cos(2 * t)};
      }
      p += o.noise * Vec3(unit(rng), unit(rng), unit(rng));
      m.vertices.push_back(p);
    }
  auto at = [&](int i, int j) { return static_cast<std::uint32_t>((j % nv) * nu + (i % nu)); };
  std::uniform_int_distribution<int> rot(0, 3), coin(0, 1);
  std::uniform_real_distribution<double> param(0.3, 3.0);
  for (int r = 0; r < o.rows; ++r)
    for (int c = 0; c < o.cols; ++c) {
      const int i = 2 * c, j = 2 * r;
      std::array<std::uint32_t, 8> ring = {at(i, j),         at(i + 1, j),     at(i + 2, j),
                                           at(i + 2, j + 1), at(i + 2, j + 2), at(i + 1, j + 2),
                                           at(i, j + 2),     at(i, j + 1)};
      Frame f;
      f.vertices = o.randomOrientation ? reorient(ring, rot(rng), coin(rng) == 1) : ring;
      if (o.randomParameters) {
        f.a1 = {param(rng), param(rng), param(rng)};
        f.a2 = {param(rng), param(rng), param(rng)};
      }
      m.frames.push_back(f);
    }
  return m;
}

/// Three frames sharing one edge (a fin on a sheet): a non-manifold branch.
inline VertexFrameModel branchModel(std::mt19937& rng, bool randomOrientation) {
  std::uniform_int_distribution<int> rot(0, 3), coin(0, 1);
  VertexFrameModel m;
  // The shared edge: vertices 0, 1, 2 along x.
  m.vertices = {{0, 0, 0},  {1, 0, 0},    {2, 0, 0},                              // shared edge
                {2, 1, 0},  {2, 2, 0.2},  {1, 2, 0.1}, {0, 2, 0},    {0, 1, 0},   // sheet +y
                {2, -1, 0}, {2, -2, 0.1}, {1, -2, 0},  {0, -2, 0.2}, {0, -1, 0},  // sheet -y
                {2, 0, 1},  {2, 0.1, 2},  {1, 0, 2.2}, {0, 0.1, 2},  {0, 0, 1}};  // fin +z
  std::vector<std::array<std::uint32_t, 8>> rings = {
      {0, 1, 2, 3, 4, 5, 6, 7}, {2, 1, 0, 12, 11, 10, 9, 8}, {0, 1, 2, 13, 14, 15, 16, 17}};
  for (auto& r : rings) {
    Frame f;
    f.vertices = randomOrientation ? reorient(r, rot(rng), coin(rng) == 1) : r;
    m.frames.push_back(f);
  }
  return m;
}

/// A closed cap: `sectors` frames around a pole, each with its inner edge collapsed to
/// the pole vertex 0, under a ring that is shared around.
inline VertexFrameModel poleModel(int sectors, bool randomOrientation, std::mt19937& rng) {
  std::uniform_int_distribution<int> rot(0, 3), coin(0, 1);
  VertexFrameModel m;
  m.vertices.push_back({0, 0, 1});
  // Ring at radius 0.5 (middles of the radial edges) and 1 (outer), 2 per sector.
  const int n = 2 * sectors;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    m.vertices.push_back({0.5 * std::cos(a), 0.5 * std::sin(a), 0.8});
  }
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    m.vertices.push_back({std::cos(a), std::sin(a), 0.2 * std::cos(3 * a)});
  }
  auto mid = [&](int i) { return static_cast<std::uint32_t>(1 + (i % n)); };
  auto out = [&](int i) { return static_cast<std::uint32_t>(1 + n + (i % n)); };
  for (int s = 0; s < sectors; ++s) {
    const int i = 2 * s;
    // P1..P3 collapsed at the pole, P3→P5 radial, P5 P6 P7 on the outer ring, P7→P1 radial.
    std::array<std::uint32_t, 8> ring = {0,          0,          0,      mid(i + 2),
                                         out(i + 2), out(i + 1), out(i), mid(i)};
    Frame f;
    f.vertices = randomOrientation ? reorient(ring, rot(rng), coin(rng) == 1) : ring;
    m.frames.push_back(f);
  }
  return m;
}

/// A Möbius band: a strip of frames whose ends are glued with a half twist.
inline VertexFrameModel mobiusModel(int segments) {
  VertexFrameModel m;
  const int n = 2 * segments;
  for (int i = 0; i < n; ++i)
    for (int w = -1; w <= 1; ++w) {
      const double a = 2 * M_PI * i / n;
      const double h = 0.5 * w;
      m.vertices.push_back({(2 + h * std::cos(a / 2)) * std::cos(a),
                            (2 + h * std::cos(a / 2)) * std::sin(a), h * std::sin(a / 2)});
    }
  auto at = [&](int i, int w) -> std::uint32_t {
    if (i >= n) return static_cast<std::uint32_t>(3 * (i - n) + (2 - w));  // the twist
    return static_cast<std::uint32_t>(3 * i + w);
  };
  for (int s = 0; s < segments; ++s) {
    const int i = 2 * s;
    Frame f;
    f.vertices = {at(i, 0),     at(i + 1, 0), at(i + 2, 0), at(i + 2, 1),
                  at(i + 2, 2), at(i + 1, 2), at(i, 2),     at(i, 1)};
    m.frames.push_back(f);
  }
  return m;
}

/// Two frames over the same eight vertices, one mirrored, pushed apart by opposite forces:
/// a closed pillow (both frames share both sides at every corner).
inline VertexFrameModel pillowModel() {
  VertexFrameModel m;
  m.vertices = {{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {1, 0.5, 0},
                {1, 1, 0}, {0.5, 1, 0}, {0, 1, 0}, {0, 0.5, 0}};
  Frame top, bottom;
  top.vertices = {0, 1, 2, 3, 4, 5, 6, 7};
  top.forces.push_back({Vec3(0, 0, 10), Region{}});
  bottom.vertices = {0, 7, 6, 5, 4, 3, 2, 1};
  bottom.forces.push_back({Vec3(0, 0, -10), Region{}});
  m.frames = {top, bottom};
  return m;
}

}  // namespace pdesurf::testing
