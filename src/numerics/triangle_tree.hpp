// The CGAL AABB tree of triangles that closest-point queries share (mesh distances, the
// rebuild's fitting), and the conversions between pdesurf's and CGAL's points.
#pragma once

#include <cstdint>
#include <vector>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include "pdesurf/mesh.hpp"
#include "pdesurf/vertex_frames.hpp"

namespace pdesurf::detail {

// Plain doubles: closest points need no exact predicates.
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Triangles = std::vector<Triangle>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

inline Point toPoint(const Vec3& p) { return {p.x(), p.y(), p.z()}; }
inline Vec3 toVec(const Point& p) { return {p.x(), p.y(), p.z()}; }

/// Vertex v of a mesh, in double.
inline Vec3 meshVertex(const Mesh& mesh, std::uint32_t v) {
  return {mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
}

}  // namespace pdesurf::detail
