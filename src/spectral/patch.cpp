// Solving and evaluating one spectral patch (docs/derivations.md §2; seed 003 §2.1, seed 002 §3.2).
#include "numerics/eigen_warnings.hpp"  // first: see the file

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <Eigen/QR>

#include "spectral/internal.hpp"

namespace pdesurf {

namespace {
using spectral::kTwoPi;
using spectral::numberText;

/// cos/sin(nv) differentiated kv times: n^kv cos(nv + kv π/2), n^kv sin(nv + kv π/2).
void trig(std::uint32_t n, double v, std::uint32_t kv, double& c, double& s) {
  const double nd = n;
  const double f = std::pow(nd, static_cast<double>(kv));
  const double arg = nd * v + kv * std::numbers::pi / 2.0;
  c = f * std::cos(arg);
  s = f * std::sin(arg);
}

/// Relative pivot (to the largest) below which mode 0's condition system counts as singular:
/// below a double ulp (a singular set gives a pivot at rounding level), far below the
/// ~1e-12 of equispaced polynomial interpolation of degree 39 (order 40).
constexpr double kSingularPivot = 1e-17;

/// A QR of the row-equilibrated condition matrix of one mode, in precision T.
template <class M>
struct ModeSystem {
  using Matrix = M;
  using T = typename M::Scalar;
  Eigen::ColPivHouseholderQR<Matrix> qr;
  Eigen::Matrix<T, Eigen::Dynamic, 1, 0, M::MaxRowsAtCompileTime, 1> rowScale;
  Matrix matrix;  ///< the equilibrated system
};

template <class M>
ModeSystem<M> factorMode(const spectral::ModeBasis& basis,
                         const std::vector<spectral::ConditionData>& conditions, double uStart,
                         double length, std::uint32_t n) {
  const auto order = static_cast<Eigen::Index>(basis.size());
  using T = typename M::Scalar;
  M c(order, order), table;
  ModeSystem<M> sys;
  sys.rowScale.resize(order);
  for (Eigen::Index i = 0; i < order; ++i) {
    const auto& cond = conditions[static_cast<std::size_t>(i)];
    basis.evaluate((cond.u - uStart) / length, cond.derivative, table);
    c.row(i) = table.row(cond.derivative);
    const T m = c.row(i).cwiseAbs().maxCoeff();
    // Rows of derivative conditions scale like |root|^k and rows at interior u like
    // e^{-|root| dist}: equilibrate so that QR sees rows of comparable size.
    using std::isfinite;  // Quad's by argument-dependent lookup
    sys.rowScale(i) = m > T(0) && isfinite(m) ? T(1) / m : T(1);
    c.row(i) *= sys.rowScale(i);
  }
  sys.qr.compute(c);
  sys.matrix = std::move(c);
  // Singular condition sets (only derivative conditions leave mode 0's constant free; two
  // conditions alike at one u) show in mode 0, whose basis is well conditioned. Higher
  // modes may be ill-conditioned yet solvable (docs/spectral.md): every pivot is used and
  // the solution is checked by its residual instead.
  sys.qr.setThreshold(n == 0 ? static_cast<T>(kSingularPivot) : std::numeric_limits<T>::min());
  if (n == 0 && sys.qr.rank() < order)
    throw InvalidArgument(
        "the conditions do not determine mode " + std::to_string(n) + " (rank " +
        std::to_string(sys.qr.rank()) + " of " + std::to_string(order) +
        "): e.g. only derivative conditions, or several conditions at the same u");
  return sys;
}

/// Relative residual of a mode's solve above which the system counts as singular (a
/// resonance of an oscillatory basis, e.g. Fu with a < 0, or a basis too ill-conditioned
/// even for quad precision): far above the ≤ 1e-12 reached by solvable systems
/// (docs/spectral.md).
constexpr double kModeResidualLimit = 1e-6;

/// Relative residual above which a mode is solved again in the next precision (double →
/// long double → quad): two orders below the 1e-9 the conditions must meet, and far above
/// the ~1e-15 of a well-conditioned double solve. Deterministic: the same data take the
/// same path.
constexpr double kEscalateResidual = 1e-11;

/// max |matrix · x − rhs| / max |rhs| (NaN when the solve produced non-finite values).
template <class M>
double relativeResidual(const M& matrix, const M& rhs, const M& x) {
  using T = typename M::Scalar;
  const M r = matrix.lazyProduct(x) - rhs;
  const T scale = rhs.cwiseAbs().maxCoeff();
  const T res = r.cwiseAbs().maxCoeff() / (scale > T(0) ? scale : T(1));
  using std::isfinite;
  return isfinite(res) ? static_cast<double>(res) : std::numeric_limits<double>::quiet_NaN();
}

/// Solves mode n in precision T into `coef` (order × 3 cosine and sine coefficients; a quad
/// solution split into hi + lo) and returns the relative residual of its system.
template <class M>
double solveMode(const spectral::ModeBasis& basis,
                 const std::vector<spectral::ConditionData>& conditions, double uStart,
                 double length, std::uint32_t n, SpectralPatch::ModeCoefficients& coef) {
  using T = typename M::Scalar;
  const ModeSystem<M> sys = factorMode<M>(basis, conditions, uStart, length, n);
  const auto order = static_cast<Eigen::Index>(basis.size());
  M rhs(order, 6);
  for (Eigen::Index i = 0; i < order; ++i) {
    const spectral::ConditionData& c = conditions[static_cast<std::size_t>(i)];
    const T s =
        static_cast<T>(std::pow(length, static_cast<double>(c.derivative))) * sys.rowScale(i);
    const Vec3 cs = n == 0 ? c.fourier.a0 : c.fourier.a[n - 1];
    const Vec3 sn = n == 0 ? Vec3::Zero() : c.fourier.b[n - 1];
    for (int d = 0; d < 3; ++d) {
      rhs(i, d) = s * static_cast<T>(cs[d]);
      rhs(i, 3 + d) = s * static_cast<T>(sn[d]);
    }
  }
  const M x = sys.qr.solve(rhs);
  const auto size = static_cast<std::size_t>(order);
  coef.cosine.resize(3 * size);
  coef.sine.resize(3 * size);
  if constexpr (std::is_same_v<T, spectral::Quad>) {
    coef.cosineLow.resize(3 * size);
    coef.sineLow.resize(3 * size);
  } else {
    coef.cosineLow.clear();
    coef.sineLow.clear();
  }
  for (std::size_t k = 0; k < size; ++k)
    for (std::size_t d = 0; d < 3; ++d) {
      const auto row = static_cast<Eigen::Index>(k), col = static_cast<Eigen::Index>(d);
      if constexpr (std::is_same_v<T, spectral::Quad>) {
        spectral::split(x(row, col), coef.cosine[3 * k + d], coef.cosineLow[3 * k + d]);
        spectral::split(x(row, 3 + col), coef.sine[3 * k + d], coef.sineLow[3 * k + d]);
      } else {
        coef.cosine[3 * k + d] = static_cast<spectral::Real>(x(row, col));
        coef.sine[3 * k + d] = static_cast<spectral::Real>(x(row, 3 + col));
      }
    }
  return relativeResidual<M>(sys.matrix, rhs, x);
}

/// Solves mode n in the precision its basis suggests (ModeBasis::extended), then in the next
/// precision while the residual exceeds kEscalateResidual; refuses the mode if even quad
/// leaves it above kModeResidualLimit.
void solveModeTiered(const spectral::ModeBasis& basis,
                     const std::vector<spectral::ConditionData>& conditions, double uStart,
                     double length, std::uint32_t n, SpectralPatch::ModeCoefficients& coef) {
  ModePrecision tier = basis.extended() ? ModePrecision::Extended : ModePrecision::Double;
  if (basis.nearPolynomial()) {
    // Mode 0 and short patches (basis.hpp): a near-polynomial basis is evaluated accurately
    // in double, but its system loses the digits of its condition (~1e3) against data whose
    // derivative conditions are h^k times smaller than its positions (short chain patches);
    // solved in long double, the coefficients are exact to double rounding and the chain
    // stays C2 to rounding at any section count (tests/spectral/global_chain_test.cpp).
    const double residual =
        solveMode<spectral::MatrixR>(basis, conditions, uStart, length, n, coef);
    coef.precision = ModePrecision::Double;
    if (residual <= kEscalateResidual) return;
    tier = ModePrecision::Quad;
  }
  for (;;) {
    double residual = 0.0;
    switch (tier) {
      case ModePrecision::Double:
        residual = solveMode<spectral::SmallMatrix>(basis, conditions, uStart, length, n, coef);
        break;
      case ModePrecision::Extended:
        residual = solveMode<spectral::MatrixR>(basis, conditions, uStart, length, n, coef);
        break;
      case ModePrecision::Quad:
        residual = solveMode<spectral::MatrixQ>(basis, conditions, uStart, length, n, coef);
        break;
    }
    coef.precision = tier;
    if (residual <= kEscalateResidual) return;
    if (tier == ModePrecision::Quad) {
      if (residual <= kModeResidualLimit) return;  // the best there is, and still sound
      throw InvalidArgument("the conditions do not determine mode " + std::to_string(n) +
                            " (its system is singular or too ill-conditioned; see "
                            "docs/spectral.md)");
    }
    tier = tier == ModePrecision::Double ? ModePrecision::Extended : ModePrecision::Quad;
  }
}

/// The ku-th t-derivative of mode n's cosine and sine functions (An, Bn) at t, in the mode's
/// precision (long double for double and extended modes, as the single-point evaluations
/// always were; quad for quad modes). `table` is scratch space.
void modeAt(const spectral::ModeBasis& basis, const SpectralPatch::ModeCoefficients& coef, double t,
            std::uint32_t ku, spectral::MatrixR& table, Vec3& a, Vec3* b) {
  if (coef.precision == ModePrecision::Quad) {
    using spectral::Quad;
    spectral::MatrixQ tableQ;
    basis.evaluate(t, ku, tableQ);
    a = (tableQ.row(ku) * spectral::coefficientMatrix<Quad>(coef.cosine, coef.cosineLow))
            .transpose()
            .cast<double>();
    if (b)
      *b = (tableQ.row(ku) * spectral::coefficientMatrix<Quad>(coef.sine, coef.sineLow))
               .transpose()
               .cast<double>();
    return;
  }
  basis.evaluate(t, ku, table);
  a = (table.row(ku) * spectral::coefficients(coef.cosine)).transpose().cast<double>();
  if (b) *b = (table.row(ku) * spectral::coefficients(coef.sine)).transpose().cast<double>();
}

}  // namespace

SpectralOperator SpectralOperator::ugail(std::uint32_t n, std::optional<double> a) {
  SpectralOperator op;
  op.kind = OperatorKind::Ugail;
  op.power = n;
  op.a = a.value_or(static_cast<double>(n));
  op.validate();
  return op;
}

SpectralOperator SpectralOperator::fu(double a) {
  SpectralOperator op;
  op.kind = OperatorKind::Fu;
  op.power = 3;
  op.a = a;
  op.validate();
  return op;
}

void SpectralOperator::validate() const {
  if (!std::isfinite(a)) throw InvalidArgument("operator parameter a is not finite");
  if (kind == OperatorKind::Ugail) {
    if (power < 1) throw InvalidArgument("Ugail operator needs N >= 1, got N = 0");
    if (power > 64)
      throw InvalidArgument("Ugail operator: N = " + std::to_string(power) +
                            " exceeds 64 (order 128)");
    if (a <= 0.0) throw InvalidArgument("Ugail operator needs a > 0, got a = " + numberText(a));
  } else {
    if (a == 0.0)
      throw InvalidArgument("Fu operator needs a != 0 (a = 0 leaves ∂⁶X/∂u⁶ = 0 alone)");
  }
}

namespace spectral {

SpectralPatch solveResolved(const SpectralOperator& op, std::uint32_t modes, double uStart,
                            double uEnd, std::vector<ConditionData> conditions) {
  SpectralPatch patch;
  patch.operator_ = op;
  patch.modes_ = modes;
  patch.uStart_ = uStart;
  patch.uEnd_ = uEnd;
  const double length = uEnd - uStart;
  patch.coefficients_.resize(modes + 1);
  auto bases = std::make_shared<std::vector<ModeBasis>>();
  for (std::uint32_t n = 0; n <= modes; ++n) bases->emplace_back(modeRoots(op, n, length));
  patch.bases_ = bases;
  for (std::uint32_t n = 0; n <= modes; ++n)
    solveModeTiered((*bases)[n], conditions, uStart, length, n, patch.coefficients_[n]);
  const bool anyTail = std::any_of(conditions.begin(), conditions.end(),
                                   [](const ConditionData& c) { return !c.tail.empty(); });
  if (anyTail) {
    // Remainder on the basis of the first truncated mode, M+1 (docs/derivations.md §2.3): cardinal
    // functions ψ_i with L_j ψ_i = δ_ij, so R = Σ ψ_i(t) d_i(v) meets every condition.
    auto tail = std::make_shared<SpectralTailData>();
    tail->basis = ModeBasis(modeRoots(op, modes + 1, length));
    const auto sys = factorMode<MatrixR>(tail->basis, conditions, uStart, length, modes + 1);
    const MatrixR scale = sys.rowScale.asDiagonal();
    tail->cardinal = sys.qr.solve(scale);
    // The cardinal matrix is C⁻¹ (scale⁻¹ · scale): L_j ψ_i − δ_ij is row j of the
    // equilibrated residual over its row scale. Redone in quad where long double leaves it
    // above kEscalateResidual (mode M+1 ill-conditioned, e.g. M = 0 at high order).
    auto cardinalError = [](const auto& s, const auto& x, const auto& d) {
      using T = typename std::decay_t<decltype(x)>::Scalar;
      T worst = T(0);
      for (Eigen::Index j = 0; j < x.rows(); ++j) {
        const T e = (s.matrix.row(j) * x - d.row(j)).cwiseAbs().maxCoeff() / s.rowScale(j);
        if (!(e <= worst)) {
          worst = e;
          if (!(e == e)) break;  // NaN: stop here
        }
      }
      return static_cast<double>(worst);
    };
    if (!(cardinalError(sys, tail->cardinal, scale) <= kEscalateResidual)) {
      const auto quad = factorMode<MatrixQ>(tail->basis, conditions, uStart, length, modes + 1);
      const MatrixQ scaleQ = quad.rowScale.asDiagonal();
      tail->cardinalQ = quad.qr.solve(scaleQ);
      tail->cardinal.resize(0, 0);
      tail->precision = ModePrecision::Quad;
    }
    for (const ConditionData& c : conditions) {
      tail->terms.push_back(c.tail);
      tail->scale.push_back(std::pow(length, static_cast<double>(c.derivative)));
    }
    patch.tail_ = std::move(tail);
  }
  storeConditions(patch, std::move(conditions));
  return patch;
}

void storeConditions(SpectralPatch& patch, std::vector<ConditionData> conditions) {
  for (ConditionData& c : conditions) {
    SpectralPatch::ResolvedCondition r;
    r.derivative = c.derivative;
    r.u = c.u;
    r.fourier = std::move(c.fourier);
    r.points = std::move(c.points);
    r.v = std::move(c.v);
    patch.conditions_.push_back(std::move(r));
  }
}

MatrixR SpectralTailData::psi(double t, std::uint32_t first, std::uint32_t last) const {
  const auto rows = static_cast<Eigen::Index>(last - first + 1);
  if (precision == ModePrecision::Quad) {
    MatrixQ table;
    basis.evaluate(t, last, table);
    return (table.middleRows(first, rows) * cardinalQ).cast<Real>();
  }
  MatrixR table;
  basis.evaluate(t, last, table);
  return table.middleRows(first, rows) * cardinal;
}

ConditionData derivativeCondition(const SpectralPatch& patch, double t, std::uint32_t k) {
  ConditionData c;
  c.derivative = k;
  const std::uint32_t modes = patch.modes();
  const double length = patch.uEnd() - patch.uStart();
  c.fourier.a.assign(modes, Vec3::Zero());
  c.fourier.b.assign(modes, Vec3::Zero());
  const double scale = std::pow(length, -static_cast<double>(k));  // t → u derivatives
  MatrixR table;
  for (std::uint32_t n = 0; n <= modes; ++n) {
    Vec3 a, b;
    modeAt((*patch.bases_)[n], patch.coefficients_[n], t, k, table, a, &b);
    a *= scale;
    b *= scale;
    if (n == 0) {
      c.fourier.a0 = a;
    } else {
      c.fourier.a[n - 1] = a;
      c.fourier.b[n - 1] = b;
    }
  }
  for (const SpineOffset& s : patch.spineOffsets_)
    c.fourier.a0 += evaluateNaturalSpline(s, patch.uStart() + t * length, k);
  if (patch.tail_) {
    const SpectralTailData& tail = *patch.tail_;
    const MatrixR psi = tail.psi(t, k, k);
    for (std::size_t i = 0; i < tail.terms.size(); ++i)
      for (const TailTerm& term : tail.terms[i]) {
        TailTerm w = term;
        w.weight *=
            static_cast<double>(psi(0, static_cast<Eigen::Index>(i))) * tail.scale[i] * scale;
        if (w.weight != 0.0) c.tail.push_back(std::move(w));
      }
  }
  return c;
}

}  // namespace spectral

Vec3 SpectralPatch::derivative(double u, double v, std::uint32_t ku, std::uint32_t kv) const {
  const double length = uEnd_ - uStart_;
  const double t = (u - uStart_) / length;
  Vec3 x = Vec3::Zero();
  spectral::MatrixR table;
  for (std::uint32_t n = 0; n <= modes_; ++n) {
    if (n == 0 && kv > 0) continue;
    Vec3 a, b;
    modeAt((*bases_)[n], coefficients_[n], t, ku, table, a, n == 0 ? nullptr : &b);
    if (n == 0) {
      x += a;
      continue;
    }
    double c, s;
    trig(n, v, kv, c, s);
    x += a * c + b * s;
  }
  if (tail_) {
    const spectral::MatrixR psi = tail_->psi(t, ku, ku);
    for (std::size_t i = 0; i < tail_->terms.size(); ++i)
      if (!tail_->terms[i].empty())
        x +=
            static_cast<double>(psi(0, static_cast<Eigen::Index>(i))) * tail_->difference(i, v, kv);
  }
  x *= std::pow(length, -static_cast<double>(ku));
  if (kv == 0)
    for (const SpineOffset& s : spineOffsets_) x += spectral::evaluateNaturalSpline(s, u, ku);
  return x;
}

SurfacePoint SpectralPatch::evaluate(double u, double v) const {
  return {derivative(u, v, 0, 0), derivative(u, v, 1, 0), derivative(u, v, 0, 1)};
}

Vec3 SpectralPatch::conditionTarget(std::size_t i, double v) const {
  const ResolvedCondition& c = conditions_[i];
  Vec3 x = c.fourier.evaluate(v);
  if (tail_)
    for (const spectral::TailTerm& term : tail_->terms[i]) x += term.evaluate(v, 0);
  return x;
}

Vec3 SpectralPatch::spine(double u, std::uint32_t k) const {
  const double length = uEnd_ - uStart_;
  spectral::MatrixR table;
  Vec3 x;
  modeAt((*bases_)[0], coefficients_[0], (u - uStart_) / length, k, table, x, nullptr);
  x *= std::pow(length, -static_cast<double>(k));
  for (const SpineOffset& s : spineOffsets_) x += spectral::evaluateNaturalSpline(s, u, k);
  return x;
}

std::vector<double> placeCurves(std::span<const CurveInput> curves, UPlacement placement,
                                VParameterization parameterization) {
  const std::size_t count = curves.size();
  std::vector<double> u(count, 0.0);
  if (count < 2) return u;
  if (placement != UPlacement::ChordLength) {
    for (std::size_t i = 0; i < count; ++i)
      u[i] = static_cast<double>(i) / static_cast<double>(count - 1);
    return u;
  }
  // Seed 003 §3.0.1: the average Euclidean distance between consecutive curves, then u
  // proportional to it. Curves are compared at the same v (Fourier input evaluated,
  // sampled input interpolated linearly along its own v).
  constexpr int kSamples = 64;
  auto sample = [&](const CurveInput& c, std::size_t index) {
    std::vector<Vec3> s(kSamples);
    if (const auto* f = std::get_if<FourierCurve>(&c)) {
      for (int j = 0; j < kSamples; ++j) s[j] = f->evaluate(kTwoPi * j / kSamples);
      return s;
    }
    const auto& sc = std::get<SampledCurve>(c);
    std::vector<double> v;
    try {
      v = curveParameters(sc, parameterization);
    } catch (const InvalidArgument& e) {
      throw InvalidArgument("curve " + std::to_string(index) + ": " + e.what());
    }
    const std::size_t n = v.size();
    for (int j = 0; j < kSamples; ++j) {
      const double x = kTwoPi * j / kSamples;
      std::size_t k = static_cast<std::size_t>(std::upper_bound(v.begin(), v.end(), x) - v.begin());
      const std::size_t k0 = k == 0 ? n - 1 : k - 1, k1 = k == n ? 0 : k;
      double x0 = v[k0], x1 = v[k1];
      if (k == 0) x0 -= kTwoPi;
      if (k == n) x1 += kTwoPi;
      const double w = x1 > x0 ? (x - x0) / (x1 - x0) : 0.0;
      s[j] = (1 - w) * sc.points[k0] + w * sc.points[k1];
    }
    return s;
  };
  std::vector<Vec3> prev = sample(curves[0], 0);
  for (std::size_t i = 1; i < count; ++i) {
    std::vector<Vec3> cur = sample(curves[i], i);
    double d = 0.0;
    for (int j = 0; j < kSamples; ++j) d += (cur[j] - prev[j]).norm();
    d /= kSamples;
    if (!(d > 0.0))
      throw InvalidArgument("curves " + std::to_string(i - 1) + " and " + std::to_string(i) +
                            " coincide: chord-length u places them at the same u");
    u[i] = u[i - 1] + d;
    prev = std::move(cur);
  }
  for (double& x : u) x /= u.back();
  return u;
}

SpectralPatch solve(const SpectralOperator& op, std::span<const SpectralCondition> conditions,
                    const SpectralOptions& options) {
  op.validate();
  const std::size_t order = op.order();
  if (conditions.size() != order)
    throw InvalidArgument("an operator of order " + std::to_string(order) + " needs " +
                          std::to_string(order) + " conditions, got " +
                          std::to_string(conditions.size()));
  if (options.modes > 512)
    throw InvalidArgument("M = " + std::to_string(options.modes) + " modes exceeds 512");
  // u positions.
  std::vector<CurveInput> positionCurves;
  std::vector<std::size_t> positionIndex;
  for (std::size_t i = 0; i < conditions.size(); ++i)
    if (conditions[i].derivative == 0) {
      positionCurves.push_back(conditions[i].curve);
      positionIndex.push_back(i);
    }
  std::vector<double> u(conditions.size(), std::numeric_limits<double>::quiet_NaN());
  if (options.placement != UPlacement::Given) {
    const std::vector<double> placed =
        placeCurves(positionCurves, options.placement, options.parameterization);
    for (std::size_t j = 0; j < placed.size(); ++j) u[positionIndex[j]] = placed[j];
  }
  for (std::size_t i = 0; i < conditions.size(); ++i) {
    const SpectralCondition& c = conditions[i];
    if (c.u) {
      if (!std::isfinite(*c.u))
        throw InvalidArgument("condition " + std::to_string(i) + ": u is not finite");
      u[i] = *c.u;
    } else if (c.derivative > 0) {
      for (std::size_t j = i; j-- > 0;)
        if (conditions[j].derivative == 0) {
          u[i] = u[j];
          break;
        }
    }
    if (std::isnan(u[i]))
      throw InvalidArgument(
          "condition " + std::to_string(i) +
          (c.derivative == 0
               ? ": no u given (placement is Given)"
               : ": derivative condition has no u and no position condition before it"));
    if (c.derivative >= order)
      throw InvalidArgument("condition " + std::to_string(i) + ": derivative order " +
                            std::to_string(c.derivative) + " must be below the PDE order " +
                            std::to_string(order));
  }
  for (std::size_t i = 0; i < conditions.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (u[i] == u[j] && conditions[i].derivative == conditions[j].derivative)
        throw InvalidArgument("conditions " + std::to_string(j) + " and " + std::to_string(i) +
                              " both fix derivative " + std::to_string(conditions[i].derivative) +
                              " at u = " + numberText(u[i]));
  const auto [lo, hi] = std::minmax_element(u.begin(), u.end());
  if (!(*hi > *lo))
    throw InvalidArgument("all conditions sit at u = " + numberText(*lo) +
                          ": the patch has no extent");
  std::vector<spectral::ConditionData> data;
  for (std::size_t i = 0; i < conditions.size(); ++i) {
    data.push_back(spectral::resolveCurve(conditions[i].curve, options.modes,
                                          options.parameterization, options.remainder,
                                          "condition " + std::to_string(i)));
    data.back().derivative = conditions[i].derivative;
    data.back().u = u[i];
  }
  return spectral::solveResolved(op, options.modes, *lo, *hi, std::move(data));
}

std::vector<double> conditionErrors(const SpectralPatch& patch, std::uint32_t samples) {
  // Errors are relative to the largest target among the conditions of the same derivative
  // order (a derivative curve that happens to be 0 is measured against its siblings).
  const auto& conds = patch.conditions();
  std::vector<double> err(conds.size(), 0.0), size(conds.size(), 0.0);
  for (std::size_t i = 0; i < conds.size(); ++i) {
    const auto& c = conds[i];
    auto check = [&](double v, const Vec3& target) {
      err[i] = std::max(err[i], (patch.derivative(c.u, v, c.derivative, 0) - target).norm());
      size[i] = std::max(size[i], target.norm());
    };
    for (std::size_t j = 0; j < c.points.size(); ++j) check(c.v[j], c.points[j]);
    for (std::uint32_t j = 0; j < samples; ++j) {
      const double v = kTwoPi * j / samples;
      check(v, patch.conditionTarget(i, v));
    }
  }
  std::vector<double> relative(conds.size());
  for (std::size_t i = 0; i < conds.size(); ++i) {
    double scale = 0.0;
    for (std::size_t j = 0; j < conds.size(); ++j)
      if (conds[j].derivative == conds[i].derivative) scale = std::max(scale, size[j]);
    relative[i] = scale > 0.0 ? err[i] / scale : err[i];
  }
  return relative;
}

std::vector<Vec3> spinePolyline(const SpectralPatch& patch, std::uint32_t count) {
  std::vector<Vec3> p;
  for (std::uint32_t j = 0; j < count; ++j) {
    const double w = count > 1 ? static_cast<double>(j) / (count - 1) : 0.0;
    p.push_back(patch.spine(patch.uStart() + w * (patch.uEnd() - patch.uStart())));
  }
  return p;
}

SpectralPatch editSpine(const SpectralPatch& patch, const SpineEdit& edit) {
  if (edit.u.empty()) throw InvalidArgument("spine edit has no control points");
  if (edit.u.size() != edit.moved.size())
    throw InvalidArgument("spine edit has " + std::to_string(edit.u.size()) + " u values but " +
                          std::to_string(edit.moved.size()) + " moved points");
  std::vector<Vec3> delta;
  for (std::size_t j = 0; j < edit.u.size(); ++j) {
    if (!std::isfinite(edit.u[j]) || !edit.moved[j].allFinite())
      throw InvalidArgument("spine edit point " + std::to_string(j) + " is not finite");
    if (j > 0 && !(edit.u[j] > edit.u[j - 1]))
      throw InvalidArgument("spine edit u values must increase strictly (point " +
                            std::to_string(j) + ")");
    delta.push_back(edit.moved[j] - patch.spine(edit.u[j]));
  }
  SpectralPatch out = patch;
  out.spineOffsets_.push_back(spectral::naturalSpline(edit.u, std::move(delta)));
  return out;
}

}  // namespace pdesurf
