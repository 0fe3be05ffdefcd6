// The polygon peer: CGAL's Garland–Heckbert edge collapse, the fewest edges within a target
// RMS (apps/accuracy/peers.hpp).
#include <cmath>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <fmt/format.h>

#include "pdesurf/analysis.hpp"
#include "peers.hpp"

namespace pdesurf {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace SMS = CGAL::Surface_mesh_simplification;

/// The truth as a CGAL surface mesh (every vertex, every triangle as given).
SurfaceMesh toSurfaceMesh(const Mesh& mesh) {
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> v(mesh.vertexCount());
  for (std::size_t i = 0; i < mesh.vertexCount(); ++i)
    v[i] = sm.add_vertex(
        {mesh.positions[3 * i], mesh.positions[3 * i + 1], mesh.positions[3 * i + 2]});
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const std::uint32_t* c = &mesh.indices[3 * t];
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;  // no triangle at all
    if (sm.add_face(v[c[0]], v[c[1]], v[c[2]]) == SurfaceMesh::null_face())
      throw InvalidArgument(fmt::format(
          "triangle {} cannot join the others: simplification needs a manifold, consistently "
          "oriented mesh",
          t));
  }
  return sm;
}

Mesh toMesh(SurfaceMesh sm) {
  sm.collect_garbage();
  Mesh out;
  for (auto v : sm.vertices())
    for (int c = 0; c < 3; ++c) out.positions.push_back(static_cast<float>(sm.point(v)[c]));
  for (auto f : sm.faces())
    for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm))
      out.indices.push_back(static_cast<std::uint32_t>(v));
  return out;
}

/// The truth with edges collapsed (cheapest quadric error first) until fewer than `edges`
/// remain, or none can be.
Mesh simplified(const SurfaceMesh& truth, std::size_t edges) {
  SurfaceMesh sm = truth;
  SMS::GarlandHeckbert_plane_policies<SurfaceMesh, Kernel> policies(sm);
  SMS::edge_collapse(
      sm, SMS::Count_stop_predicate<SurfaceMesh>(edges),
      CGAL::parameters::get_cost(policies.get_cost()).get_placement(policies.get_placement()));
  return toMesh(std::move(sm));
}

}  // namespace

double accuracyRms(const MeshDistance& d) {
  return std::sqrt(
      0.5 * (d.aToB.rmsRelative * d.aToB.rmsRelative + d.bToA.rmsRelative * d.bToA.rmsRelative));
}

double accuracyRms(const Mesh& model, const Mesh& truth, const DistanceOptions& options) {
  return accuracyRms(meshDistance(model, truth, options));
}

PolygonPeer simplifiedPeer(const Mesh& truth, double targetRms, const DistanceOptions& distance) {
  const SurfaceMesh sm = toSurfaceMesh(truth);
  PolygonPeer best;
  best.mesh = toMesh(sm);
  best.rms = 0.0;
  best.bytes = storageBytes(best.mesh);
  // meets(E): the simplification keeping about E edges is within the target. Bisection on
  // E in (lo, hi]: hi meets (the truth itself), lo misses (or is the fewest possible).
  std::size_t lo = 5, hi = sm.number_of_edges();
  auto trial = [&](std::size_t edges, Mesh& mesh) {
    mesh = simplified(sm, edges);
    ++best.trials;
    return mesh.triangleCount() > 0 ? accuracyRms(mesh, truth, distance) : 1e300;
  };
  Mesh mesh;
  const double loRms = trial(lo, mesh);
  if (loRms <= targetRms) {
    best.mesh = std::move(mesh);
    best.rms = loRms;
    best.reached = true;
    best.bytes = storageBytes(best.mesh);
    return best;
  }
  best.coarserRms = loRms;
  best.reached = true;  // the truth itself meets any target ≥ 0
  while (hi - lo > 1) {
    const std::size_t mid = lo + (hi - lo) / 2;
    const double rms = trial(mid, mesh);
    if (rms <= targetRms) {
      hi = mid;
      best.mesh = std::move(mesh);
      best.rms = rms;
    } else {
      lo = mid;
      best.coarserRms = rms;
    }
  }
  best.bytes = storageBytes(best.mesh);
  return best;
}

}  // namespace pdesurf
