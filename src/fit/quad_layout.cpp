// A quad mesh as a vertex-frame layout: one frame per quad, one midpoint vertex per edge.
#include <algorithm>
#include <filesystem>
#include <limits>
#include <map>
#include <utility>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>
#include <fmt/format.h>

#include "pdesurf/rebuild.hpp"

namespace pdesurf {

PolygonMesh readPolygonMesh(const std::string& path) {
  using Point = CGAL::Simple_cartesian<double>::Point_3;
  if (!std::filesystem::is_regular_file(path)) throw LayoutError(path, "no such file");
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  if (!CGAL::IO::read_polygon_soup(path, points, polygons))
    throw LayoutError(path, "cannot be read as a polygon mesh (OBJ, OFF or PLY by its extension)");
  if (polygons.empty()) throw LayoutError(path, "the mesh has no faces");
  PolygonMesh mesh;
  mesh.points.reserve(points.size());
  for (const Point& p : points) {
    const Vec3 q(p.x(), p.y(), p.z());
    if (!q.allFinite())
      throw LayoutError(path, fmt::format("vertex {} is not a finite point", mesh.points.size()));
    mesh.points.push_back(q);
  }
  mesh.faces.reserve(polygons.size());
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    std::vector<std::uint32_t> face;
    for (std::size_t i : polygons[f]) {
      if (i >= points.size())
        throw LayoutError(path, fmt::format("face {}: vertex index {} out of range ({} vertices)",
                                            f, i, points.size()));
      face.push_back(static_cast<std::uint32_t>(i));
    }
    mesh.faces.push_back(std::move(face));
  }
  return mesh;
}

VertexFrameModel quadLayout(const PolygonMesh& quads, const std::string& source) {
  // Every face a quad with four distinct corners.
  for (std::size_t f = 0; f < quads.faces.size(); ++f) {
    const auto& face = quads.faces[f];
    if (face.size() != 4)
      throw LayoutError(
          source,
          fmt::format(
              "face {} has {} corners: a vertex-frame layout takes quads only (one frame per "
              "quad)",
              f, face.size()));
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (face[i] == face[j])
          throw LayoutError(
              source,
              fmt::format("face {} repeats vertex {}: a quad needs four corners", f, face[i]));
  }
  // Edges: each undirected edge once, with the faces on it; more than two is non-manifold.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> edgeFaces;
  for (std::size_t f = 0; f < quads.faces.size(); ++f)
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t a = quads.faces[f][i], b = quads.faces[f][(i + 1) % 4];
      edgeFaces[{std::min(a, b), std::max(a, b)}].push_back(static_cast<std::uint32_t>(f));
    }
  for (const auto& [edge, faces] : edgeFaces)
    if (faces.size() > 2)
      throw LayoutError(
          source,
          fmt::format(
              "face {}: its edge {}-{} is shared by {} faces ({}): a layout must be a manifold "
              "quad mesh (each edge on one or two faces)",
              faces[2], edge.first, edge.second, faces.size(), fmt::join(faces, ", ")));

  VertexFrameModel model;
  // The quads' used vertices first, in file order.
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> index(quads.points.size(), kUnused);
  for (const auto& face : quads.faces)
    for (std::uint32_t v : face) index[v] = 0;
  for (std::size_t v = 0; v < quads.points.size(); ++v)
    if (index[v] != kUnused) {
      index[v] = static_cast<std::uint32_t>(model.vertices.size());
      model.vertices.push_back(quads.points[v]);
    }
  // Then one midpoint per edge, in the order the quads first reach their edges.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoint;
  auto middle = [&](std::uint32_t a, std::uint32_t b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    const auto [it, inserted] =
        midpoint.emplace(key, static_cast<std::uint32_t>(model.vertices.size()));
    if (inserted) model.vertices.push_back(0.5 * (quads.points[a] + quads.points[b]));
    return it->second;
  };
  model.frames.reserve(quads.faces.size());
  for (const auto& face : quads.faces) {
    Frame frame;
    for (int i = 0; i < 4; ++i) {
      frame.vertices[2 * i] = index[face[i]];
      frame.vertices[2 * i + 1] = middle(face[i], face[(i + 1) % 4]);
    }
    model.frames.push_back(std::move(frame));
  }
  return model;
}

}  // namespace pdesurf
