// Closest-point pairs between a fitted surface and its mesh (closest_pairs.hpp).
#include "fit/closest_pairs.hpp"
#include "pdesurf/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <Eigen/Dense>

namespace pdesurf::fit {

using detail::Point;
using detail::toPoint;
using detail::toVec;
using detail::Tree;
using detail::Triangle;
using detail::Triangles;

namespace {

/// Gauss–Newton steps that move a mesh vertex's foot point from the sample triangle's
/// estimate onto the patch: the estimate is within a sample cell, so a few suffice.
constexpr int kProjectionSteps = 4;

/// A foot point whose barycentric coordinate opposite a boundary edge is below this lies on
/// the boundary: its pair counts the whole distance, not the normal part alone.
constexpr double kOnBoundary = 1e-9;

/// A foot point whose smallest barycentric coordinate is below this lies on an edge or a
/// corner of its triangle (where the distance's direction, not the triangle's normal, is
/// the pair's normal); a sample nearer than this (relative to the diagonal) keeps the
/// triangle's normal.
constexpr double kOnEdge = 1e-9;

/// The barycentric coordinates of p (in the triangle's plane) in triangle a b c.
Eigen::Vector3d barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double total = n.squaredNorm();
  if (!(total > 0.0)) return {1.0, 0.0, 0.0};
  const double lb = (p - a).cross(c - a).dot(n) / total;
  const double lc = (b - a).cross(p - a).dot(n) / total;
  return {1.0 - lb - lc, lb, lc};
}

}  // namespace

SampleGrid::SampleGrid(std::uint32_t g) : perSide(g) {
  for (std::uint32_t j = 0; j < g; ++j)
    for (std::uint32_t i = 0; i < g; ++i) {
      // Trapezoid weights: a border sample stands for half a cell, a corner for a quarter.
      const double wu = (i == 0 || i + 1 == g) ? 0.5 : 1.0;
      const double wv = (j == 0 || j + 1 == g) ? 0.5 : 1.0;
      points.push_back(
          {static_cast<double>(i) / (g - 1), static_cast<double>(j) / (g - 1), wu * wv});
    }
}

Target::Target(const Mesh& mesh) {
  auto vertex = [&](std::uint32_t v) { return detail::meshVertex(mesh, v); };
  std::vector<double> area(mesh.vertexCount(), 0.0);
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  double total = 0.0;
  // Edges of one triangle with area are the boundary.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edgeUse;
  std::vector<std::size_t> kept;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const std::uint32_t* i = &mesh.indices[3 * t];
    const Vec3 a = vertex(i[0]), b = vertex(i[1]), c = vertex(i[2]);
    if (!((b - a).cross(c - a).norm() > 0.0)) continue;
    kept.push_back(t);
    for (int k = 0; k < 3; ++k) ++edgeUse[std::minmax(i[(k + 1) % 3], i[(k + 2) % 3])];
  }
  for (std::size_t t : kept) {
    const std::uint32_t* i = &mesh.indices[3 * t];
    const Vec3 a = vertex(i[0]), b = vertex(i[1]), c = vertex(i[2]);
    const double at = 0.5 * (b - a).cross(c - a).norm();
    std::uint8_t bits = 0;
    for (int k = 0; k < 3; ++k)
      if (edgeUse[std::minmax(i[(k + 1) % 3], i[(k + 2) % 3])] == 1) bits |= 1u << k;
    boundary.push_back(bits);
    triangles.emplace_back(toPoint(a), toPoint(b), toPoint(c));
    normals.push_back((b - a).cross(c - a).normalized());
    for (int k = 0; k < 3; ++k) {
      area[i[k]] += at / 3.0;
      lo = lo.cwiseMin(vertex(i[k]));
      hi = hi.cwiseMax(vertex(i[k]));
    }
    total += at;
  }
  if (triangles.empty())
    throw InvalidArgument(
        fmt::format("the mesh has no triangle with area ({} triangles)", mesh.triangleCount()));
  for (std::uint32_t v = 0; v < mesh.vertexCount(); ++v)
    if (area[v] > 0.0) {
      samples.push_back(vertex(v));
      weights.push_back(area[v] / total);
    }
  diagonal = (hi - lo).norm();
  tree.insert(triangles.cbegin(), triangles.cend());
  tree.build();
  tree.accelerate_distance_queries();
}

Evaluation closestPairs(VertexFrameSurface surface, const SampleGrid& grid, const Target& target,
                        const Evaluation* hints) {
  const std::uint32_t g = grid.perSide;
  const auto nFrames = static_cast<std::uint32_t>(surface.patches.size());
  const std::size_t perFrame = grid.points.size();
  Evaluation e;
  e.pairs.reserve(std::size_t{nFrames} * perFrame + target.samples.size());
  const double diag = target.diagonal > 0.0 ? target.diagonal : 1.0;

  // Surface samples -> mesh, weighted by the area they stand for.
  const std::size_t count = std::size_t{nFrames} * perFrame;
  std::vector<Vec3> positions(count);
  std::vector<double> cosine(count), distances(count);
  e.pairs.resize(count);
  e.meshTriangle.resize(count);
  e.du.resize(count);
  e.dv.resize(count);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, nFrames), [&](const auto& range) {
    for (std::uint32_t k = range.begin(); k != range.end(); ++k) {
      const double flip = surface.topology->flipped[k] ? -1.0 : 1.0;
      for (std::size_t s = 0; s < perFrame; ++s) {
        const std::size_t i = k * perFrame + s;
        const SampleGrid::Point& gp = grid.points[s];
        const SurfacePoint sp = surface.patches[k].evaluate(gp.u, gp.v);
        positions[i] = sp.p;
        e.du[i] = sp.du;
        e.dv[i] = sp.dv;
        const auto hit =
            hints ? target.tree.closest_point_and_primitive(
                        toPoint(sp.p), {toPoint(hints->pairs[i].target),
                                        target.triangles.cbegin() + hints->meshTriangle[i]})
                  : target.tree.closest_point_and_primitive(toPoint(sp.p));
        const auto t = static_cast<std::size_t>(hit.second - target.triangles.cbegin());
        e.meshTriangle[i] = static_cast<std::uint32_t>(t);
        const Vec3 foot = toVec(hit.first);
        const Vec3 normal = sp.du.cross(sp.dv);
        const double length = normal.norm();
        cosine[i] = length > 0.0 ? flip * normal.dot(target.normals[t]) / length : 0.0;
        Pair pair{k,
                  gp.u,
                  gp.v,
                  foot,
                  target.normals[t],
                  gp.weight * length,
                  static_cast<std::int64_t>(i)};
        const Triangle& tri = target.triangles[t];
        const Eigen::Vector3d l = barycentric(foot, toVec(tri[0]), toVec(tri[1]), toVec(tri[2]));
        // A foot on an edge or a corner of the triangle is as near to its neighbours: the
        // triangle's own normal is one of several, chosen by how the tree breaks the tie.
        // The direction from the foot to the sample is the distance's gradient there, the
        // same whichever triangle the tree returns.
        const Vec3 away = sp.p - foot;
        if (l.minCoeff() < kOnEdge && away.norm() > kOnEdge * target.diagonal)
          pair.normal = away.normalized();
        for (int c = 0; c < 3; ++c)
          if ((target.boundary[t] >> c & 1u) && l[c] < kOnBoundary) pair.normal.setZero();
        distances[i] = (foot - sp.p).norm();
        e.pairs[i] = pair;
      }
    }
  });
  double totalArea = 0.0, agreement = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    totalArea += e.pairs[i].weight;
    agreement += e.pairs[i].weight * cosine[i];
  }
  if (!(totalArea > 0.0)) throw InvalidArgument("the model's surface has no area");
  // Folds: samples that disagree with the orientation most of the surface agrees on.
  const double orientation = agreement < 0.0 ? -1.0 : 1.0;
  e.foldsPerFrame.assign(nFrames, 0);
  double sum = 0.0, sumSquares = 0.0, max = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    e.pairs[i].weight /= totalArea;
    sum += e.pairs[i].weight * distances[i];
    sumSquares += e.pairs[i].weight * distances[i] * distances[i];
    max = std::max(max, distances[i]);
    if (orientation * cosine[i] < 0.0) {
      ++e.foldsPerFrame[e.pairs[i].frame];
      e.measure.foldedArea += e.pairs[i].weight;
    }
  }
  e.orientation = orientation;
  e.measure.samples = static_cast<std::uint32_t>(count);
  for (std::uint32_t f : e.foldsPerFrame) e.measure.foldedSamples += f;
  e.measure.rmsToMesh = std::sqrt(sumSquares) / diag;
  e.measure.meanToMesh = sum / diag;
  e.measure.maxToMesh = max / diag;

  // Mesh vertices -> surface: the closest point on the sample grids' triangles, then
  // Gauss–Newton on that patch from there.
  Triangles cells;
  cells.reserve(std::size_t{nFrames} * 2 * (g - 1) * (g - 1));
  for (std::uint32_t k = 0; k < nFrames; ++k)
    for (std::uint32_t j = 0; j + 1 < g; ++j)
      for (std::uint32_t i = 0; i + 1 < g; ++i) {
        const Vec3* p = &positions[k * perFrame];
        const Point a = toPoint(p[j * g + i]), b = toPoint(p[j * g + i + 1]);
        const Point c = toPoint(p[(j + 1) * g + i + 1]), d = toPoint(p[(j + 1) * g + i]);
        cells.emplace_back(a, b, c);
        cells.emplace_back(a, c, d);
      }
  Tree onSurface(cells.cbegin(), cells.cend());
  onSurface.build();
  // Without hints, a k-d tree of the cells' points starts each query.
  if (!hints) onSurface.accelerate_distance_queries();
  const double cell = 1.0 / (g - 1);
  const FrameTopology& topo = *surface.topology;
  const std::size_t meshCount = target.samples.size();
  std::vector<double> meshDistances(meshCount);
  e.pairs.resize(count + meshCount);
  e.surfaceCell.resize(meshCount);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, meshCount), [&](const auto& range) {
    for (std::size_t m = range.begin(); m != range.end(); ++m) {
      const Vec3& x = target.samples[m];
      const std::uint32_t hint = hints ? hints->surfaceCell[m] : 0;
      const auto closest = hints ? onSurface.closest_point_and_primitive(
                                       toPoint(x), {cells[hint].vertex(0), cells.cbegin() + hint})
                                 : onSurface.closest_point_and_primitive(toPoint(x));
      const auto t = static_cast<std::size_t>(closest.second - cells.cbegin());
      e.surfaceCell[m] = static_cast<std::uint32_t>(t);
      const auto k = static_cast<std::uint32_t>(t / (2 * (g - 1) * (g - 1)));
      const std::size_t local = t % (2 * (g - 1) * (g - 1));
      const std::size_t i = (local / 2) % (g - 1), j = (local / 2) / (g - 1);
      // The cell's (u, v) at the closest point, from its barycentric coordinates.
      const Triangle& tri = cells[t];
      const Vec3 a = toVec(tri[0]), b = toVec(tri[1]), c = toVec(tri[2]);
      const Vec3 pc = toVec(closest.first);
      const double total = (b - a).cross(c - a).norm();
      double lb = 0.0, lc = 0.0;
      if (total > 0.0) {
        lb = (pc - a).cross(c - a).norm() / total;
        lc = (b - a).cross(pc - a).norm() / total;
      }
      // Corners in (u, v): a = (i, j); first triangle b = (i+1, j), c = (i+1, j+1);
      // second triangle b = (i+1, j+1), c = (i, j+1).
      double du, dv;
      if (local % 2 == 0)
        du = lb + lc, dv = lc;
      else
        du = lb, dv = lb + lc;
      double u = (static_cast<double>(i) + du) * cell, v = (static_cast<double>(j) + dv) * cell;
      const VertexFramePatch& patch = surface.patches[k];
      double best = (patch.position(u, v) - x).squaredNorm();
      double bu = u, bv = v;
      for (int step = 0; step < kProjectionSteps; ++step) {
        const SurfacePoint sp = patch.evaluate(u, v);
        const Vec3 r = sp.p - x;
        Eigen::Matrix2d jtj;
        jtj << sp.du.dot(sp.du), sp.du.dot(sp.dv), sp.du.dot(sp.dv), sp.dv.dot(sp.dv);
        const Eigen::Vector2d jtr(sp.du.dot(r), sp.dv.dot(r));
        if (!(jtj.determinant() > 0.0)) break;
        const Eigen::Vector2d delta = jtj.ldlt().solve(-jtr);
        u = std::clamp(u + delta.x(), 0.0, 1.0);
        v = std::clamp(v + delta.y(), 0.0, 1.0);
        const double d2 = (patch.position(u, v) - x).squaredNorm();
        if (d2 < best) best = d2, bu = u, bv = v;
      }
      meshDistances[m] = std::sqrt(best);
      const SurfacePoint foot = patch.evaluate(bu, bv);
      const Vec3 normal = foot.du.cross(foot.dv);
      const double length = normal.norm();
      // A foot on a side no other frame shares is on the surface's boundary.
      bool onBoundary = false;
      const std::array<bool, 4> atSide = {bv == 0.0, bu == 1.0, bv == 1.0, bu == 0.0};
      for (int side = 0; side < 4; ++side)
        if (atSide[side] && topo.edges[topo.edgeOf[k][side]].sideCount == 1) onBoundary = true;
      e.pairs[count + m] = {k,
                            bu,
                            bv,
                            x,
                            length > 0.0 && !onBoundary ? Vec3(normal / length) : Vec3::Zero(),
                            target.weights[m],
                            -1};
    }
  });
  sum = sumSquares = max = 0.0;
  for (std::size_t m = 0; m < meshCount; ++m) {
    const double w = target.weights[m], dist = meshDistances[m];
    sum += w * dist;
    sumSquares += w * dist * dist;
    max = std::max(max, dist);
  }
  e.measure.rmsToModel = std::sqrt(sumSquares) / diag;
  e.measure.meanToModel = sum / diag;
  e.measure.maxToModel = max / diag;
  e.surface = std::move(surface);
  return e;
}

}  // namespace pdesurf::fit
