// Patches as clamped bicubic B-spline surfaces: exact conversions (Bézier form of the
// vertex-frame polynomial, clamping of uniform B-splines) and the interpolating
// approximation with its measured deviation (docs/nurbs-export.md).
#include "numerics/eigen_warnings.hpp"  // first: before Eigen

#include "pdesurf/nurbs.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <Eigen/LU>

#include "pdesurf/analysis.hpp"

namespace pdesurf {

namespace {

constexpr std::uint32_t kMaxDegree = 3;

/// The knot span index s with knots[s] ≤ t < knots[s+1] among the `count` poles' spans
/// (the last span at the domain's end), for a clamped knot vector.
std::uint32_t findSpan(std::span<const double> knots, std::uint32_t degree, std::uint32_t count,
                       double t) {
  if (t >= knots[count]) return count - 1;
  if (t <= knots[degree]) return degree;
  const auto it = std::upper_bound(knots.begin() + degree, knots.begin() + count + 1, t);
  return static_cast<std::uint32_t>(it - knots.begin()) - 1;
}

/// Values and first derivatives of the degree + 1 basis functions acting on span s at t
/// (Piegl & Tiller A2.3, first derivative only): N_{s-degree+r} = value[r].
struct BasisRow {
  std::array<double, kMaxDegree + 1> value{}, slope{};
};

BasisRow basisRow(std::span<const double> knots, std::uint32_t degree, std::uint32_t s, double t) {
  BasisRow row;
  // ndu[j][r]: the triangular table of A2.3 (values above the diagonal, knot differences below).
  double ndu[kMaxDegree + 1][kMaxDegree + 1];
  double left[kMaxDegree + 1], right[kMaxDegree + 1];
  ndu[0][0] = 1.0;
  for (std::uint32_t j = 1; j <= degree; ++j) {
    left[j] = t - knots[s + 1 - j];
    right[j] = knots[s + j] - t;
    double saved = 0.0;
    for (std::uint32_t r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (std::uint32_t r = 0; r <= degree; ++r) row.value[r] = ndu[r][degree];
  if (degree == 0) return row;
  // First derivative: p (N_{r,p-1}/(t_{r+p} - t_r) - N_{r+1,p-1}/(t_{r+p+1} - t_{r+1})).
  for (std::uint32_t r = 0; r <= degree; ++r) {
    double d = 0.0;
    if (r >= 1) d += ndu[r - 1][degree - 1] / ndu[degree][r - 1];
    if (r <= degree - 1) d -= ndu[r][degree - 1] / ndu[degree][r];
    row.slope[r] = static_cast<double>(degree) * d;
  }
  return row;
}

/// Clamped cubic knots over [a, b] with about `spans` spans: a triple knot at each crease
/// strictly inside (a, b), each piece between creases cut into uniform spans in proportion
/// to its length (at least one).
std::vector<double> creasedKnots(double a, double b, std::vector<double> creases,
                                 std::uint32_t spans) {
  std::erase_if(creases, [&](double c) { return !(c > a && c < b); });
  std::sort(creases.begin(), creases.end());
  creases.erase(std::unique(creases.begin(), creases.end()), creases.end());
  std::vector<double> breaks{a};
  breaks.insert(breaks.end(), creases.begin(), creases.end());
  breaks.push_back(b);
  std::vector<double> knots(4, a);
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double x0 = breaks[k], x1 = breaks[k + 1];
    const auto n = std::max<std::uint32_t>(
        1, static_cast<std::uint32_t>(std::lround(spans * (x1 - x0) / (b - a))));
    for (std::uint32_t i = 1; i < n; ++i) knots.push_back(x0 + (x1 - x0) * i / n);
    if (k + 2 < breaks.size()) knots.insert(knots.end(), 3, x1);
  }
  knots.insert(knots.end(), 4, b);
  return knots;
}

/// The check parameters of a knot vector: each non-empty span at `perSpan` + 1 points.
std::vector<double> checkParameters(const std::vector<double>& knots, std::uint32_t perSpan) {
  std::vector<double> ts{knots.front()};
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    if (!(knots[k + 1] > knots[k])) continue;
    for (std::uint32_t i = 1; i <= perSpan; ++i)
      ts.push_back(i == perSpan ? knots[k + 1]
                                : knots[k] + (knots[k + 1] - knots[k]) * i / perSpan);
  }
  return ts;
}

/// Greville abscissae (t_{i+1} + t_{i+2} + t_{i+3}) / 3 of a cubic knot vector.
std::vector<double> greville(const std::vector<double>& knots) {
  std::vector<double> g(knots.size() - 4);
  for (std::size_t i = 0; i < g.size(); ++i)
    g[i] = (knots[i + 1] + knots[i + 2] + knots[i + 3]) / 3;
  g.front() = knots.front();
  g.back() = knots.back();
  return g;
}

/// The collocation matrix A(k, i) = N_i(t_k) of cubic knots at the parameters.
Eigen::MatrixXd collocation(const std::vector<double>& knots, const std::vector<double>& ts) {
  const auto count = static_cast<std::uint32_t>(knots.size() - 4);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(ts.size()), count);
  for (std::size_t k = 0; k < ts.size(); ++k) {
    const std::uint32_t s = findSpan(knots, 3, count, ts[k]);
    const BasisRow row = basisRow(knots, 3, s, ts[k]);
    for (std::uint32_t r = 0; r <= 3; ++r)
      a(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(s - 3 + r)) = row.value[r];
  }
  return a;
}

/// Inserts knot x into a cubic curve's knots and poles once (Boehm).
template <typename Point>
void insertKnot(std::vector<double>& knots, std::vector<Point>& poles, double x) {
  constexpr std::uint32_t p = 3;
  const auto count = static_cast<std::uint32_t>(poles.size());
  // Span k with t_k ≤ x < t_{k+1} (the last non-empty one at the end).
  std::uint32_t k = p;
  while (k + 1 < count && knots[k + 1] <= x) ++k;
  std::vector<Point> out;
  out.reserve(count + 1);
  for (std::uint32_t i = 0; i <= count; ++i) {
    if (i + p <= k) {
      out.push_back(poles[i]);
    } else if (i > k) {
      out.push_back(poles[i - 1]);
    } else {
      const double alpha = (x - knots[i]) / (knots[i + p] - knots[i]);
      out.push_back(alpha * poles[i] + (1.0 - alpha) * poles[i - 1]);
    }
  }
  knots.insert(knots.begin() + k + 1, x);
  poles = std::move(out);
}

/// The cubic curve (knots, poles) clamped to [a, b] (knots already in the vector): the
/// knots a and b raised to multiplicity 3, then the poles whose support misses [a, b]
/// dropped. Returns the clamped knots; `poles` becomes the clamped poles.
template <typename Point>
std::vector<double> clampCurve(std::vector<double> knots, std::vector<Point>& poles, double a,
                               double b) {
  auto multiplicity = [&](double x) { return std::count(knots.begin(), knots.end(), x); };
  while (multiplicity(a) < 3) insertKnot(knots, poles, a);
  while (multiplicity(b) < 3) insertKnot(knots, poles, b);
  // The first knot equal to a at index f with multiplicity m: the clamped curve starts at
  // pole f + m - 4 (m = 3: the pole the curve passes through at a).
  const auto first =
      static_cast<std::size_t>(std::find(knots.begin(), knots.end(), a) - knots.begin());
  const auto m = static_cast<std::size_t>(multiplicity(a));
  assert(m == 3 || m == 4);
  const std::size_t start = first + m - 4;
  std::vector<double> clamped(4, a);
  for (double t : knots)
    if (t > a && t < b) clamped.push_back(t);
  clamped.insert(clamped.end(), 4, b);
  const std::size_t count = clamped.size() - 4;
  poles = std::vector<Point>(poles.begin() + static_cast<std::ptrdiff_t>(start),
                             poles.begin() + static_cast<std::ptrdiff_t>(start + count));
  return clamped;
}

double binomial(int n, int k) {
  double r = 1.0;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

/// The patch at every (us[i], vs[j]), out[i * vs.size() + j]: through its grid evaluation
/// when it has one.
std::vector<Vec3> sampleGrid(const PatchFunction& f, std::span<const double> us,
                             std::span<const double> vs) {
  std::vector<Vec3> out;
  if (f.grid) {
    f.grid(us, vs, out);
    return out;
  }
  out.reserve(us.size() * vs.size());
  for (double u : us)
    for (double v : vs) out.push_back(f.position(u, v));
  return out;
}

/// max |surface - patch| over the grid us × vs (the same parameters on both).
double gridDeviation(const NurbsSurface& s, const PatchFunction& f, std::span<const double> us,
                     std::span<const double> vs) {
  const std::vector<Vec3> want = sampleGrid(f, us, vs);
  double worst = 0.0;
  for (std::size_t i = 0; i < us.size(); ++i)
    for (std::size_t j = 0; j < vs.size(); ++j)
      worst = std::max(worst, (s.position(us[i], vs[j]) - want[i * vs.size() + j]).norm());
  return worst;
}

/// Bounding-box diagonal of patches sampled on a grid.
double sampledDiagonal(std::span<const PatchFunction> patches, std::uint32_t samples) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const PatchFunction& f : patches) {
    std::vector<double> us(samples), vs(samples);
    for (std::uint32_t i = 0; i < samples; ++i) {
      us[i] = f.u0 + (f.u1 - f.u0) * i / (samples - 1.0);
      vs[i] = f.v0 + (f.v1 - f.v0) * i / (samples - 1.0);
    }
    for (const Vec3& p : sampleGrid(f, us, vs)) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  return patches.empty() ? 0.0 : (hi - lo).norm();
}

/// Samples per side of the grid that measures an exact face's deviation.
constexpr std::uint32_t kExactCheckSamples = 33;
/// Samples per side for the model's bounding box (spectral and approximated models).
constexpr std::uint32_t kBoxSamples = 65;

/// The tolerance to use: the given one, or the default relative to the diagonal (a flat
/// point-like model keeps a tiny positive tolerance rather than 0).
double absoluteTolerance(const NurbsExportOptions& options, double diagonal) {
  if (options.tolerance > 0.0) return options.tolerance;
  return kDefaultRelativeExportTolerance * (diagonal > 0.0 ? diagonal : 1.0);
}

NurbsFace approximateFace(const PatchFunction& f, std::uint32_t index, double tolerance,
                          const NurbsExportOptions& exportOptions, ApproximationOptions options) {
  options.tolerance = tolerance;
  options.maxSpans =
      std::max({exportOptions.maxSpans, options.initialUSpans, options.initialVSpans});
  Approximation a = approximate(f, options);
  if (!a.withinTolerance && exportOptions.keepBest)
    return {std::move(a.surface), index, false, a.deviation, false};
  if (!a.withinTolerance)
    throw NurbsToleranceError(fmt::format(
        "patch {}: the closest bicubic B-spline of up to {} spans per direction deviates by "
        "{:.3g}, more than half the tolerance {:.3g} (the margin kept for the points between "
        "checks): give a larger --tolerance",
        index, options.maxSpans, a.deviation, tolerance));
  return {std::move(a.surface), index, false, a.deviation};
}

}  // namespace

SurfacePoint NurbsSurface::evaluate(double u, double v) const {
  u = std::clamp(u, uMin(), uMax());
  v = std::clamp(v, vMin(), vMax());
  const std::uint32_t su = findSpan(uKnots, uDegree, uCount, u);
  const std::uint32_t sv = findSpan(vKnots, vDegree, vCount, v);
  const BasisRow bu = basisRow(uKnots, uDegree, su, u);
  const BasisRow bv = basisRow(vKnots, vDegree, sv, v);
  SurfacePoint r{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  for (std::uint32_t a = 0; a <= uDegree; ++a) {
    Vec3 row = Vec3::Zero(), rowDv = Vec3::Zero();
    for (std::uint32_t b = 0; b <= vDegree; ++b) {
      const Vec3& p = pole(su - uDegree + a, sv - vDegree + b);
      row += bv.value[b] * p;
      rowDv += bv.slope[b] * p;
    }
    r.p += bu.value[a] * row;
    r.du += bu.slope[a] * row;
    r.dv += bu.value[a] * rowDv;
  }
  return r;
}

NurbsSurface bezierPatch(const VertexFramePatch& patch) {
  // Monomial coefficients C(a, b) of u^a v^b (seed eq. 4 order: 1, u, u², u³, v, v², v³,
  // uv, u²v, uv²).
  std::array<std::array<Vec3, 4>, 4> c;
  for (auto& row : c) row.fill(Vec3::Zero());
  const auto& k = patch.c;
  c[0][0] = k[0], c[1][0] = k[1], c[2][0] = k[2], c[3][0] = k[3];
  c[0][1] = k[4], c[0][2] = k[5], c[0][3] = k[6];
  c[1][1] = k[7], c[2][1] = k[8], c[1][2] = k[9];
  // t^a = Σ_{i ≥ a} binom(i,a)/binom(3,a) B_i(t): P_{ij} = Σ M(i,a) M(j,b) C(a,b).
  double m[4][4] = {};
  for (int i = 0; i < 4; ++i)
    for (int a = 0; a <= i; ++a) m[i][a] = binomial(i, a) / binomial(3, a);
  NurbsSurface s;
  s.uKnots = s.vKnots = {0, 0, 0, 0, 1, 1, 1, 1};
  s.uCount = s.vCount = 4;
  s.poles.assign(16, Vec3::Zero());
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      Vec3 p = Vec3::Zero();
      for (int a = 0; a <= i; ++a)
        for (int b = 0; b <= j; ++b) p += (m[i][a] * m[j][b]) * c[a][b];
      s.poles[static_cast<std::size_t>(i * 4 + j)] = p;
    }
  return s;
}

NurbsSurface toNurbs(const BSplineSurface& surface) {
  const ControlNet& net = surface.net();
  const std::uint32_t nu = net.nu + 1, nv = net.nv + 1;
  const std::vector<double> uKnots(surface.uKnots().begin(), surface.uKnots().end());
  const std::vector<double> vKnots(surface.vKnots().begin(), surface.vKnots().end());
  // Clamp along v, row by row, then along u, column by column.
  std::vector<std::vector<Vec3>> rows(nu);
  std::vector<double> vClamped;
  for (std::uint32_t i = 0; i < nu; ++i) {
    rows[i].assign(net.points.begin() + i * nv, net.points.begin() + (i + 1) * nv);
    vClamped = clampCurve(vKnots, rows[i], 0.0, 1.0);
  }
  const auto vCount = static_cast<std::uint32_t>(rows[0].size());
  NurbsSurface s;
  s.vKnots = vClamped;
  s.vCount = vCount;
  std::vector<std::vector<Vec3>> columns(vCount);
  for (std::uint32_t j = 0; j < vCount; ++j) {
    columns[j].resize(nu);
    for (std::uint32_t i = 0; i < nu; ++i) columns[j][i] = rows[i][j];
    s.uKnots = clampCurve(uKnots, columns[j], 0.0, 1.0);
  }
  s.uCount = static_cast<std::uint32_t>(columns[0].size());
  s.poles.resize(std::size_t{s.uCount} * vCount);
  for (std::uint32_t i = 0; i < s.uCount; ++i)
    for (std::uint32_t j = 0; j < vCount; ++j) s.poles[i * vCount + j] = columns[j][i];
  return s;
}

Approximation approximate(const PatchFunction& f, const ApproximationOptions& options) {
  assert(options.checkPerSpan >= 2 && options.tolerance > 0.0);
  std::uint32_t mu = std::max(1u, options.initialUSpans), mv = std::max(1u, options.initialVSpans);
  const double goal = kApproximationSafety * options.tolerance;
  Approximation result;
  while (true) {
    NurbsSurface s;
    s.uKnots = creasedKnots(f.u0, f.u1, f.uCreases, mu);
    s.vKnots = creasedKnots(f.v0, f.v1, f.vCreases, mv);
    s.uCount = static_cast<std::uint32_t>(s.uKnots.size() - 4);
    s.vCount = static_cast<std::uint32_t>(s.vKnots.size() - 4);
    const std::vector<double> gu = greville(s.uKnots), gv = greville(s.vKnots);
    // Samples F(k, l) at the Greville points, per component; the closed direction's last
    // column repeats the first.
    const std::vector<Vec3> samples = sampleGrid(f, gu, gv);
    Eigen::MatrixXd fx(s.uCount, s.vCount), fy(s.uCount, s.vCount), fz(s.uCount, s.vCount);
    for (std::uint32_t k = 0; k < s.uCount; ++k)
      for (std::uint32_t l = 0; l < s.vCount; ++l) {
        const bool wrap = f.vClosed && l + 1 == s.vCount;
        const Vec3& p = samples[k * s.vCount + (wrap ? 0 : l)];
        fx(k, l) = p.x(), fy(k, l) = p.y(), fz(k, l) = p.z();
      }
    // A P Bᵀ = F: P = A⁻¹ F B⁻ᵀ (Schoenberg–Whitney holds at the Greville points).
    const Eigen::PartialPivLU<Eigen::MatrixXd> a(collocation(s.uKnots, gu));
    const Eigen::PartialPivLU<Eigen::MatrixXd> b(collocation(s.vKnots, gv));
    const auto solve = [&](const Eigen::MatrixXd& values) -> Eigen::MatrixXd {
      const Eigen::MatrixXd left = a.solve(values);  // A⁻¹ F
      return b.solve(left.transpose()).transpose();  // (B⁻¹ (A⁻¹ F)ᵀ)ᵀ
    };
    const Eigen::MatrixXd px = solve(fx), py = solve(fy), pz = solve(fz);
    s.poles.resize(std::size_t{s.uCount} * s.vCount);
    for (std::uint32_t i = 0; i < s.uCount; ++i)
      for (std::uint32_t j = 0; j < s.vCount; ++j)
        s.poles[i * s.vCount + j] = Vec3(px(i, j), py(i, j), pz(i, j));
    if (f.vClosed)  // the interpolants of equal samples: make the equality exact
      for (std::uint32_t i = 0; i < s.uCount; ++i)
        s.poles[i * s.vCount + s.vCount - 1] = s.poles[i * s.vCount];

    // Deviation on checkPerSpan + 1 points per span. On a row through Greville v's the fit
    // is the u interpolant alone (and vice versa): their errors say which way to refine.
    const std::vector<double> cu = checkParameters(s.uKnots, options.checkPerSpan);
    const std::vector<double> cv = checkParameters(s.vKnots, options.checkPerSpan);
    const double uError = gridDeviation(s, f, cu, gv), vError = gridDeviation(s, f, gu, cv);
    const double worst = std::max({gridDeviation(s, f, cu, cv), uError, vError});
    result.surface = std::move(s);
    result.deviation = worst;
    result.withinTolerance = worst <= goal;
    if (result.withinTolerance) return result;
    bool refineU = uError > 0.25 * goal;
    bool refineV = vError > 0.25 * goal;
    if (!refineU && !refineV) refineU = refineV = true;
    if (refineU && 2 * mu > options.maxSpans) refineU = false;
    if (refineV && 2 * mv > options.maxSpans) refineV = false;
    if (!refineU && !refineV) return result;
    if (refineU) mu *= 2;
    if (refineV) mv *= 2;
  }
}

double measureDeviation(const NurbsSurface& surface, const PatchFunction& f,
                        std::uint32_t samples) {
  std::vector<double> us(samples), vs(samples), su(samples), sv(samples);
  for (std::uint32_t i = 0; i < samples; ++i) {
    const double t = static_cast<double>(i) / (samples - 1);
    us[i] = f.u0 + (f.u1 - f.u0) * t;
    vs[i] = f.v0 + (f.v1 - f.v0) * t;
    su[i] = surface.uMin() + (surface.uMax() - surface.uMin()) * t;
    sv[i] = surface.vMin() + (surface.vMax() - surface.vMin()) * t;
  }
  const std::vector<Vec3> want = sampleGrid(f, us, vs);
  double worst = 0.0;
  for (std::uint32_t i = 0; i < samples; ++i)
    for (std::uint32_t j = 0; j < samples; ++j)
      worst = std::max(worst, (surface.position(su[i], sv[j]) - want[i * samples + j]).norm());
  return worst;
}

double NurbsModel::maxDeviation() const {
  double worst = 0.0;
  for (const NurbsFace& f : faces) worst = std::max(worst, f.deviation);
  return worst;
}

std::size_t NurbsModel::exactCount() const {
  return static_cast<std::size_t>(
      std::count_if(faces.begin(), faces.end(), [](const NurbsFace& f) { return f.exact; }));
}

std::size_t NurbsModel::overToleranceCount() const {
  return static_cast<std::size_t>(std::count_if(
      faces.begin(), faces.end(), [](const NurbsFace& f) { return !f.withinTolerance; }));
}

NurbsModel toNurbs(const VertexFrameSurface& surface, const NurbsExportOptions& options) {
  NurbsModel model;
  model.diagonal = surfaceBounds(surface).diagonal();
  model.tolerance = absoluteTolerance(options, model.diagonal);
  for (std::uint32_t k = 0; k < surface.patches.size(); ++k) {
    const VertexFramePatch& patch = surface.patches[k];
    PatchFunction f;
    f.position = [&patch](double u, double v) { return patch.position(u, v); };
    for (const ForceTerm& force : patch.forces) {
      f.uCreases.insert(f.uCreases.end(), {force.region.u0, force.region.u1});
      f.vCreases.insert(f.vCreases.end(), {force.region.v0, force.region.v1});
    }
    if (patch.forces.empty()) {
      NurbsFace face{bezierPatch(patch), k, true, 0.0};
      face.deviation = measureDeviation(face.surface, f, kExactCheckSamples);
      model.faces.push_back(std::move(face));
    } else {
      model.faces.push_back(approximateFace(f, k, model.tolerance, options, {}));
    }
  }
  return model;
}

NurbsModel toNurbs(const SolvedSpectral& solved, const NurbsExportOptions& options) {
  std::vector<PatchFunction> functions;
  for (std::size_t k = 0; k < solved.patchCount(); ++k) {
    const SpectralPatch& patch = solved.patchAt(k);
    PatchFunction f;
    f.position = [&patch](double u, double v) { return patch.position(u, v); };
    f.grid = [&patch](std::span<const double> us, std::span<const double> vs,
                      std::vector<Vec3>& out) { out = evaluateGrid(patch, us, vs).p; };
    std::tie(f.u0, f.u1) = solved.range(k);
    f.v0 = 0.0;
    f.v1 = 2.0 * std::numbers::pi;
    f.vClosed = true;
    functions.push_back(std::move(f));
  }
  NurbsModel model;
  model.diagonal = sampledDiagonal(functions, kBoxSamples);
  model.tolerance = absoluteTolerance(options, model.diagonal);
  // A turn around v is about 2π times as long as a patch is along u: more spans there.
  ApproximationOptions approximation;
  approximation.initialVSpans = 16;
  for (std::uint32_t k = 0; k < functions.size(); ++k)
    model.faces.push_back(
        approximateFace(functions[k], k, model.tolerance, options, approximation));
  return model;
}

NurbsModel toNurbs(std::span<const BSplineSurface> surfaces, const NurbsExportOptions& options) {
  NurbsModel model;
  std::vector<PatchFunction> functions;
  for (const BSplineSurface& s : surfaces) {
    PatchFunction f;
    f.position = [&s](double u, double v) { return s.position(u, v); };
    functions.push_back(std::move(f));
  }
  model.diagonal = sampledDiagonal(functions, kBoxSamples);
  model.tolerance = absoluteTolerance(options, model.diagonal);
  for (std::uint32_t k = 0; k < surfaces.size(); ++k) {
    NurbsFace face{toNurbs(surfaces[k]), k, true, 0.0};
    face.deviation = measureDeviation(face.surface, functions[k], kExactCheckSamples);
    model.faces.push_back(std::move(face));
  }
  return model;
}

}  // namespace pdesurf
