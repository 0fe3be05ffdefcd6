// A U × V grid of frames on a disk-like mesh, through CGAL's parameterisation onto a square
// (mean-value coordinates inside a square border), with the grid's lines placed so that
// each row and each column of frames covers an equal share of the mesh's area.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <CGAL/Eigen_solver_traits.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/Surface_mesh_parameterization/Mean_value_coordinates_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Square_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <fmt/format.h>
#include <Eigen/SparseLU>

#include "fit/disk_grids.hpp"
#include "fit/lattice_frame.hpp"
#include "numerics/triangle_tree.hpp"
#include "pdesurf/rebuild.hpp"

namespace pdesurf {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point2 = Kernel::Point_2;
using Point3 = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point3>;
using VertexIndex = SurfaceMesh::Vertex_index;
namespace SMP = CGAL::Surface_mesh_parameterization;

/// A lattice point counts as inside a uv triangle when no barycentric coordinate is below
/// -this: points on the square's border and on shared triangle edges land somewhere.
constexpr double kInsideTolerance = 1e-9;

/// Bins of the area distribution along u and along v (a grid line lands within 1/4096 of
/// its quantile).
constexpr int kAreaBins = 4096;

/// The uv triangles in buckets of a regular grid over the unit square, for point location.
class UvLocator {
 public:
  UvLocator(const std::vector<Eigen::Vector2d>& uv,
            const std::vector<std::array<std::uint32_t, 3>>& tris)
      : uv_(uv), tris_(tris) {
    n_ = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(tris.size()))));
    buckets_.resize(static_cast<std::size_t>(n_) * n_);
    for (std::uint32_t t = 0; t < tris.size(); ++t) {
      Eigen::Vector2d lo = uv[tris[t][0]], hi = lo;
      for (int k = 1; k < 3; ++k)
        lo = lo.cwiseMin(uv[tris[t][k]]), hi = hi.cwiseMax(uv[tris[t][k]]);
      for (int j = cell(lo.y()); j <= cell(hi.y()); ++j)
        for (int i = cell(lo.x()); i <= cell(hi.x()); ++i) buckets_[j * n_ + i].push_back(t);
    }
  }

  /// The triangle holding p and p's barycentric coordinates there (the triangle where p is
  /// least outside, should rounding put p just outside all of them).
  std::pair<std::uint32_t, Eigen::Vector3d> locate(const Eigen::Vector2d& p) const {
    double best = -std::numeric_limits<double>::infinity();
    std::pair<std::uint32_t, Eigen::Vector3d> found{0, Eigen::Vector3d(1, 0, 0)};
    auto test = [&](std::uint32_t t) {
      const Eigen::Vector2d a = uv_[tris_[t][0]], b = uv_[tris_[t][1]], c = uv_[tris_[t][2]];
      const double det = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
      if (det == 0.0) return;
      const Eigen::Vector2d d = p - a;
      const double lb = (d.x() * (c - a).y() - d.y() * (c - a).x()) / det;
      const double lc = ((b - a).x() * d.y() - (b - a).y() * d.x()) / det;
      const Eigen::Vector3d l(1.0 - lb - lc, lb, lc);
      if (l.minCoeff() > best) best = l.minCoeff(), found = {t, l};
    };
    for (std::uint32_t t : buckets_[cell(p.y()) * n_ + cell(p.x())]) test(t);
    if (best < -kInsideTolerance)  // not in its bucket (rounding at a bucket's edge): all
      for (std::uint32_t t = 0; t < tris_.size(); ++t) test(t);
    return found;
  }

 private:
  int cell(double x) const { return std::clamp(static_cast<int>(x * n_), 0, n_ - 1); }

  const std::vector<Eigen::Vector2d>& uv_;
  const std::vector<std::array<std::uint32_t, 3>>& tris_;
  int n_ = 1;
  std::vector<std::vector<std::uint32_t>> buckets_;
};

}  // namespace

namespace detail {

/// The parameterisation, what every grid reads from it: uv and 3D positions per vertex, the
/// triangles (as the mesh orients them), a locator of uv points, and per parameter direction
/// the cumulative share of the mesh's area.
struct DiskGrids::Map {
  std::vector<Eigen::Vector2d> uv;
  std::vector<Vec3> xyz;
  std::vector<std::array<std::uint32_t, 3>> tris;
  std::unique_ptr<UvLocator> locator;
  std::array<std::vector<double>, 2> cumulative;
};

DiskGrids::~DiskGrids() = default;

DiskGrids::DiskGrids(const Mesh& disk, const std::string& source) : map_(std::make_unique<Map>()) {
  // The mesh as a CGAL surface mesh: used vertices only, triangles with area only.
  SurfaceMesh sm;
  std::vector<VertexIndex> handle(disk.vertexCount());
  std::vector<std::uint32_t> vertexOf;  // surface-mesh vertex -> Mesh vertex
  std::vector<char> used(disk.vertexCount(), 0);
  auto point = [&](std::uint32_t v) { return detail::meshVertex(disk, v); };
  std::vector<std::size_t> kept;
  for (std::size_t t = 0; t < disk.triangleCount(); ++t) {
    const std::uint32_t* i = &disk.indices[3 * t];
    if (!((point(i[1]) - point(i[0])).cross(point(i[2]) - point(i[0])).norm() > 0.0)) continue;
    kept.push_back(t);
    for (int k = 0; k < 3; ++k) used[i[k]] = 1;
  }
  for (std::uint32_t v = 0; v < disk.vertexCount(); ++v)
    if (used[v]) {
      const Vec3 p = point(v);
      handle[v] = sm.add_vertex(Point3(p.x(), p.y(), p.z()));
      vertexOf.push_back(v);
    }
  for (std::size_t t : kept) {
    const std::uint32_t* i = &disk.indices[3 * t];
    if (sm.add_face(handle[i[0]], handle[i[1]], handle[i[2]]) == SurfaceMesh::null_face())
      throw LayoutError(
          source,
          fmt::format("triangle {} cannot join the others: --grid needs a manifold, consistently "
                      "oriented mesh (an edge of three triangles, or a flipped triangle, stops it)",
                      t));
  }
  if (sm.number_of_faces() == 0) throw LayoutError(source, "the mesh has no triangle with area");
  std::vector<SurfaceMesh::Halfedge_index> borders;
  CGAL::Polygon_mesh_processing::extract_boundary_cycles(sm, std::back_inserter(borders));
  const auto euler = static_cast<long>(sm.number_of_vertices()) -
                     static_cast<long>(sm.number_of_edges()) +
                     static_cast<long>(sm.number_of_faces());
  if (borders.size() != 1 || euler != 1)
    throw LayoutError(
        source,
        fmt::format(
            "the mesh has {} boundary loop{} and Euler characteristic {}: --grid needs a disk "
            "(one boundary loop, Euler characteristic 1); use --layout with a quad mesh instead",
            borders.size(), borders.size() == 1 ? "" : "s", euler));

  // Mean-value coordinates inside a square border placed by arc length (one-to-one, the
  // square being convex), solved by sparse LU. (CGAL 5.5's iterative authalic
  // parameterizer is compiled with its debugging on: it prints to standard output and
  // writes last_solve.off into the working directory.)
  using Border = SMP::Square_border_arc_length_parameterizer_3<SurfaceMesh>;
  using LuSolver = CGAL::Eigen_solver_traits<
      Eigen::SparseLU<CGAL::Eigen_sparse_matrix<double>::EigenType, Eigen::COLAMDOrdering<int>>>;
  using Parameterizer = SMP::Mean_value_coordinates_parameterizer_3<SurfaceMesh, Border, LuSolver>;
  auto uvMap = sm.add_property_map<VertexIndex, Point2>("v:uv").first;
  const auto border = CGAL::Polygon_mesh_processing::longest_border(sm).first;
  const SMP::Error_code status = SMP::parameterize(sm, Parameterizer(), border, uvMap);
  if (status != SMP::OK)
    throw LayoutError(source, fmt::format("the parameterisation onto a square failed: {}",
                                          SMP::get_error_message(status)));

  // uv and 3D positions per surface-mesh vertex; triangles as the mesh orients them.
  auto& [uv, xyz, tris, locator, cumulative] = *map_;
  uv.resize(sm.number_of_vertices());
  xyz.resize(sm.number_of_vertices());
  for (VertexIndex v : sm.vertices()) {
    uv[v] = {uvMap[v].x(), uvMap[v].y()};
    xyz[v] = point(vertexOf[v]);
  }
  double signedArea = 0.0;
  for (auto f : sm.faces()) {
    std::array<std::uint32_t, 3> t{};
    int k = 0;
    for (VertexIndex v : CGAL::vertices_around_face(sm.halfedge(f), sm)) t[k++] = v;
    const Eigen::Vector2d e1 = uv[t[1]] - uv[t[0]], e2 = uv[t[2]] - uv[t[0]];
    signedArea += e1.x() * e2.y() - e1.y() * e2.x();
    tris.push_back(t);
  }
  // Where the parameterisation mirrors the mesh, swap u and v, so that the frames'
  // normals S_u × S_v face the way the mesh's triangles do.
  if (signedArea < 0.0)
    for (auto& p : uv) std::swap(p.x(), p.y());
  locator = std::make_unique<UvLocator>(uv, tris);

  // Grid lines at equal shares of area: mean-value coordinates squeeze a cap (a head above
  // its neck) into the middle of the square, and a uniform grid would give it one frame.
  // Each triangle's 3D area is binned by its uv centroid; the lines are the quantiles.
  for (auto& c : cumulative) c.assign(kAreaBins + 1, 0.0);
  for (const auto& t : tris) {
    const double area = 0.5 * (xyz[t[1]] - xyz[t[0]]).cross(xyz[t[2]] - xyz[t[0]]).norm();
    const Eigen::Vector2d centre = (uv[t[0]] + uv[t[1]] + uv[t[2]]) / 3.0;
    for (int d = 0; d < 2; ++d)
      cumulative[d][1 + std::clamp(static_cast<int>(centre[d] * kAreaBins), 0, kAreaBins - 1)] +=
          area;
  }
  for (auto& c : cumulative) {
    for (int b = 0; b < kAreaBins; ++b) c[b + 1] += c[b];
    for (double& x : c) x /= c.back();
  }
}

VertexFrameModel DiskGrids::grid(const GridLayoutOptions& options) const {
  const auto& [uv, xyz, tris, locator, cumulative] = *map_;
  // The parameter where the area share reaches `share`, linear inside a bin.
  auto line = [&](int d, double share) {
    const auto& c = cumulative[d];
    const auto it = std::lower_bound(c.begin(), c.end(), share);
    if (it == c.begin()) return 0.0;
    if (it == c.end()) return 1.0;
    const auto b = static_cast<int>(it - c.begin()) - 1;
    const double span = c[b + 1] - c[b];
    return (b + (span > 0.0 ? (share - c[b]) / span : 0.0)) / kAreaBins;
  };

  // The (2U+1) × (2V+1) lattice of frame vertices, each where its (u, v) lies on the mesh,
  // but the frames' centres (odd i and j), which no frame uses.
  VertexFrameModel model;
  const std::uint32_t nu = 2 * options.u + 1, nv = 2 * options.v + 1;
  std::vector<std::uint32_t> vertexOfPoint(std::size_t{nu} * nv, 0);
  model.vertices.reserve(std::size_t{nu} * nv - std::size_t{options.u} * options.v);
  for (std::uint32_t j = 0; j < nv; ++j)
    for (std::uint32_t i = 0; i < nu; ++i) {
      if (i % 2 == 1 && j % 2 == 1) continue;
      vertexOfPoint[std::size_t{j} * nu + i] = static_cast<std::uint32_t>(model.vertices.size());
      const Eigen::Vector2d p(line(0, static_cast<double>(i) / (nu - 1)),
                              line(1, static_cast<double>(j) / (nv - 1)));
      const auto [t, l] = locator->locate(p);
      model.vertices.push_back(l[0] * xyz[tris[t][0]] + l[1] * xyz[tris[t][1]] +
                               l[2] * xyz[tris[t][2]]);
    }
  auto at = [&](std::uint32_t i, std::uint32_t j) {
    return vertexOfPoint[std::size_t{j} * nu + i];
  };
  for (std::uint32_t r = 0; r < options.v; ++r)
    for (std::uint32_t c = 0; c < options.u; ++c)
      model.frames.push_back(latticeFrame(at, 2 * c, 2 * r));
  return model;
}

}  // namespace detail

VertexFrameModel gridLayout(const Mesh& disk, const GridLayoutOptions& options,
                            const std::string& source) {
  if (options.u < 1 || options.v < 1)
    throw LayoutError(source, "a grid needs at least 1 × 1 frames");
  return detail::DiskGrids(disk, source).grid(options);
}

}  // namespace pdesurf
