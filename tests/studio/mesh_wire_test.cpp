// The studio's binary mesh stream (apps/studio/mesh_wire.hpp), decoded without HTTP.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "mesh_wire.hpp"

namespace pdesurf::studio {
namespace {

/// A strip of `n` vertices (positions i, 2i, 3i; normals 0, 0, 1) and n − 2 triangles.
Mesh strip(std::uint32_t n) {
  Mesh m;
  for (std::uint32_t i = 0; i < n; ++i) {
    m.positions.insert(m.positions.end(), {float(i), float(2 * i), float(3 * i)});
    m.normals.insert(m.normals.end(), {0.0f, 0.0f, 1.0f});
  }
  for (std::uint32_t i = 0; i + 2 < n; ++i) m.indices.insert(m.indices.end(), {i, i + 1, i + 2});
  return m;
}

template <class T>
std::vector<T> read(const std::string& bytes, std::size_t& at, std::size_t count) {
  std::vector<T> out(count);
  EXPECT_LE(at + count * sizeof(T), bytes.size());
  std::memcpy(out.data(), bytes.data() + at, count * sizeof(T));
  at += count * sizeof(T);
  return out;
}

TEST(MeshWire, AWholeMeshDecodesToItsBuffers) {
  const Mesh m = strip(5);
  const std::string bytes = encodeMesh(m, (std::uint64_t{1} << 32) + 7, 17);
  std::size_t at = 0;
  const auto header = read<std::uint32_t>(bytes, at, 4);
  EXPECT_EQ(header, (std::vector<std::uint32_t>{5, 3, 7, 17}));  // revision mod 2^32
  EXPECT_EQ(read<float>(bytes, at, 15), std::vector<float>(m.positions.begin(), m.positions.end()));
  EXPECT_EQ(read<float>(bytes, at, 15), std::vector<float>(m.normals.begin(), m.normals.end()));
  EXPECT_EQ(read<std::uint32_t>(bytes, at, 9),
            std::vector<std::uint32_t>(m.indices.begin(), m.indices.end()));
  EXPECT_EQ(at, bytes.size());
}

/// `from` with the delta applied, as the page does it.
Mesh applyDelta(Mesh from, const std::string& bytes) {
  std::size_t at = 0;
  const auto header = read<std::uint32_t>(bytes, at, 5);
  EXPECT_EQ(header[0], from.vertexCount());
  const auto runs = read<std::uint32_t>(bytes, at, 2 * header[4]);
  for (auto* buffer : {&from.positions, &from.normals})
    for (std::size_t r = 0; r < runs.size(); r += 2) {
      const auto values = read<float>(bytes, at, 3 * std::size_t{runs[r + 1]});
      std::copy(values.begin(), values.end(), buffer->begin() + 3 * std::size_t{runs[r]});
    }
  EXPECT_EQ(at, bytes.size());
  return from;
}

TEST(MeshWire, ADeltaTurnsTheOldMeshIntoTheNewOne) {
  const Mesh from = strip(40);
  Mesh to = from;
  to.positions[3 * 2] = 100.0f;      // vertex 2
  to.normals[3 * 5 + 1] = 0.5f;      // vertex 5: within kDeltaRunGap of 2, one run
  to.positions[3 * 30 + 2] = -1.0f;  // vertex 30: a run of its own
  const std::vector<std::uint32_t> runs = changedRuns(from, to);
  EXPECT_EQ(runs, (std::vector<std::uint32_t>{2, 4, 30, 1}));
  const Mesh applied = applyDelta(from, encodeMeshDelta(from, to, 3, 9));
  EXPECT_EQ(applied.positions, to.positions);
  EXPECT_EQ(applied.normals, to.normals);
  EXPECT_TRUE(changedRuns(to, to).empty());
}

}  // namespace
}  // namespace pdesurf::studio
