// A torus mesh with known geometry (genus 1) for the automatic layout's tests.
#pragma once

#include <cmath>
#include <cstdint>

#include "support/test_meshes.hpp"

namespace pdesurf::testing {

/// A torus round the z axis: tube radius r about a circle of radius R, `around` × `across`
/// quads (two triangles each), oriented outwards.
inline Mesh torusMesh(double R, double r, int around, int across) {
  MeshBuilder b;
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      const double a = 2 * M_PI * i / around, t = 2 * M_PI * j / across;
      b.vertex((R + r * std::cos(t)) * std::cos(a), (R + r * std::cos(t)) * std::sin(a),
               r * std::sin(t));
    }
  auto at = [&](int i, int j) {
    return static_cast<std::uint32_t>((i % around) * across + j % across);
  };
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) b.quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  return b.mesh();
}

}  // namespace pdesurf::testing
