// Mesh-to-mesh distances: area-weighted face samples, closest points by CGAL AABB trees.
#include "pdesurf/mesh_distance.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>
#include <Eigen/Geometry>

#include "numerics/triangle_tree.hpp"
#include "pdesurf/error.hpp"

namespace pdesurf {
namespace {

using detail::Point;
using detail::toPoint;
using detail::Tree;
using detail::Triangles;
constexpr auto vertex = &detail::meshVertex;

/// A mesh's triangles with area (corners not collinear in double arithmetic).
struct AreaTriangles {
  std::vector<std::array<Vec3, 3>> corners;
  std::vector<double> areas;
  double total = 0.0;
};

AreaTriangles areaTriangles(const Mesh& mesh, const char* which) {
  AreaTriangles out;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const std::array<Vec3, 3> p = {vertex(mesh, mesh.indices[3 * t]),
                                   vertex(mesh, mesh.indices[3 * t + 1]),
                                   vertex(mesh, mesh.indices[3 * t + 2])};
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    if (!(area > 0.0)) continue;
    out.corners.push_back(p);
    out.areas.push_back(area);
    out.total += area;
  }
  if (out.corners.empty())
    throw InvalidArgument(
        fmt::format("the {} mesh has no triangle with area ({} triangles, all degenerate)", which,
                    mesh.triangleCount()));
  return out;
}

double boxDiagonal(const Mesh& mesh) {
  if (mesh.indices.empty()) return 0.0;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::uint32_t v : mesh.indices) {
    lo = lo.cwiseMin(vertex(mesh, v));
    hi = hi.cwiseMax(vertex(mesh, v));
  }
  return (hi - lo).norm();
}

/// The AABB tree of B's triangles (which must outlive it), with its KD-tree of hints built.
class ClosestPoints {
 public:
  explicit ClosestPoints(const AreaTriangles& b) {
    triangles_.reserve(b.corners.size());
    for (const auto& p : b.corners)
      triangles_.emplace_back(toPoint(p[0]), toPoint(p[1]), toPoint(p[2]));
    tree_.insert(triangles_.cbegin(), triangles_.cend());
    tree_.build();
    tree_.accelerate_distance_queries();
  }
  Point closest(const Point& q) const { return tree_.closest_point(q); }
  /// Faster when `hint` is near the answer (the previous sample's closest point).
  Point closest(const Point& q, const Point& hint) const { return tree_.closest_point(q, hint); }
  /// The index (into the AreaTriangles it was built from) of a triangle closest to q.
  std::size_t closestTriangle(const Point& q) const {
    return static_cast<std::size_t>(tree_.closest_point_and_primitive(q).second -
                                    triangles_.cbegin());
  }

 private:
  Triangles triangles_;
  Tree tree_;
};

/// The running measures of a range of samples. Ranges are fixed blocks of the input, each
/// tallied alone and merged in order, so the result does not depend on the thread count.
struct Tally {
  std::size_t samples = 0;
  double sum = 0.0, sumSquares = 0.0;  ///< area-weighted, face samples only
  double max = -1.0, coverRadius = 0.0;
  Vec3 maxAt = Vec3::Zero();

  void add(const Vec3& p, double dist) {
    if (dist > max) max = dist, maxAt = p;
    ++samples;
  }
  void merge(const Tally& o) {
    samples += o.samples;
    sum += o.sum;
    sumSquares += o.sumSquares;
    coverRadius = std::max(coverRadius, o.coverRadius);
    if (o.max > max) max = o.max, maxAt = o.maxAt;
  }
};

/// Vertices and triangles per block of work.
constexpr std::size_t kVertexBlock = 4096, kTriangleBlock = 512;

/// Samples A (as in DistanceOptions) and measures each sample's distance to B.
OneWayDistance oneWay(const Mesh& a, const AreaTriangles& at, const ClosestPoints& b,
                      double diagonal, const DistanceOptions& options) {
  // The vertices that triangles use, each once.
  std::vector<std::uint32_t> vertices;
  {
    std::vector<std::uint8_t> seen(a.vertexCount(), 0);
    for (std::uint32_t v : a.indices)
      if (!seen[v]) seen[v] = 1, vertices.push_back(v);
  }
  const double minK = std::ceil(
      std::sqrt(static_cast<double>(std::max<std::uint32_t>(1, options.minSamplesPerTriangle))));
  const double perArea = static_cast<double>(options.samples) / at.total;

  auto vertexBlock = [&](std::size_t first, std::size_t last, Tally& tally) {
    for (std::size_t i = first; i < last; ++i) {
      const Vec3 p = vertex(a, vertices[i]);
      const Point q = toPoint(p);
      tally.add(p, std::sqrt(CGAL::squared_distance(q, b.closest(q))));
    }
  };
  // Faces: k² similar sub-triangles, each sampled at its centroid with weight area / k².
  auto triangleBlock = [&](std::size_t first, std::size_t last, Tally& tally) {
    for (std::size_t t = first; t < last; ++t) {
      const auto& [p0, p1, p2] = at.corners[t];
      const double kd = std::max(minK, std::ceil(std::sqrt(perArea * at.areas[t])));
      const int k = static_cast<int>(kd);
      const Vec3 e1 = (p1 - p0) / kd, e2 = (p2 - p0) / kd;
      const double weight = at.areas[t] / (kd * kd);
      const Vec3 g = (p0 + p1 + p2) / 3.0;
      tally.coverRadius = std::max(
          tally.coverRadius, std::max({(p0 - g).norm(), (p1 - g).norm(), (p2 - g).norm()}) / kd);
      // Neighbouring samples have neighbouring closest points: each one's is the next hint.
      Point hint = b.closest(toPoint(p0 + (e1 + e2) / 3.0));
      auto sample = [&](double s, double r) {
        const Vec3 p = p0 + s * e1 + r * e2;
        const Point q = toPoint(p);
        hint = b.closest(q, hint);
        const double dist = std::sqrt(CGAL::squared_distance(q, hint));
        tally.sum += weight * dist;
        tally.sumSquares += weight * dist * dist;
        tally.add(p, dist);
      };
      for (int i = 0; i < k; ++i)
        for (int j = 0; i + j < k; ++j) {
          sample(i + 1.0 / 3.0, j + 1.0 / 3.0);                     // upward sub-triangle
          if (i + j + 1 < k) sample(i + 2.0 / 3.0, j + 2.0 / 3.0);  // downward one
        }
    }
  };

  const std::size_t vertexBlocks = (vertices.size() + kVertexBlock - 1) / kVertexBlock;
  const std::size_t blocks =
      vertexBlocks + (at.corners.size() + kTriangleBlock - 1) / kTriangleBlock;
  std::vector<Tally> tallies(blocks);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t i) {
    if (i < vertexBlocks) {
      vertexBlock(i * kVertexBlock, std::min(vertices.size(), (i + 1) * kVertexBlock), tallies[i]);
    } else {
      const std::size_t j = i - vertexBlocks;
      triangleBlock(j * kTriangleBlock, std::min(at.corners.size(), (j + 1) * kTriangleBlock),
                    tallies[i]);
    }
  });

  Tally total;
  for (const Tally& tally : tallies) total.merge(tally);
  OneWayDistance d;
  d.samples = total.samples;
  d.max = total.max;
  d.maxAt = total.maxAt;
  d.coverRadius = total.coverRadius;
  d.mean = total.sum / at.total;
  d.rms = std::sqrt(total.sumSquares / at.total);
  const double scale = diagonal > 0.0 ? 1.0 / diagonal : 1.0;
  d.meanRelative = d.mean * scale;
  d.rmsRelative = d.rms * scale;
  d.maxRelative = d.max * scale;
  return d;
}

/// Runs `work` on `threads` threads (0: as many as oneTBB allows: all cores, or the CLI's
/// --threads).
template <class Work>
void withThreads(unsigned threads, Work&& work) {
  if (threads > 0)
    tbb::task_arena(static_cast<int>(threads)).execute(work);
  else
    work();
}

}  // namespace

MeshDistance meshDistance(const Mesh& a, const Mesh& b, const DistanceOptions& options) {
  const AreaTriangles at = areaTriangles(a, "first"), bt = areaTriangles(b, "second");
  MeshDistance result;
  result.diagonal = boxDiagonal(b);
  auto work = [&] {
    // Both trees at once (each build is serial in CGAL), then each way's samples in parallel.
    std::optional<ClosestPoints> onA, onB;
    tbb::parallel_invoke([&] { onB.emplace(bt); }, [&] { onA.emplace(at); });
    result.aToB = oneWay(a, at, *onB, result.diagonal, options);
    result.bToA = oneWay(b, bt, *onA, result.diagonal, options);
  };
  withThreads(options.threads, work);
  result.hausdorff = std::max(result.aToB.max, result.bToA.max);
  result.hausdorffRelative =
      result.diagonal > 0.0 ? result.hausdorff / result.diagonal : result.hausdorff;
  return result;
}

NormalDeviation normalDeviation(const Mesh& a, const Mesh& b, unsigned threads) {
  const AreaTriangles at = areaTriangles(a, "first"), bt = areaTriangles(b, "second");
  // Per triangle of A: the cosine between its normal and that of B's triangle closest to
  // its centroid.
  std::vector<double> cosine(at.corners.size());
  withThreads(threads, [&] {
    const ClosestPoints onB(bt);
    tbb::parallel_for(std::size_t{0}, at.corners.size(), [&](std::size_t t) {
      const auto& [p0, p1, p2] = at.corners[t];
      const std::size_t u = onB.closestTriangle(toPoint((p0 + p1 + p2) / 3.0));
      const auto& [q0, q1, q2] = bt.corners[u];
      cosine[t] = std::clamp(
          (p1 - p0).cross(p2 - p0).normalized().dot((q1 - q0).cross(q2 - q0).normalized()), -1.0,
          1.0);
    });
  });
  double agreement = 0.0;
  for (std::size_t t = 0; t < cosine.size(); ++t) agreement += at.areas[t] * cosine[t];
  NormalDeviation result;
  result.reversed = agreement < 0.0;
  const double sign = result.reversed ? -1.0 : 1.0;
  double folded = 0.0, squares = 0.0;
  for (std::size_t t = 0; t < cosine.size(); ++t) {
    const double c = sign * cosine[t];
    if (c < 0.0) folded += at.areas[t];
    const double angle = std::acos(c) * 180.0 / std::numbers::pi;
    squares += at.areas[t] * angle * angle;
  }
  result.foldedArea = folded / at.total;
  result.rmsDegrees = std::sqrt(squares / at.total);
  return result;
}

}  // namespace pdesurf
