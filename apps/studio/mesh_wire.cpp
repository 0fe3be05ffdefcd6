// The studio's binary mesh stream (mesh_wire.hpp).
#include "mesh_wire.hpp"

#include <bit>
#include <cstring>

namespace pdesurf::studio {

std::string encodeMesh(const Mesh& mesh, std::uint64_t revision, std::uint32_t resolution) {
  static_assert(std::endian::native == std::endian::little,
                "the mesh stream is little-endian; add byte swapping for this machine");
  const std::size_t v = mesh.vertexCount(), t = mesh.triangleCount();
  std::string body(16 + 4 * (6 * v + 3 * t), '\0');
  char* out = body.data();
  const std::uint32_t header[4] = {static_cast<std::uint32_t>(v), static_cast<std::uint32_t>(t),
                                   static_cast<std::uint32_t>(revision & 0xffffffffu), resolution};
  std::memcpy(out, header, sizeof header);
  out += sizeof header;
  std::memcpy(out, mesh.positions.data(), 12 * v);
  out += 12 * v;
  if (mesh.normals.size() == 3 * v) std::memcpy(out, mesh.normals.data(), 12 * v);
  out += 12 * v;
  std::memcpy(out, mesh.indices.data(), 12 * t);
  return body;
}

std::vector<std::uint32_t> changedRuns(const Mesh& from, const Mesh& to) {
  const std::size_t v = to.vertexCount();
  const bool normals = to.normals.size() == 3 * v;
  const auto differs = [&](std::size_t i) {
    return std::memcmp(&from.positions[3 * i], &to.positions[3 * i], 12) != 0 ||
           (normals && std::memcmp(&from.normals[3 * i], &to.normals[3 * i], 12) != 0);
  };
  std::vector<std::uint32_t> runs;  // start, count, start, count, ...
  for (std::size_t i = 0; i < v; ++i) {
    if (!differs(i)) continue;
    std::size_t end = i + 1;
    for (std::size_t gap = 0; end < v && gap <= kDeltaRunGap; ++end)
      gap = differs(end) ? 0 : gap + 1;
    while (end > i + 1 && !differs(end - 1)) --end;
    if (!runs.empty() && i - (runs[runs.size() - 2] + runs.back()) <= kDeltaRunGap) {
      runs.back() = static_cast<std::uint32_t>(end - runs[runs.size() - 2]);
    } else {
      runs.push_back(static_cast<std::uint32_t>(i));
      runs.push_back(static_cast<std::uint32_t>(end - i));
    }
    i = end - 1;
  }
  return runs;
}

std::string encodeMeshDelta(const Mesh& from, const Mesh& to, std::uint64_t revision,
                            std::uint32_t resolution) {
  const std::vector<std::uint32_t> runs = changedRuns(from, to);
  std::size_t changed = 0;
  for (std::size_t r = 1; r < runs.size(); r += 2) changed += runs[r];
  std::string body(20 + 4 * runs.size() + 24 * changed, '\0');
  char* out = body.data();
  const std::uint32_t header[5] = {static_cast<std::uint32_t>(to.vertexCount()),
                                   static_cast<std::uint32_t>(to.triangleCount()),
                                   static_cast<std::uint32_t>(revision & 0xffffffffu), resolution,
                                   static_cast<std::uint32_t>(runs.size() / 2)};
  std::memcpy(out, header, sizeof header);
  out += sizeof header;
  std::memcpy(out, runs.data(), 4 * runs.size());
  out += 4 * runs.size();
  const bool normals = to.normals.size() == to.positions.size();
  for (const auto* buffer : {&to.positions, &to.normals})
    for (std::size_t r = 0; r < runs.size(); r += 2) {
      const std::size_t bytes = 12 * std::size_t{runs[r + 1]};
      if (buffer == &to.positions || normals)
        std::memcpy(out, buffer->data() + 3 * std::size_t{runs[r]}, bytes);
      out += bytes;
    }
  return body;
}

}  // namespace pdesurf::studio
