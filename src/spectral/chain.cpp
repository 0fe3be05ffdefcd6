// Cross-section chains of sixth-order patches (seed 002 §3.2): the global C4 chain (all
// joints solved together, docs/spectral.md "The global chain"), method 2 (exact C2 by
// derivative matching) and method 1 (overlapping windows of six curves).
#include "numerics/eigen_warnings.hpp"  // first: see the file

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>

#include "numerics/banded_lu.hpp"
#include "spectral/internal.hpp"

namespace pdesurf {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;
using spectral::ConditionData;

/// Relative step (to the whole chain) below which two consecutive curves count as sitting at
/// the same chain parameter: the patch between them would need unbounded derivatives.
constexpr double kCoincidentSpacing = 1e-9;

ConditionData positionAt(const ConditionData& curve, double t) {
  ConditionData c = curve;
  c.derivative = 0;
  c.u = t;
  return c;
}

/// A condition ∂^k X(t) = 0 (used to complete a lone patch through fewer than 6 curves).
ConditionData zeroDerivative(std::uint32_t k, double t, std::uint32_t modes) {
  ConditionData c;
  c.derivative = k;
  c.u = t;
  c.fourier.a.assign(modes, Vec3::Zero());
  c.fourier.b.assign(modes, Vec3::Zero());
  return c;
}

/// A solved patch as the part of a chain through curves first..last, shown whole.
ChainPatch chainPatch(SpectralPatch patch, std::uint32_t first, std::uint32_t last) {
  ChainPatch p;
  p.patch = std::move(patch);
  p.firstCurve = first;
  p.lastCurve = last;
  p.shownFirstCurve = first;
  p.shownLastCurve = last;
  p.length = last - first;
  return p;
}

ChainPatch makePatch(const SpectralOperator& op, std::uint32_t modes,
                     std::vector<ConditionData> conditions, std::uint32_t first,
                     std::uint32_t last) {
  return chainPatch(spectral::solveResolved(op, modes, 0.0, 1.0, std::move(conditions)), first,
                    last);
}

/// Multiplies a condition's data (Fourier part and remainder tail) by f.
void scaleCondition(ConditionData& c, double f) {
  c.fourier.a0 *= f;
  for (Vec3& x : c.fourier.a) x *= f;
  for (Vec3& x : c.fourier.b) x *= f;
  for (auto& term : c.tail) term.weight *= f;
}

/// A patch through curves [first, last] (q = last - first ≤ 3 intervals at t = j/q) that
/// matches derivatives 1..5-q of `neighbour` at the shared curve: `first` (the neighbour's
/// t = 1) when growing to the right, `last` (the neighbour's t = 0) when growing left.
/// Derivatives are matched in the chain parameter s (curve i at s = i), in which a patch
/// over q intervals has ∂s = ∂t / q: the neighbour's k-th t-derivative is scaled by
/// (q / q_neighbour)^k. Matching raw t-derivatives of patches of different lengths would
/// impose the neighbour's speed on a shorter patch (a 5-interval root drives a 1-interval
/// last step 5 times too fast, and the surface overshoots its last curve).
ChainPatch growPatch(const SpectralOperator& op, std::uint32_t modes,
                     const std::vector<ConditionData>& curves, const ChainPatch& neighbour,
                     std::uint32_t first, std::uint32_t last, bool toRight) {
  const std::uint32_t q = last - first;
  const double ratio =
      static_cast<double>(q) / static_cast<double>(neighbour.lastCurve - neighbour.firstCurve);
  std::vector<ConditionData> cond;
  for (std::uint32_t j = 0; j <= q; ++j)
    cond.push_back(positionAt(curves[first + j], double(j) / q));
  const double tShared = toRight ? 0.0 : 1.0;
  const double tNeighbour = toRight ? 1.0 : 0.0;
  for (std::uint32_t k = 1; k + q <= 5; ++k) {
    ConditionData d = spectral::derivativeCondition(neighbour.patch, tNeighbour, k);
    scaleCondition(d, std::pow(ratio, k));
    d.u = tShared;
    cond.push_back(std::move(d));
  }
  return makePatch(op, modes, std::move(cond), first, last);
}

// ---------------------------------------------------------------------------------------
// The global chain (docs/spectral.md, "The global chain").

/// The chain parameter of every curve in [0, 1]: the given values, or the cumulative
/// spacing of `options.spacing`, normalised.
std::vector<double> chainParameters(const std::vector<ConditionData>& data,
                                    const CrossSectionOptions& options) {
  const std::size_t count = data.size();
  std::vector<double> u(count, 0.0);
  if (!options.u.empty()) {
    if (options.u.size() != count)
      throw InvalidArgument("u: " + std::to_string(options.u.size()) + " values for " +
                            std::to_string(count) + " curves");
    for (std::size_t i = 0; i < count; ++i) {
      if (!std::isfinite(options.u[i]))
        throw InvalidArgument("u[" + std::to_string(i) + "] is not finite");
      if (i > 0 && !(options.u[i] > options.u[i - 1]))
        throw InvalidArgument("u[" + std::to_string(i) +
                              "] = " + spectral::numberText(options.u[i]) +
                              " does not increase from u[" + std::to_string(i - 1) +
                              "] = " + spectral::numberText(options.u[i - 1]));
      u[i] = options.u[i] - options.u[0];
    }
  } else {
    constexpr int kSamples = 64;  // v samples of the mean distance (seed 003 §3.0.1)
    for (std::size_t i = 1; i < count; ++i) {
      double step = 1.0;
      if (options.spacing == ChainSpacing::Centroids) {
        step = (data[i].fourier.a0 - data[i - 1].fourier.a0).norm();
      } else if (options.spacing == ChainSpacing::MeanDistance) {
        step = 0.0;
        for (int j = 0; j < kSamples; ++j) {
          const double v = kTwoPi * j / kSamples;
          step += (data[i].fourier.evaluate(v) - data[i - 1].fourier.evaluate(v)).norm();
        }
        step /= kSamples;
      }
      u[i] = u[i - 1] + step;
    }
  }
  const double total = u.back();
  for (std::size_t i = 1; i < count; ++i)
    if (!(u[i] - u[i - 1] > kCoincidentSpacing * total))
      throw InvalidArgument(
          "curves " + std::to_string(i - 1) + " and " + std::to_string(i) +
          (options.u.empty() && options.spacing == ChainSpacing::Centroids
               ? " have the same centroid: the chain parameter cannot follow their spacing "
                 "(give \"u\" or another \"spacing\")"
               : " sit at the same chain parameter"));
  for (double& x : u) x /= total;
  u.back() = 1.0;
  return u;
}

/// A mode's Fourier data of a curve as a row of `columns` values: mode 0 → a0 (3), mode n →
/// a_n, b_n (6).
void modeRow(const FourierCurve& f, std::uint32_t n, numerics::RowMatrix& m, Eigen::Index row,
             double scale) {
  if (n == 0) {
    m.row(row).head<3>() = scale * f.a0.transpose();
    return;
  }
  m.row(row).head<3>() = scale * f.a[n - 1].transpose();
  m.row(row).tail<3>() = scale * f.b[n - 1].transpose();
}

/// One mode of one patch of length h, on its local t = (u − u_i) / h: the basis, the
/// inverse of the Hermite matrix (its rows: X, ∂tX, ∂²tX at t = 0, then at t = 1) and the
/// map from the end data in u (X, ∂uX, ∂²uX at u_i; the same at u_{i+1}) to (∂³uX, ∂⁴uX at
/// u_i; the same at u_{i+1}). In long double on the mode's basis (a series for short
/// patches, basis.hpp).
struct PatchMode {
  spectral::ModeBasis basis;
  spectral::MatrixR inverse;  ///< coefficients = inverse · (t-space end data)
  Eigen::Matrix<double, 4, 6> map;
  double residual = 0.0;  ///< max |H · inverse − I|
};

PatchMode patchMode(const SpectralOperator& op, std::uint32_t n, double h) {
  PatchMode out{spectral::ModeBasis(spectral::modeRoots(op, n, h)), {}, {}, 0.0};
  spectral::MatrixR at0, at1;
  out.basis.evaluate(0.0, 4, at0);
  out.basis.evaluate(1.0, 4, at1);
  spectral::MatrixR given(6, 6), wanted(4, 6);
  given << at0.topRows(3), at1.topRows(3);
  wanted << at0.middleRows(3, 2), at1.middleRows(3, 2);
  out.inverse = given.colPivHouseholderQr().inverse();
  out.residual = static_cast<double>(
      (given * out.inverse - spectral::MatrixR::Identity(6, 6)).cwiseAbs().maxCoeff());
  const spectral::MatrixR map = wanted * out.inverse;
  constexpr int kIn[6] = {0, 1, 2, 0, 1, 2}, kOut[4] = {3, 4, 3, 4};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 6; ++c)
      out.map(r, c) = static_cast<double>(
          map(r, c) * std::pow(static_cast<spectral::Real>(h), kIn[c] - kOut[r]));
  return out;
}

/// Residual of a Hermite inverse above which the patch is solved again through the
/// general solver (solveResolved, with its precision tiers): the level at which that solver
/// escalates too.
constexpr double kHermiteResidual = 1e-11;

/// ∂u and ∂²u at u[e] of the polynomial through the curves `ids` (their mode rows).
void estimateEnd(const std::vector<double>& u, const std::vector<std::uint32_t>& ids,
                 std::uint32_t e, const numerics::RowMatrix& values, numerics::RowMatrix& d1,
                 numerics::RowMatrix& d2) {
  const auto q = static_cast<Eigen::Index>(ids.size());
  // Monomials in x = (u − u_e) / spread, solved in long double (q ≤ 6).
  double spread = 0.0;
  for (std::uint32_t i : ids) spread = std::max(spread, std::abs(u[i] - u[e]));
  spectral::MatrixR vander(q, q), rhs(q, values.cols());
  for (Eigen::Index r = 0; r < q; ++r) {
    const spectral::Real x = (u[ids[r]] - u[e]) / spread;
    spectral::Real p = 1;
    for (Eigen::Index c = 0; c < q; ++c, p *= x) vander(r, c) = p;
    rhs.row(r) = values.row(ids[r]).cast<spectral::Real>();
  }
  const spectral::MatrixR coef = vander.colPivHouseholderQr().solve(rhs);
  d1 = q > 1 ? numerics::RowMatrix(coef.row(1).cast<double>() / spread)
             : numerics::RowMatrix::Zero(1, values.cols());
  d2 = q > 2 ? numerics::RowMatrix(2.0 * coef.row(2).cast<double>() / (spread * spread))
             : numerics::RowMatrix::Zero(1, values.cols());
}

/// The patch through its six end conditions (no remainder) straight from the Hermite
/// inverses the joint solve computed: what solveResolved would find, without factoring
/// each mode again.
ChainPatch hermitePatch(const SpectralOperator& local, std::uint32_t modes,
                        std::vector<ConditionData> cond, const std::vector<PatchMode>& cache,
                        std::uint32_t first) {
  SpectralPatch patch;
  patch.operator_ = local;
  patch.modes_ = modes;
  patch.uStart_ = 0.0;
  patch.uEnd_ = 1.0;
  auto bases = std::make_shared<std::vector<spectral::ModeBasis>>();
  patch.coefficients_.resize(modes + 1);
  for (std::uint32_t n = 0; n <= modes; ++n) {
    bases->push_back(cache[n].basis);
    spectral::MatrixR rhs(6, 6);
    for (Eigen::Index r = 0; r < 6; ++r) {
      const FourierCurve& f = cond[static_cast<std::size_t>(r)].fourier;
      const Vec3 cs = n == 0 ? f.a0 : f.a[n - 1];
      const Vec3 sn = n == 0 ? Vec3::Zero() : f.b[n - 1];
      for (int d = 0; d < 3; ++d) {
        rhs(r, d) = cs[d];
        rhs(r, 3 + d) = sn[d];
      }
    }
    const spectral::MatrixR x = cache[n].inverse * rhs;
    SpectralPatch::ModeCoefficients& c = patch.coefficients_[n];
    c.cosine.resize(18);
    c.sine.resize(18);
    for (Eigen::Index k = 0; k < 6; ++k)
      for (Eigen::Index d = 0; d < 3; ++d) {
        c.cosine[static_cast<std::size_t>(3 * k + d)] = x(k, d);
        c.sine[static_cast<std::size_t>(3 * k + d)] = x(k, 3 + d);
      }
    c.precision = cache[n].basis.extended() ? ModePrecision::Extended : ModePrecision::Double;
  }
  patch.bases_ = std::move(bases);
  spectral::storeConditions(patch, std::move(cond));
  return chainPatch(std::move(patch), first, first + 1);
}

CrossSectionChain buildGlobalChain(const std::vector<ConditionData>& data,
                                   const CrossSectionOptions& options) {
  const auto count = static_cast<std::uint32_t>(data.size());
  const std::uint32_t modes = options.modes, patches = count - 1;
  const SpectralOperator op = SpectralOperator::fu(options.a);
  const std::vector<double> u = chainParameters(data, options);
  std::vector<double> h(patches);
  for (std::uint32_t i = 0; i < patches; ++i) h[i] = u[i + 1] - u[i];
  // Per mode: unknowns ∂uX, ∂²uX at every curve (2K), one banded system, 3 or 6 columns.
  std::vector<FourierCurve> first(count), second(count);
  for (std::uint32_t i = 0; i < count; ++i)
    for (FourierCurve* f : {&first[i], &second[i]}) {
      f->a.assign(modes, Vec3::Zero());
      f->b.assign(modes, Vec3::Zero());
    }
  const int m = 2 * static_cast<int>(count);
  std::vector<std::vector<PatchMode>> cache(patches);  // [patch][mode]
  for (auto& c : cache) c.reserve(modes + 1);
  for (std::uint32_t n = 0; n <= modes; ++n) {
    const Eigen::Index columns = n == 0 ? 3 : 6;
    numerics::RowMatrix values(count, columns);
    for (std::uint32_t i = 0; i < count; ++i) modeRow(data[i].fourier, n, values, i, 1.0);
    for (std::uint32_t i = 0; i < patches; ++i) cache[i].push_back(patchMode(op, n, h[i]));
    auto maps = [&](std::uint32_t i) -> const Eigen::Matrix<double, 4, 6>& {
      return cache[i][n].map;
    };
    // Unknown 2i is ∂uX(u_i)·s_i, 2i+1 is ∂²uX(u_i)·s_i², s_i the mean neighbouring step:
    // so that both columns of a curve have entries of like size.
    std::vector<double> s(count);
    for (std::uint32_t i = 0; i < count; ++i)
      s[i] = i == 0 ? h[0] : i == patches ? h[patches - 1] : 0.5 * (h[i - 1] + h[i]);
    numerics::BandedLu lu(m, 3, 3);
    numerics::RowMatrix rhs = numerics::RowMatrix::Zero(m, columns);
    // Row `row` gets `sign` × row r of patch p's map (its end data: curves p and p+1).
    auto addPatchRow = [&](int row, std::uint32_t p, int r, double sign) {
      for (int e = 0; e < 2; ++e) {
        const std::uint32_t curve = p + e;
        rhs.row(row) -= sign * maps(p)(r, 3 * e) * values.row(curve);
        lu.at(row, 2 * curve) += sign * maps(p)(r, 3 * e + 1) / s[curve];
        lu.at(row, 2 * curve + 1) += sign * maps(p)(r, 3 * e + 2) / (s[curve] * s[curve]);
      }
    };
    auto fixEnd = [&](int row, std::uint32_t curve, std::uint32_t k,
                      const numerics::RowMatrix& value) {
      lu.at(row, 2 * curve + k) = 1.0;
      rhs.row(row) = value * std::pow(s[curve], k + 1.0);
    };
    if (options.ends == ChainEnds::Natural || count < 3) {
      addPatchRow(0, 0, 0, 1.0);  // ∂³u X(u_0) = 0
      addPatchRow(1, 0, 1, 1.0);  // ∂⁴u X(u_0) = 0
      addPatchRow(m - 2, patches - 1, 2, 1.0);
      addPatchRow(m - 1, patches - 1, 3, 1.0);
    } else {
      const std::uint32_t q = std::min<std::uint32_t>(count, 6);
      std::vector<std::uint32_t> head(q), tail(q);
      for (std::uint32_t j = 0; j < q; ++j) {
        head[j] = j;
        tail[j] = count - 1 - j;
      }
      numerics::RowMatrix d1, d2;
      estimateEnd(u, head, 0, values, d1, d2);
      fixEnd(0, 0, 0, d1);
      fixEnd(1, 0, 1, d2);
      estimateEnd(u, tail, count - 1, values, d1, d2);
      fixEnd(m - 2, count - 1, 0, d1);
      fixEnd(m - 1, count - 1, 1, d2);
    }
    for (std::uint32_t i = 1; i < patches; ++i)
      for (int r = 0; r < 2; ++r) {  // ∂³u, ∂⁴u continuous at curve i
        const int row = 2 * static_cast<int>(i) + r;
        addPatchRow(row, i - 1, 2 + r, 1.0);
        addPatchRow(row, i, r, -1.0);
      }
    // Rows equilibrated to unit max norm.
    for (int row = 0; row < m; ++row) {
      double big = 0.0;
      for (int c = std::max(0, row - 3); c <= std::min(m - 1, row + 3); ++c)
        big = std::max(big, std::abs(lu.at(row, c)));
      if (!(big > 0.0)) continue;
      for (int c = std::max(0, row - 3); c <= std::min(m - 1, row + 3); ++c) lu.at(row, c) /= big;
      rhs.row(row) /= big;
    }
    if (!lu.factor())
      throw InvalidArgument("the global chain's system for mode " + std::to_string(n) +
                            " is singular (a = " + spectral::numberText(options.a) +
                            "): try another a");
    lu.solve(rhs);
    for (std::uint32_t i = 0; i < count; ++i) {
      const Eigen::RowVectorXd d1 = rhs.row(2 * i) / s[i], d2 = rhs.row(2 * i + 1) / (s[i] * s[i]);
      if (n == 0) {
        first[i].a0 = d1.head<3>().transpose();
        second[i].a0 = d2.head<3>().transpose();
      } else {
        first[i].a[n - 1] = d1.head<3>().transpose();
        first[i].b[n - 1] = d1.tail<3>().transpose();
        second[i].a[n - 1] = d2.head<3>().transpose();
        second[i].b[n - 1] = d2.tail<3>().transpose();
      }
    }
  }
  // Each patch on its local t ∈ [0, 1]: operator a·h⁶ (∂u = ∂t / h), t-derivative data
  // h^k ∂u^k X, so that its ∂³t, ∂⁴t at the ends are exactly those the system made continuous.
  CrossSectionChain chain;
  chain.method = ChainMethod::Global;
  chain.op = op;
  chain.curveU = u;
  chain.patches.reserve(patches);
  for (std::uint32_t i = 0; i < patches; ++i) {
    const SpectralOperator local = SpectralOperator::fu(options.a * std::pow(h[i], 6.0));
    std::vector<ConditionData> cond;
    for (std::uint32_t e = 0; e < 2; ++e) {
      const double t = e;
      cond.push_back(positionAt(data[i + e], t));
      for (std::uint32_t k = 1; k <= 2; ++k) {
        ConditionData d;
        d.derivative = k;
        d.u = t;
        d.fourier = k == 1 ? first[i + e] : second[i + e];
        d.fourier.a0 *= std::pow(h[i], k);
        for (Vec3& x : d.fourier.a) x *= std::pow(h[i], k);
        for (Vec3& x : d.fourier.b) x *= std::pow(h[i], k);
        cond.push_back(std::move(d));
      }
    }
    const bool tails = data[i].tail.size() + data[i + 1].tail.size() > 0;
    const bool exact = std::all_of(cache[i].begin(), cache[i].end(), [](const PatchMode& pm) {
      return pm.residual <= kHermiteResidual;
    });
    ChainPatch p = tails || !exact ? makePatch(local, modes, std::move(cond), i, i + 1)
                                   : hermitePatch(local, modes, std::move(cond), cache[i], i);
    p.length = h[i];
    chain.patches.push_back(std::move(p));
  }
  return chain;
}

}  // namespace

CrossSectionChain solve(std::span<const CurveInput> curves, const CrossSectionOptions& options) {
  const SpectralOperator op = SpectralOperator::fu(options.a);
  const auto count = static_cast<std::uint32_t>(curves.size());
  const bool exact = options.method == ChainMethod::ExactC2;
  const std::uint32_t least = options.method == ChainMethod::Global    ? 2
                              : options.method == ChainMethod::ExactC2 ? 4
                                                                       : 6;
  if (count < least)
    throw InvalidArgument(std::string("a cross-section chain (method \"") +
                          chainMethodName(options.method) + "\") needs at least " +
                          std::to_string(least) + " curves, got " + std::to_string(count));
  std::vector<ConditionData> data;
  for (std::uint32_t i = 0; i < count; ++i) {
    data.push_back(spectral::resolveCurve(curves[i], options.modes, options.parameterization,
                                          options.remainder, "curve " + std::to_string(i)));
    if (data.back().collapsed && i > 0 && i + 1 < count)
      throw InvalidArgument("curve " + std::to_string(i) +
                            ": degenerate section (all points coincide); only the first "
                            "and last sections may collapse to a point");
  }
  if (options.method == ChainMethod::Global) return buildGlobalChain(data, options);
  CrossSectionChain chain;
  chain.method = options.method;
  chain.op = op;
  for (std::uint32_t i = 0; i < count; ++i) chain.curveU.push_back(i);
  const std::uint32_t modes = options.modes;
  if (exact) {
    if (count < 6) {
      // One patch through all K curves; the missing 6-K conditions ∂^k X(½) = 0 (k = K..5)
      // make mode 0 the lowest-degree interpolant.
      std::vector<ConditionData> cond;
      for (std::uint32_t j = 0; j < count; ++j)
        cond.push_back(positionAt(data[j], double(j) / (count - 1)));
      for (std::uint32_t k = count; k < 6; ++k) cond.push_back(zeroDerivative(k, 0.5, modes));
      chain.patches.push_back(makePatch(op, modes, std::move(cond), 0, count - 1));
      return chain;
    }
    // Root through 6 curves [r0, r0+5] at t = 0, 0.2, ..., 1 (seed: C4..C9 of 12), then
    // patches of 3 new curves outward (seed: C1..C4 and C9..C12); a last step of 1 or 2
    // curves matches derivatives up to 4 or 3 instead of 2.
    const std::uint32_t r0 = 3 * ((count - 6) / 6);
    std::vector<ConditionData> cond;
    for (std::uint32_t j = 0; j < 6; ++j) cond.push_back(positionAt(data[r0 + j], j / 5.0));
    std::vector<ChainPatch> left, right;
    left.reserve(count);  // `neighbour` points into these: no reallocation
    right.reserve(count);
    ChainPatch root = makePatch(op, modes, std::move(cond), r0, r0 + 5);
    const ChainPatch* neighbour = &root;
    for (std::uint32_t end = r0; end > 0;) {
      const std::uint32_t first = end >= 3 ? end - 3 : 0;
      left.push_back(growPatch(op, modes, data, *neighbour, first, end, false));
      neighbour = &left.back();
      end = first;
    }
    neighbour = &root;
    for (std::uint32_t start = r0 + 5; start + 1 < count;) {
      const std::uint32_t last = std::min(start + 3, count - 1);
      right.push_back(growPatch(op, modes, data, *neighbour, start, last, true));
      neighbour = &right.back();
      start = last;
    }
    // `neighbour` pointers are only used during construction; now assemble in order.
    for (auto it = left.rbegin(); it != left.rend(); ++it) chain.patches.push_back(std::move(*it));
    chain.rootPatch = static_cast<std::uint32_t>(chain.patches.size());
    chain.patches.push_back(std::move(root));
    for (ChainPatch& p : right) chain.patches.push_back(std::move(p));
    return chain;
  }
  // Method 1: windows of 6 curves starting at s_j = min(3j, K-6); the root (middle) window
  // is shown whole, a window left of it up to the next window's first curve, a window right
  // of it from the previous window's last curve (seed: C1..C6 shown on [0, 0.6] up to C4,
  // C7..C12 shown on [0.4, 1] from C9).
  const std::uint32_t windows = (count - 6 + 2) / 3 + 1;
  std::vector<std::uint32_t> start(windows);
  for (std::uint32_t j = 0; j < windows; ++j) start[j] = std::min(3 * j, count - 6);
  const std::uint32_t root = (windows - 1) / 2;
  for (std::uint32_t j = 0; j < windows; ++j) {
    std::vector<ConditionData> cond;
    for (std::uint32_t k = 0; k < 6; ++k) cond.push_back(positionAt(data[start[j] + k], k / 5.0));
    ChainPatch p = makePatch(op, modes, std::move(cond), start[j], start[j] + 5);
    if (j < root) p.shownLastCurve = start[j + 1];
    if (j > root) p.shownFirstCurve = start[j - 1] + 5;
    p.tStart = (p.shownFirstCurve - start[j]) / 5.0;
    p.tEnd = (p.shownLastCurve - start[j]) / 5.0;
    chain.patches.push_back(std::move(p));
  }
  chain.rootPatch = root;
  return chain;
}

const char* chainMethodName(ChainMethod method) {
  // In the order of ChainMethod.
  static constexpr const char* kNames[] = {"global", "c2", "shared-curves"};
  const auto index = static_cast<std::size_t>(method);
  return index < std::size(kNames) ? kNames[index] : "?";
}

std::vector<JointGap> measureJointGaps(const CrossSectionChain& chain, std::uint32_t samples) {
  // Extent: the bounding box of every patch sampled on its shown range.
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const ChainPatch& p : chain.patches)
    for (int r = 0; r <= 8; ++r)
      for (std::uint32_t j = 0; j < samples; ++j) {
        const Vec3 x =
            p.patch.position(p.tStart + (p.tEnd - p.tStart) * r / 8.0, kTwoPi * j / samples);
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
      }
  const double extent = std::max((hi - lo).norm(), 1e-300);
  std::vector<JointGap> gaps;
  for (std::size_t k = 0; k + 1 < chain.patches.size(); ++k) {
    const ChainPatch &a = chain.patches[k], &b = chain.patches[k + 1];
    JointGap g;
    g.curve = a.shownLastCurve;
    // Derivatives in the chain parameter (s, curve i at s = i, or the global u):
    // ∂^k = ∂t^k / length^k.
    const double qa = a.length, qb = b.length;
    for (std::uint32_t j = 0; j < samples; ++j) {
      const double v = kTwoPi * j / samples;
      double* gap[3] = {&g.c0, &g.c1, &g.c2};
      for (std::uint32_t d = 0; d < 3; ++d) {
        const Vec3 da = a.patch.derivative(a.tEnd, v, d, 0) / std::pow(qa, d);
        const Vec3 db = b.patch.derivative(b.tStart, v, d, 0) / std::pow(qb, d);
        *gap[d] = std::max(*gap[d], (da - db).norm());
      }
    }
    g.c0Relative = g.c0 / extent;
    g.c1Relative = g.c1 / extent;
    g.c2Relative = g.c2 / extent;
    gaps.push_back(g);
  }
  return gaps;
}

}  // namespace pdesurf
