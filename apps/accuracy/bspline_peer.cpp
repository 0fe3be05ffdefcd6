// The NURBS peer: bicubic B-splines fitted by linear least squares on a layout's
// parameterisation, the coarsest net within a target RMS (apps/accuracy/peers.hpp).
#include <algorithm>
#include <array>
#include <cmath>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <fmt/format.h>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "peers.hpp"

namespace pdesurf {

namespace {

// The fine grid's triangles in CGAL's AABB tree, for the samples' closest points (the peer
// uses CGAL itself, as polygon_peer.cpp does: the library's tree is private to it).
using Cgal = CGAL::Simple_cartesian<double>;
using GridTriangles = std::vector<Cgal::Triangle_3>;
using GridTree = CGAL::AABB_tree<
    CGAL::AABB_traits<Cgal, CGAL::AABB_triangle_primitive<Cgal, GridTriangles::const_iterator>>>;
Cgal::Point_3 cgalPoint(const Vec3& p) { return {p.x(), p.y(), p.z()}; }
Vec3 fromCgal(const Cgal::Point_3& p) { return {p.x(), p.y(), p.z()}; }

/// The four cubic basis functions that are non-zero at t and the first control index they
/// weigh (the others follow, mod n where the direction is closed).
struct Basis {
  std::uint32_t first = 0;
  std::array<double, 4> w{};
};

/// Uniform knots: periodic with n spans when closed; else clamped (end knots of
/// multiplicity 4) with n − 3 spans. Cox–de Boor's recurrence (Piegl & Tiller, A2.2).
Basis basisAt(double t, std::uint32_t n, bool closed) {
  Basis b;
  if (closed) {
    double x = t * n;
    x -= n * std::floor(x / n);
    const auto s = std::min(static_cast<std::uint32_t>(x), n - 1);
    const double f = x - s, g = 1.0 - f;
    b.first = s;
    b.w = {g * g * g / 6.0, (3 * f * f * f - 6 * f * f + 4) / 6.0,
           (-3 * f * f * f + 3 * f * f + 3 * f + 1) / 6.0, f * f * f / 6.0};
    return b;
  }
  const std::uint32_t spans = n - 3;
  auto knot = [&](int i) { return std::clamp(static_cast<double>(i - 3) / spans, 0.0, 1.0); };
  t = std::clamp(t, 0.0, 1.0);
  const int k = 3 + static_cast<int>(std::min<double>(std::floor(t * spans), spans - 1));
  std::array<double, 4> left{}, right{};
  b.w[0] = 1.0;
  for (int j = 1; j <= 3; ++j) {
    left[j] = t - knot(k + 1 - j);
    right[j] = knot(k + j) - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = b.w[r] / (right[r + 1] + left[j - r]);
      b.w[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    b.w[j] = saved;
  }
  b.first = static_cast<std::uint32_t>(k - 3);
  return b;
}

/// Control points along a direction of `spans` spans.
std::uint32_t controlCount(std::uint32_t spans, bool closed) {
  return closed ? std::max(spans, 4u) : spans + 3;
}

}  // namespace

Vec3 BSplineGrid::position(double u, double v) const {
  const Basis bu = basisAt(u, nu, closedU), bv = basisAt(v, nv, closedV);
  Vec3 p = Vec3::Zero();
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a)
      p += bu.w[a] * bv.w[b] * control[((bv.first + b) % nv) * nu + (bu.first + a) % nu];
  return p;
}

Mesh tessellate(const BSplineGrid& s, std::uint32_t samplesU, std::uint32_t samplesV) {
  Mesh out;
  auto param = [](std::uint32_t i, std::uint32_t n, bool closed) {
    return closed ? double(i) / n : double(i) / (n - 1);
  };
  for (std::uint32_t j = 0; j < samplesV; ++j)
    for (std::uint32_t i = 0; i < samplesU; ++i) {
      const Vec3 p = s.position(param(i, samplesU, s.closedU), param(j, samplesV, s.closedV));
      for (int c = 0; c < 3; ++c) out.positions.push_back(static_cast<float>(p[c]));
    }
  auto at = [&](std::uint32_t i, std::uint32_t j) {
    return (j % samplesV) * samplesU + i % samplesU;
  };
  const std::uint32_t cu = s.closedU ? samplesU : samplesU - 1;
  const std::uint32_t cv = s.closedV ? samplesV : samplesV - 1;
  for (std::uint32_t j = 0; j < cv; ++j)
    for (std::uint32_t i = 0; i < cu; ++i)
      out.indices.insert(out.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j),
                                             at(i + 1, j + 1), at(i, j + 1)});
  return out;
}

std::size_t storageBytes(const BSplineGrid& s) {
  std::size_t bytes = fmt::formatted_size("{} {}\n", s.nu, s.nv);
  for (const Vec3& p : s.control)
    bytes += fmt::formatted_size("{:.6g} {:.6g} {:.6g} ", p.x(), p.y(), p.z());
  return bytes;
}

BSplineGrid fitBSpline(std::span<const ParamSample> samples, std::uint32_t nu, std::uint32_t nv,
                       bool closedU, bool closedV, double smoothness) {
  BSplineGrid out;
  out.nu = nu;
  out.nv = nv;
  out.closedU = closedU;
  out.closedV = closedV;
  const Eigen::Index unknowns = Eigen::Index{nu} * nv;
  // The design matrix (16 basis products a sample) scaled by sqrt(weight): its normal
  // equations are the weighted data term.
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(samples.size() * 16);
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(samples.size()), 3);
  double totalWeight = 0.0;
  for (std::size_t row = 0; row < samples.size(); ++row) {
    const ParamSample& s = samples[row];
    const Basis bu = basisAt(s.u, nu, closedU), bv = basisAt(s.v, nv, closedV);
    const double root = std::sqrt(s.weight);
    for (int b = 0; b < 4; ++b)
      for (int a = 0; a < 4; ++a)
        triplets.emplace_back(static_cast<Eigen::Index>(row),
                              Eigen::Index{(bv.first + b) % nv} * nu + (bu.first + a) % nu,
                              root * bu.w[a] * bv.w[b]);
    points.row(static_cast<Eigen::Index>(row)) = root * s.p.transpose();
    totalWeight += s.weight;
  }
  Eigen::SparseMatrix<double> design(static_cast<Eigen::Index>(samples.size()), unknowns);
  design.setFromTriplets(triplets.begin(), triplets.end());  // repeated entries add up
  const Eigen::MatrixX3d rhs = design.transpose() * points;
  triplets.clear();
  // Second differences of the net along u and v (wrapping where closed): they hold control
  // points that few samples see, and change the fit by about `smoothness` elsewhere.
  const double lambda = smoothness * totalWeight;
  auto difference = [&](std::array<Eigen::Index, 3> i) {
    const std::array<double, 3> c{1.0, -2.0, 1.0};
    for (int x = 0; x < 3; ++x)
      for (int y = 0; y < 3; ++y) triplets.emplace_back(i[x], i[y], lambda * c[x] * c[y]);
  };
  for (std::uint32_t j = 0; j < nv; ++j)
    for (std::uint32_t i = 0; i < nu; ++i) {
      if (closedU || i + 2 < nu)
        difference({j * nu + i, j * nu + (i + 1) % nu, j * nu + (i + 2) % nu});
      if (closedV || j + 2 < nv)
        difference({j * nu + i, ((j + 1) % nv) * nu + i, ((j + 2) % nv) * nu + i});
    }
  Eigen::SparseMatrix<double> smooth(unknowns, unknowns);
  smooth.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::SparseMatrix<double> normal =
      Eigen::SparseMatrix<double>(design.transpose() * design) + smooth;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  if (solver.info() != Eigen::Success)
    throw InvalidArgument(fmt::format(
        "the least-squares system of a {} × {} B-spline net is singular: too few samples", nu, nv));
  const Eigen::MatrixX3d x = solver.solve(rhs);
  out.control.resize(unknowns);
  for (Eigen::Index i = 0; i < unknowns; ++i) out.control[i] = x.row(i).transpose();
  return out;
}

std::vector<ParamSample> layoutSamples(const VertexFrameSurface& surface, const LayoutGrid& grid,
                                       const Mesh& truth, std::size_t samples) {
  // Each patch as a fine grid of triangles whose corners know their (frame, u, v).
  constexpr std::uint32_t kPerSide = 17;
  struct Corner {
    std::uint32_t frame;
    double u, v;
  };
  std::vector<Corner> corners;
  GridTriangles triangles;
  std::vector<std::array<std::uint32_t, 3>> cornerOf;
  for (std::uint32_t k = 0; k < surface.patches.size(); ++k) {
    const auto base = static_cast<std::uint32_t>(corners.size());
    std::vector<Vec3> p;
    for (std::uint32_t j = 0; j < kPerSide; ++j)
      for (std::uint32_t i = 0; i < kPerSide; ++i) {
        const double u = double(i) / (kPerSide - 1), v = double(j) / (kPerSide - 1);
        corners.push_back({k, u, v});
        p.push_back(surface.patches[k].position(u, v));
      }
    auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      triangles.emplace_back(cgalPoint(p[a]), cgalPoint(p[b]), cgalPoint(p[c]));
      cornerOf.push_back({base + a, base + b, base + c});
    };
    for (std::uint32_t j = 0; j + 1 < kPerSide; ++j)
      for (std::uint32_t i = 0; i + 1 < kPerSide; ++i) {
        const std::uint32_t a = j * kPerSide + i;
        add(a, a + 1, a + 1 + kPerSide);
        add(a, a + 1 + kPerSide, a + kPerSide);
      }
  }
  GridTree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();

  // The truth's samples: triangle t cut into k_t² similar pieces, sampled at their centroids,
  // k_t = ceil(sqrt(samples · area_t / area)), each weighted by the area it stands for.
  auto vertex = [&](std::uint32_t i) {
    return Vec3(truth.positions[3 * i], truth.positions[3 * i + 1], truth.positions[3 * i + 2]);
  };
  double area = 0.0;
  for (std::size_t t = 0; t < truth.triangleCount(); ++t) {
    const Vec3 a = vertex(truth.indices[3 * t]), b = vertex(truth.indices[3 * t + 1]),
               c = vertex(truth.indices[3 * t + 2]);
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  std::vector<ParamSample> out;
  out.reserve(samples + truth.triangleCount());
  for (std::size_t t = 0; t < truth.triangleCount(); ++t) {
    const Vec3 a = vertex(truth.indices[3 * t]), b = vertex(truth.indices[3 * t + 1]),
               c = vertex(truth.indices[3 * t + 2]);
    const double at = 0.5 * (b - a).cross(c - a).norm();
    if (!(at > 0.0)) continue;
    const int k = std::max(
        1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(samples) * at / area))));
    const double w = at / (k * k);
    // Sub-triangle centroids: upright ones at (i + 1/3, j + 1/3), inverted at (i + 2/3, j + 2/3).
    for (int j = 0; j < k; ++j)
      for (int i = 0; i + j < k; ++i)
        for (int flip = 0; flip < (i + j + 1 < k ? 2 : 1); ++flip) {
          const double s = (i + (flip ? 2.0 : 1.0) / 3.0) / k,
                       r = (j + (flip ? 2.0 : 1.0) / 3.0) / k;
          out.push_back({0.0, 0.0, a + s * (b - a) + r * (c - a), w});
        }
  }
  // Each sample's parameter: its closest point's (u, v) on the fine grid, refined by
  // Gauss–Newton on the patch (kept inside it), mapped through the layout's grid.
  constexpr int kRefineSteps = 4;
  for (ParamSample& s : out) {
    const auto [point, primitive] = tree.closest_point_and_primitive(cgalPoint(s.p));
    const auto t = static_cast<std::size_t>(primitive - triangles.cbegin());
    const Cgal::Triangle_3& tri = triangles[t];
    // Barycentric coordinates of the closest point in its triangle.
    const Vec3 p0 = fromCgal(tri[0]), e1 = fromCgal(tri[1]) - p0, e2 = fromCgal(tri[2]) - p0,
               d = fromCgal(point) - p0;
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
    const double det = d11 * d22 - d12 * d12;
    const double l1 = det > 0 ? (d22 * e1.dot(d) - d12 * e2.dot(d)) / det : 0.0;
    const double l2 = det > 0 ? (d11 * e2.dot(d) - d12 * e1.dot(d)) / det : 0.0;
    const Corner& c0 = corners[cornerOf[t][0]];
    const Corner& c1 = corners[cornerOf[t][1]];
    const Corner& c2 = corners[cornerOf[t][2]];
    double u = c0.u + l1 * (c1.u - c0.u) + l2 * (c2.u - c0.u);
    double v = c0.v + l1 * (c1.v - c0.v) + l2 * (c2.v - c0.v);
    const VertexFramePatch& patch = surface.patches[c0.frame];
    for (int step = 0; step < kRefineSteps; ++step) {
      const SurfacePoint x = patch.evaluate(u, v);
      Eigen::Matrix<double, 3, 2> jac;
      jac << x.du, x.dv;
      const Eigen::Vector2d delta =
          (jac.transpose() * jac).ldlt().solve(jac.transpose() * (s.p - x.p));
      if (!delta.allFinite()) break;
      u = std::clamp(u + delta.x(), 0.0, 1.0);
      v = std::clamp(v + delta.y(), 0.0, 1.0);
    }
    s.u = (c0.frame % grid.columns + u) / grid.columns;
    s.v = (c0.frame / grid.columns + v) / grid.rows;
  }
  return out;
}

NurbsPeer bsplinePeer(std::span<const ParamSample> samples, const LayoutGrid& grid,
                      const Mesh& truth, double targetRms, const DistanceOptions& distance,
                      std::size_t maxControlPoints) {
  const double longer = std::max(grid.columns, grid.rows);
  auto net = [&](std::uint32_t m) {
    const auto su =
        std::max(1u, static_cast<std::uint32_t>(std::lround(m * grid.columns / longer)));
    const auto sv = std::max(1u, static_cast<std::uint32_t>(std::lround(m * grid.rows / longer)));
    return std::pair{controlCount(su, grid.closedU), controlCount(sv, grid.closedV)};
  };
  // No more control points than a quarter of the samples: the fit stays overdetermined.
  const std::size_t limit = std::min(maxControlPoints, samples.size() / 4);
  NurbsPeer best, last;
  auto trial = [&](std::uint32_t m) {
    NurbsPeer p;
    const auto [nu, nv] = net(m);
    p.surface = fitBSpline(samples, nu, nv, grid.closedU, grid.closedV);
    // 8 samples a span (at least 65 a side): the chords stay far below the distances.
    const Mesh mesh = tessellate(p.surface, std::max(65u, 8 * nu + 1), std::max(65u, 8 * nv + 1));
    p.rms = accuracyRms(mesh, truth, distance);
    p.bytes = storageBytes(p.surface);
    p.reached = p.rms <= targetRms;
    return p;
  };
  std::uint32_t trials = 0;
  // Doubling until the target is met or the net is too large, then bisection on (lo, hi].
  std::uint32_t lo = 0, hi = 0;
  double loRms = 0.0;
  for (std::uint32_t m = 1;; m *= 2) {
    const auto [nu, nv] = net(m);
    if (std::size_t{nu} * nv > limit) break;
    NurbsPeer p = trial(m);
    ++trials;
    if (p.reached) {
      hi = m;
      best = std::move(p);
      break;
    }
    lo = m;
    loRms = p.rms;
    last = std::move(p);
  }
  if (hi == 0) {  // unreachable within the limit: the finest net tried
    last.trials = trials;
    last.coarserRms = 0.0;
    return last;
  }
  while (hi - lo > 1) {
    const std::uint32_t mid = lo + (hi - lo) / 2;
    NurbsPeer p = trial(mid);
    ++trials;
    if (p.reached) {
      hi = mid;
      best = std::move(p);
    } else {
      lo = mid;
      loRms = p.rms;
    }
  }
  best.coarserRms = lo > 0 ? loRms : 0.0;
  best.trials = trials;
  return best;
}

}  // namespace pdesurf
