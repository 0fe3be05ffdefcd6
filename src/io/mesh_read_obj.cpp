// OBJ meshes: v, vn and f records (corners v, v/t, v//n, v/t/n; negative indices count back),
// polygons fanned into triangles, normals kept when every corner pairs a vertex with one normal.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "io/mesh_read.hpp"
#include "io/mesh_text.hpp"

namespace pdesurf::detail {

namespace {

/// The 0-based index that OBJ index `raw` (1-based, or negative counting back) denotes, of
/// one of the `defined` vertices (or normals) so far.
std::uint32_t resolveObjIndex(std::int64_t raw, std::size_t defined, const Tokenizer& tokens,
                              bool normal, std::size_t face) {
  const std::int64_t count = static_cast<std::int64_t>(defined);
  const std::int64_t index = raw > 0 ? raw - 1 : count + raw;
  if (raw == 0 || index < 0 || index >= count)
    tokens.fail("face {} refers to {} {} but only {} {} defined before it", face,
                normal ? "normal" : "vertex", raw, defined,
                normal ? (defined == 1 ? "normal is" : "normals are")
                       : (defined == 1 ? "vertex is" : "vertices are"));
  return static_cast<std::uint32_t>(index);
}

}  // namespace

Mesh readObj(const std::string& text, const std::string& path) {
  Tokenizer tokens(text, path, '#');
  Mesh mesh;
  std::vector<float> normals;
  constexpr std::int64_t kNone = -1;
  std::vector<std::int64_t> normalOf;  // per vertex, the normal every corner pairs it with
  bool normalsConsistent = true;
  std::vector<std::uint32_t> corners;
  std::size_t faceCount = 0;
  while (!tokens.atEnd()) {
    const std::string_view keyword = tokens.onLine();
    if (keyword == "v") {
      const Where where{"vertex", mesh.vertexCount()};
      for (int k = 0; k < 3; ++k) mesh.positions.push_back(tokens.numberOnLine<float>(where));
    } else if (keyword == "vn") {
      const Where where{"normal", normals.size() / 3};
      for (int k = 0; k < 3; ++k) normals.push_back(tokens.numberOnLine<float>(where));
    } else if (keyword == "f") {
      corners.clear();
      for (std::string_view corner = tokens.onLine(); !corner.empty(); corner = tokens.onLine()) {
        // v, v/vt, v//vn or v/vt/vn.
        const auto index = [&](std::string_view part) {
          const std::optional<std::int64_t> value = parseNumber<std::int64_t>(part);
          if (!value) tokens.fail("malformed corner '{}' in face {}", corner, faceCount);
          return *value;
        };
        const std::size_t slash = corner.find('/');
        const std::size_t slash2 =
            slash == std::string_view::npos ? slash : corner.find('/', slash + 1);
        const std::uint32_t vertex = resolveObjIndex(index(corner.substr(0, slash)),
                                                     mesh.vertexCount(), tokens, false, faceCount);
        corners.push_back(vertex);
        if (slash != std::string_view::npos && slash2 != slash + 1)
          index(corner.substr(slash + 1, slash2 - slash - 1));  // the texture coordinate
        if (slash2 == std::string_view::npos) {
          normalsConsistent = false;
          continue;
        }
        const std::uint32_t normal = resolveObjIndex(index(corner.substr(slash2 + 1)),
                                                     normals.size() / 3, tokens, true, faceCount);
        if (normalsConsistent) {
          normalOf.resize(mesh.vertexCount(), kNone);
          if (normalOf[vertex] == kNone) normalOf[vertex] = normal;
          normalsConsistent = normalOf[vertex] == normal;
        }
      }
      if (corners.size() < 3) tokens.fail("face {} has {} corners", faceCount, corners.size());
      appendFan(corners, mesh.indices);
      ++faceCount;
    }
    tokens.nextLine();  // Other statements (vt, g, o, s, usemtl, l, ...) are ignored.
  }
  // Per-vertex normals when every corner pairs its vertex with one normal; vertices no face
  // uses take the normal of the same number.
  if (normalsConsistent && !normals.empty()) {
    normalOf.resize(mesh.vertexCount(), kNone);
    mesh.normals.reserve(mesh.positions.size());
    for (std::size_t v = 0; v < normalOf.size() && normalsConsistent; ++v) {
      const std::int64_t n = normalOf[v] != kNone ? normalOf[v] : static_cast<std::int64_t>(v);
      normalsConsistent = static_cast<std::size_t>(n) < normals.size() / 3;
      if (normalsConsistent)
        mesh.normals.insert(mesh.normals.end(), normals.begin() + 3 * n,
                            normals.begin() + 3 * n + 3);
    }
    if (!normalsConsistent) mesh.normals.clear();
  }
  return mesh;
}

}  // namespace pdesurf::detail
