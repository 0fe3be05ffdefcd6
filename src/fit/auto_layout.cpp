// The automatic layout: CGAL's Garland–Heckbert edge collapse to a target size with creases
// and boundaries kept on edges, quads from the simplified triangles, every vertex put on the
// mesh (docs/rebuild.md, "The automatic layout").
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Edge_collapse_visitor_base.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_placement.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <fmt/format.h>

#include "numerics/triangle_tree.hpp"
#include "pdesurf/auto_layout.hpp"

namespace pdesurf {
namespace {

using detail::Kernel;
using detail::meshVertex;
using detail::toPoint;
using detail::toVec;
using SurfaceMesh = CGAL::Surface_mesh<detail::Point>;
using VertexIndex = SurfaceMesh::Vertex_index;
namespace SMS = CGAL::Surface_mesh_simplification;

/// Samples a frame side when the layout is checked for folds (foldedFrames).
constexpr std::uint32_t kFoldCheckResolution = 9;
/// Times the side middles of folded frames are flattened (unfold).
constexpr int kUnfoldPasses = 3;

/// A pair of triangles becomes a quad only when every corner angle of the quad is below this
/// (degrees): convex, with room to spare.
constexpr double kMaxPairCorner = 160.0;

/// The crease (and boundary) edges of the mesh being simplified, as neighbour lists by
/// vertex index, kept up to date as edges collapse: a collapse merges the removed vertex's
/// crease edges into the kept one's.
class Creases {
 public:
  explicit Creases(std::size_t vertices) : next_(vertices) {}
  void add(VertexIndex a, VertexIndex b) {
    link(a, b);
    link(b, a);
  }
  bool has(VertexIndex a, VertexIndex b) const {
    const auto& n = next_[a];
    return std::find(n.begin(), n.end(), std::uint32_t(b)) != n.end();
  }
  std::size_t degree(VertexIndex v) const { return next_[v].size(); }
  std::size_t edges() const {
    std::size_t sum = 0;
    for (const auto& n : next_) sum += n.size();
    return sum / 2;
  }
  /// The edge kept–removed collapsed into `kept`.
  void collapse(VertexIndex kept, VertexIndex removed) {
    unlink(kept, removed);
    unlink(removed, kept);
    for (std::uint32_t n : next_[removed]) {
      unlink(VertexIndex(n), removed);
      add(kept, VertexIndex(n));
    }
    next_[removed].clear();
  }
  /// Drops the chains (connected sets of crease edges) shorter than `minLength`, boundary
  /// edges (`keep`) never.
  template <class Keep>
  void dropShortChains(const SurfaceMesh& sm, double minLength, Keep&& keep) {
    std::vector<int> chain(next_.size(), -1);
    std::vector<double> length;
    for (std::size_t s = 0; s < next_.size(); ++s) {
      if (next_[s].empty() || chain[s] >= 0) continue;
      const int c = static_cast<int>(length.size());
      length.push_back(0.0);
      std::vector<std::uint32_t> stack{static_cast<std::uint32_t>(s)};
      chain[s] = c;
      while (!stack.empty()) {
        const std::uint32_t v = stack.back();
        stack.pop_back();
        for (std::uint32_t n : next_[v]) {
          if (v < n)
            length[c] += std::sqrt(
                CGAL::squared_distance(sm.point(VertexIndex(v)), sm.point(VertexIndex(n))));
          if (chain[n] < 0) chain[n] = c, stack.push_back(n);
        }
      }
    }
    for (std::size_t v = 0; v < next_.size(); ++v) {
      if (next_[v].empty() || length[chain[v]] >= minLength) continue;
      auto& n = next_[v];
      n.erase(std::remove_if(n.begin(), n.end(),
                             [&](std::uint32_t w) {
                               return !keep(VertexIndex(std::uint32_t(v)), VertexIndex(w));
                             }),
              n.end());
    }
  }

 private:
  void link(VertexIndex a, VertexIndex b) {
    if (!has(a, b)) next_[a].push_back(std::uint32_t(b));
  }
  void unlink(VertexIndex a, VertexIndex b) {
    auto& n = next_[a];
    n.erase(std::remove(n.begin(), n.end(), std::uint32_t(b)), n.end());
  }
  std::vector<std::vector<std::uint32_t>> next_;
};

/// The base placement (Garland–Heckbert's optimum), held to the creases: a vertex on a crease
/// stays on it, so a collapse may move along a crease but never across or off one.
/// - No end on a crease: the base placement.
/// - One end on a crease: that end's point.
/// - Both ends: only along a crease edge; at the end that is a corner (where other than two
///   crease edges meet), or, between two plain crease vertices, at the base placement's
///   nearest point on the edge. Two corners, or two creases not joined by the edge: none.
template <class Base>
class CreasePlacement : public Base {
 public:
  CreasePlacement(const Base& base, const Creases& creases) : Base(base), creases_(&creases) {}

  template <class Profile>
  boost::optional<typename Profile::Point> operator()(const Profile& profile) const {
    using Point = typename Profile::Point;
    const VertexIndex a = profile.v0(), b = profile.v1();
    const std::size_t da = creases_->degree(a), db = creases_->degree(b);
    if (da == 0 && db == 0) return static_cast<const Base&>(*this)(profile);
    const Point pa = profile.p0(), pb = profile.p1();
    if (db == 0) return pa;
    if (da == 0) return pb;
    if (!creases_->has(a, b)) return boost::none;
    if (da == 2 && db == 2) {
      const boost::optional<Point> base = static_cast<const Base&>(*this)(profile);
      const Vec3 p = toVec(pa), d = toVec(pb) - p;
      const double t =
          base ? std::clamp((toVec(*base) - p).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.5;
      return toPoint(p + t * d);
    }
    if (da == 2) return pb;
    if (db == 2) return pa;
    return boost::none;
  }

 private:
  const Creases* creases_;
};

/// Keeps the creases' lists up to date as edges collapse.
struct CreaseVisitor : SMS::Edge_collapse_visitor_base<SurfaceMesh> {
  Creases* creases;
  explicit CreaseVisitor(Creases& c) : creases(&c) {}
  template <class Profile>
  void OnCollapsed(const Profile& profile, VertexIndex kept) {
    creases->collapse(kept, kept == profile.v0() ? profile.v1() : profile.v0());
  }
};

/// The mesh as a CGAL surface mesh: triangles with area only (counted in `skipped`).
SurfaceMesh toSurfaceMesh(const Mesh& mesh, const std::string& source, std::size_t& skipped) {
  if (mesh.triangleCount() == 0) throw LayoutError(source, "the mesh has no triangles");
  SurfaceMesh sm;
  std::vector<VertexIndex> handle(mesh.vertexCount());
  for (std::uint32_t v = 0; v < mesh.vertexCount(); ++v) {
    const Vec3 p = meshVertex(mesh, v);
    if (!p.allFinite())
      throw LayoutError(source, fmt::format("vertex {} is not a finite point", v));
    handle[v] = sm.add_vertex(toPoint(p));
  }
  skipped = 0;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const std::uint32_t* c = &mesh.indices[3 * t];
    const Vec3 a = meshVertex(mesh, c[0]);
    if (!((meshVertex(mesh, c[1]) - a).cross(meshVertex(mesh, c[2]) - a).norm() > 0.0)) {
      ++skipped;
      continue;
    }
    if (sm.add_face(handle[c[0]], handle[c[1]], handle[c[2]]) == SurfaceMesh::null_face())
      throw LayoutError(
          source,
          fmt::format(
              "triangle {} ({} {} {}) cannot join the others: the automatic layout needs a "
              "manifold, consistently oriented mesh (an edge of three triangles, two fans meeting "
              "at a vertex, or a triangle turned against its neighbours stops it)",
              t, c[0], c[1], c[2]));
  }
  if (sm.number_of_faces() == 0)
    throw LayoutError(source,
                      fmt::format("none of the mesh's {} triangles has an area (all degenerate)",
                                  mesh.triangleCount()));
  // Vertices no triangle uses would stay as isolated points.
  for (VertexIndex v : handle)
    if (sm.is_isolated(v)) sm.remove_vertex(v);
  sm.collect_garbage();
  return sm;
}

Vec3 faceNormal(const SurfaceMesh& sm, SurfaceMesh::Face_index f) {
  const auto h = sm.halfedge(f);
  const Vec3 a = toVec(sm.point(sm.source(h))), b = toVec(sm.point(sm.target(h))),
             c = toVec(sm.point(sm.target(sm.next(h))));
  return (b - a).cross(c - a);
}

/// Marks the creases (dihedral angle above the threshold, chains long enough) and the
/// boundary edges.
Creases findCreases(const SurfaceMesh& sm, double angleDegrees, double diagonal) {
  Creases creases(sm.number_of_vertices());
  const double cosMax = std::cos(angleDegrees * M_PI / 180.0);
  for (auto e : sm.edges()) {
    const auto h = sm.halfedge(e);
    const VertexIndex a = sm.source(h), b = sm.target(h);
    if (sm.is_border(e)) {
      creases.add(a, b);
      continue;
    }
    const Vec3 n0 = faceNormal(sm, sm.face(h)).normalized(),
               n1 = faceNormal(sm, sm.face(sm.opposite(h))).normalized();
    if (n0.dot(n1) < cosMax) creases.add(a, b);
  }
  creases.dropShortChains(sm, kMinCreaseChain * diagonal, [&](VertexIndex a, VertexIndex b) {
    const auto h = sm.halfedge(a, b);
    return sm.is_border(sm.edge(h));
  });
  return creases;
}

/// Stops the collapse at `target` faces.
struct FaceCountStop {
  const SurfaceMesh* sm;
  std::size_t target;
  template <class FT, class Profile>
  bool operator()(const FT&, const Profile&, std::size_t, std::size_t) const {
    return sm->number_of_faces() <= target;
  }
};

/// The simplified mesh's faces as polygons (triangles, or quads where pairs were joined),
/// counter-clockwise as the mesh's.
std::vector<std::vector<std::uint32_t>> polygons(const SurfaceMesh& sm, const Creases& creases,
                                                 QuadConstruction construction) {
  auto corners = [&](SurfaceMesh::Face_index f) {
    std::vector<std::uint32_t> c;
    for (VertexIndex v : CGAL::vertices_around_face(sm.halfedge(f), sm)) c.push_back(v);
    return c;
  };
  std::vector<std::vector<std::uint32_t>> out;
  if (construction == QuadConstruction::SplitTriangles) {
    for (auto f : sm.faces()) out.push_back(corners(f));
    return out;
  }
  // Candidate pairs across interior edges that are no crease: the worst corner's distance
  // from a right angle, best first.
  struct Candidate {
    double badness;
    SurfaceMesh::Halfedge_index h;
  };
  std::vector<Candidate> candidates;
  for (auto e : sm.edges()) {
    if (sm.is_border(e)) continue;
    const auto h = sm.halfedge(e);
    if (creases.has(sm.source(h), sm.target(h))) continue;
    // h runs a -> c in the face (a c d); its opposite in (c a b): the quad is a b c d.
    const VertexIndex a = sm.source(h), c = sm.target(h);
    const VertexIndex d = sm.target(sm.next(h)), b = sm.target(sm.next(sm.opposite(h)));
    const std::array<Vec3, 4> q{toVec(sm.point(a)), toVec(sm.point(b)), toVec(sm.point(c)),
                                toVec(sm.point(d))};
    double worst = 0.0;
    bool convex = true;
    for (int i = 0; i < 4; ++i) {
      const Vec3 u = (q[(i + 3) % 4] - q[i]).normalized(), w = (q[(i + 1) % 4] - q[i]).normalized();
      const double angle = std::acos(std::clamp(u.dot(w), -1.0, 1.0)) * 180.0 / M_PI;
      if (angle > kMaxPairCorner) convex = false;
      worst = std::max(worst, std::abs(angle - 90.0));
    }
    if (convex) candidates.push_back({worst, h});
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& x, const Candidate& y) { return x.badness < y.badness; });
  std::vector<char> paired(sm.num_faces(), 0);
  for (const Candidate& cand : candidates) {
    const auto f0 = sm.face(cand.h), f1 = sm.face(sm.opposite(cand.h));
    if (paired[f0] || paired[f1]) continue;
    paired[f0] = paired[f1] = 1;
    const VertexIndex a = sm.source(cand.h), c = sm.target(cand.h);
    const VertexIndex d = sm.target(sm.next(cand.h)), b = sm.target(sm.next(sm.opposite(cand.h)));
    // f0 is (a c d) counter-clockwise, f1 (c a b): the quad a b c d.
    out.push_back({a, b, c, d});
  }
  for (auto f : sm.faces())
    if (!paired[f]) out.push_back(corners(f));
  return out;
}

/// Each polygon of n corners split into n quads through its centre and its edges' middles
/// (shared by the two polygons on an edge): corner i's quad is p_i, m(i, i+1), centre,
/// m(i-1, i), counter-clockwise as the polygon.
PolygonMesh splitIntoQuads(const std::vector<Vec3>& points,
                           const std::vector<std::vector<std::uint32_t>>& polys) {
  PolygonMesh quads;
  quads.points = points;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middles;
  auto middle = [&](std::uint32_t a, std::uint32_t b) {
    const auto key = std::minmax(a, b);
    const auto [it, inserted] =
        middles.emplace(key, static_cast<std::uint32_t>(quads.points.size()));
    if (inserted) quads.points.push_back(0.5 * (points[a] + points[b]));
    return it->second;
  };
  for (const auto& p : polys) {
    const std::size_t n = p.size();
    Vec3 centre = Vec3::Zero();
    for (std::uint32_t v : p) centre += points[v];
    const auto g = static_cast<std::uint32_t>(quads.points.size());
    quads.points.push_back(centre / static_cast<double>(n));
    for (std::size_t i = 0; i < n; ++i)
      quads.faces.push_back(
          {p[i], middle(p[i], p[(i + 1) % n]), g, middle(p[(i + n - 1) % n], p[i])});
  }
  return quads;
}

/// Puts every vertex of the model on the mesh: its closest point, where the triangle there
/// faces as the frames round the vertex do (else the vertex stays: a closest point on the
/// far side of a thin part would turn its frames over).
void putOnMesh(VertexFrameModel& model, const Mesh& mesh) {
  detail::Triangles triangles;
  triangles.reserve(mesh.triangleCount());
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const std::uint32_t* c = &mesh.indices[3 * t];
    triangles.emplace_back(toPoint(meshVertex(mesh, c[0])), toPoint(meshVertex(mesh, c[1])),
                           toPoint(meshVertex(mesh, c[2])));
  }
  std::vector<Vec3> normal(model.vertices.size(), Vec3::Zero());
  for (const Frame& f : model.frames) {
    const auto& v = f.vertices;
    const Vec3 n = (model.vertices[v[4]] - model.vertices[v[0]])
                       .cross(model.vertices[v[6]] - model.vertices[v[2]]);
    for (std::uint32_t i : v) normal[i] += n;
  }
  detail::Tree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  for (std::size_t i = 0; i < model.vertices.size(); ++i) {
    const auto [point, primitive] = tree.closest_point_and_primitive(toPoint(model.vertices[i]));
    const detail::Triangle& t = *primitive;
    const Vec3 n = (toVec(t[1]) - toVec(t[0])).cross(toVec(t[2]) - toVec(t[0]));
    if (n.dot(normal[i]) > 0.0) model.vertices[i] = toVec(point);
  }
}

/// The frames whose surface turns against their corners' quad somewhere: a triangle of the
/// tessellation at kFoldCheckResolution whose normal points against the quad's
/// ((P5 - P1) × (P7 - P3)).
std::vector<char> foldedFrames(const VertexFrameModel& model) {
  const Mesh t = tessellate(solve(model), {kFoldCheckResolution});
  std::vector<char> folded(model.frames.size(), 0);
  for (std::size_t i = 0; i < t.triangleCount(); ++i) {
    const std::uint32_t k = t.patchIds[i];
    const auto& v = model.frames[k].vertices;
    const Vec3 quad = (model.vertices[v[4]] - model.vertices[v[0]])
                          .cross(model.vertices[v[6]] - model.vertices[v[2]]);
    const std::uint32_t* c = &t.indices[3 * i];
    const Vec3 a = meshVertex(t, c[0]);
    if ((meshVertex(t, c[1]) - a).cross(meshVertex(t, c[2]) - a).dot(quad) < 0.0) folded[k] = 1;
  }
  return folded;
}

/// Where a frame's surface folds, its side middles go back to the middles of its sides'
/// chords (a flatter frame), up to kUnfoldPasses times.
void unfold(VertexFrameModel& model) {
  for (int pass = 0; pass < kUnfoldPasses; ++pass) {
    const std::vector<char> folded = foldedFrames(model);
    if (std::find(folded.begin(), folded.end(), 1) == folded.end()) return;
    for (std::size_t k = 0; k < folded.size(); ++k) {
      if (!folded[k]) continue;
      const auto& v = model.frames[k].vertices;
      for (int i = 0; i < 4; ++i)
        model.vertices[v[2 * i + 1]] =
            0.5 * (model.vertices[v[2 * i]] + model.vertices[v[(2 * i + 2) % 8]]);
    }
  }
}

double diagonalOf(const SurfaceMesh& sm) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (VertexIndex v : sm.vertices()) {
    const Vec3 p = toVec(sm.point(v));
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

}  // namespace

AutoLayout autoLayout(const Mesh& mesh, const AutoLayoutOptions& options,
                      const std::string& source) {
  AutoLayout out;
  SurfaceMesh sm = toSurfaceMesh(mesh, source, out.skippedTriangles);
  {
    auto component = sm.add_property_map<SurfaceMesh::Face_index, std::size_t>("f:cc").first;
    out.components = CGAL::Polygon_mesh_processing::connected_components(sm, component);
  }
  Creases creases = findCreases(sm, options.creaseAngle, diagonalOf(sm));
  out.creaseEdges = creases.edges();

  const double perTriangle = options.construction == QuadConstruction::SplitTriangles ? 3.0 : 2.0;
  const auto target = static_cast<std::size_t>(
      std::max(1.0, std::round(static_cast<double>(options.frames) / perTriangle)));
  if (sm.number_of_faces() > target) {
    SMS::GarlandHeckbert_plane_policies<SurfaceMesh, Kernel> policies(sm);
    using BasePlacement = std::decay_t<decltype(policies.get_placement())>;
    const SMS::Bounded_normal_change_placement<CreasePlacement<BasePlacement>> placement(
        CreasePlacement<BasePlacement>(policies.get_placement(), creases));
    SMS::edge_collapse(sm, FaceCountStop{&sm, target},
                       CGAL::parameters::get_cost(policies.get_cost())
                           .get_placement(placement)
                           .visitor(CreaseVisitor(creases)));
  }
  // The simplified mesh, compacted: vertex i of `points` is vertex index i.
  std::vector<Vec3> points;
  std::vector<std::uint32_t> compact(sm.num_vertices(), 0);
  for (VertexIndex v : sm.vertices()) {
    compact[v] = static_cast<std::uint32_t>(points.size());
    points.push_back(toVec(sm.point(v)));
  }
  out.baseTriangles = sm.number_of_faces();
  // Pairs are chosen on the uncompacted mesh (the creases' indices), then renumbered.
  std::vector<std::vector<std::uint32_t>> polys;
  polys = polygons(sm, creases, options.construction);
  for (auto& p : polys)
    for (std::uint32_t& v : p) v = compact[v];
  out.quads = splitIntoQuads(points, polys);
  out.model = quadLayout(out.quads, source);
  putOnMesh(out.model, mesh);
  unfold(out.model);
  return out;
}

}  // namespace pdesurf
