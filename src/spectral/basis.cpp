#include "numerics/eigen_warnings.hpp"  // first: see the file

#include "spectral/basis.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <type_traits>

namespace pdesurf::spectral {

std::vector<Root> modeRoots(const SpectralOperator& op, std::uint32_t n, double length) {
  const double nd = static_cast<double>(n);
  if (op.kind == OperatorKind::Ugail) {
    // (D² + a²n²·(-1)) in t: roots ±a·length·n, each N-fold (mode 0: 0, 2N-fold).
    if (n == 0) return {Root{0.0, 2 * op.power}};
    const double lambda = op.a * length * nd;
    return {Root{lambda, op.power}, Root{-lambda, op.power}};
  }
  if (n == 0) return {Root{0.0, 6}};
  // Fu: r⁶ = a' n⁶ with a' = a·length⁶ (∂u = ∂t / length). |r| = κ, arguments jπ/3 for
  // a' > 0 and π/6 + jπ/3 for a' < 0; one root per conjugate pair is kept.
  const double kappa = nd * std::pow(std::abs(op.a), 1.0 / 6.0) * length;
  if (kappa < kSeriesRadius) {
    Root series;
    series.multiplicity = 6;
    series.series = true;
    series.seriesC = op.a * std::pow(length * nd, 6.0);  // c = a' n⁶, |c| = κ⁶ < 1
    return {series};
  }
  const int shift = op.a > 0 ? 0 : 1;  // arguments in units of π/6
  std::vector<Root> roots;
  for (int j = 0; j < 6; ++j) {
    const int arg = shift + 2 * j;  // 0..11
    if (arg == 0) {
      roots.push_back({kappa, 1});
    } else if (arg == 6) {
      roots.push_back({-kappa, 1});
    } else if (arg < 6) {
      const double theta = arg * std::numbers::pi / 6.0;
      roots.push_back({std::complex<double>(kappa * std::cos(theta), kappa * std::sin(theta)), 1});
    }
  }
  return roots;
}

namespace {

/// Gauss–Legendre nodes and weights on [-1, 1] (Newton on P_n), computed once.
struct GaussLegendre {
  std::vector<double> x, w;
  explicit GaussLegendre(int n) : x(n), w(n) {
    for (int i = 0; i < n; ++i) {
      double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), dp = 0.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = z;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (z * p1 - p0) / (z * z - 1.0);
        const double dz = p1 / dp;
        z -= dz;
        if (std::abs(dz) < 1e-16) break;
      }
      x[i] = z;
      w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
  }
};

/// Nodes for the Stieltjes sums: exact for polynomial degree 2q-1 ≥ 2·count + 60.
int quadratureNodes(std::uint32_t count) {
  return std::min<int>(200, 2 * static_cast<int>(count) + 40);
}

Recurrence computeRecurrence(double sigma, std::uint32_t count, const GaussLegendre& gl) {
  // The weight is negligible beyond 2σx ≈ 4·count + 60 (even against p_k² growth): integrate
  // over [0, X] only, so a sharply decaying weight is resolved.
  const double xMax = sigma > 0.0 ? std::min(1.0, (4.0 * count + 60.0) / (2.0 * sigma)) : 1.0;
  const int q = static_cast<int>(gl.x.size());
  std::vector<Real> x(q), w(q), p(q, 0.0), pPrev(q, 0.0);
  Real total = 0.0;
  for (int i = 0; i < q; ++i) {
    x[i] = 0.5L * xMax * (gl.x[i] + 1.0L);
    w[i] = 0.5L * xMax * gl.w[i] * std::exp(-2.0L * sigma * x[i]);
    total += w[i];
  }
  Recurrence r;
  r.b.push_back(std::sqrt(total));
  for (int i = 0; i < q; ++i) p[i] = 1.0L / r.b[0];
  for (std::uint32_t k = 0; k < count; ++k) {
    Real a = 0.0;
    for (int i = 0; i < q; ++i) a += w[i] * x[i] * p[i] * p[i];
    r.alpha.push_back(a);
    if (k + 1 == count) break;
    Real norm = 0.0;
    for (int i = 0; i < q; ++i) {
      const Real next = (x[i] - a) * p[i] - r.b[k] * (k > 0 ? pPrev[i] : 0.0L);
      pPrev[i] = p[i];
      p[i] = next;
      norm += w[i] * next * next;
    }
    norm = std::sqrt(norm);
    r.b.push_back(norm);
    for (int i = 0; i < q; ++i) p[i] /= norm;
  }
  return r;
}

}  // namespace

Recurrence weightedRecurrence(double sigma, std::uint32_t count) {
  // Bases depend only on (σ, multiplicity): interactive re-solves with the same operator and
  // modes reuse them. A small process-wide cache, cleared when it grows large.
  static std::mutex mutex;
  static std::map<std::pair<double, std::uint32_t>, Recurrence> cache;
  static std::map<int, GaussLegendre> rules;
  const std::lock_guard<std::mutex> lock(mutex);
  const auto key = std::make_pair(sigma, count);
  if (const auto it = cache.find(key); it != cache.end()) return it->second;
  if (cache.size() > 4096) cache.clear();
  const int q = quadratureNodes(count);
  auto rule = rules.find(q);
  if (rule == rules.end()) rule = rules.emplace(q, GaussLegendre(q)).first;
  Recurrence r = computeRecurrence(sigma, count, rule->second);
  r.alphaD.assign(r.alpha.begin(), r.alpha.end());
  r.bD.assign(r.b.begin(), r.b.end());
  r.alphaQ.assign(r.alpha.begin(), r.alpha.end());
  r.bQ.assign(r.b.begin(), r.b.end());
  return cache.emplace(key, std::move(r)).first->second;
}

ModeBasis::ModeBasis(std::vector<Root> roots) : roots_(std::move(roots)) {
  for (const Root& r : roots_) {
    if (r.series) {  // no recurrence: the series functions are near monomials already
      nearPolynomial_ = roots_.size() == 1 && r.multiplicity <= 6;
      size_ += r.multiplicity;
      recurrences_.emplace_back();
      continue;
    }
    size_ += (r.mu.imag() != 0.0 ? 2 : 1) * r.multiplicity;
    recurrences_.push_back(weightedRecurrence(std::abs(r.mu.real()), r.multiplicity));
    const double m = r.multiplicity, mag = std::abs(r.mu);
    if (roots_.size() == 1 && mag == 0.0 && m <= 6) nearPolynomial_ = true;
    if (roots_.size() > 1 && m >= 2 && mag < 3 * m && (m >= 8 || mag < m)) extended_ = true;
  }
}

namespace {
constexpr std::uint32_t kMaxDerivatives = 130;  // orders up to 128 (N ≤ 64), plus 1

/// Pascal's triangle C(j, i) for j < kMaxDerivatives, computed once.
/// In the precision of the evaluation (T = double, Real or Quad).
template <typename T>
const std::vector<T>& binomials() {
  static const std::vector<T> table = [] {
    std::vector<T> t(kMaxDerivatives * kMaxDerivatives, T(0));
    for (std::uint32_t j = 0; j < kMaxDerivatives; ++j) {
      t[j * kMaxDerivatives] = T(1);
      for (std::uint32_t i = 1; i <= j; ++i)
        t[j * kMaxDerivatives + i] = t[(j - 1) * kMaxDerivatives + i - 1] +
                                     (i < j ? t[(j - 1) * kMaxDerivatives + i] : T(0));
    }
    return t;
  }();
  return table;
}
/// The series group of `r` (Root::series) at t: out(j, col + k) = d^j y_k / dt^j for
/// j < jCount. y_k' = y_{k-1} (k ≥ 1) and y_0' = c y_{p-1}, so derivatives rotate the values.
template <typename T, class M>
void evaluateSeries(const Root& r, double t, std::uint32_t jCount, M& out, std::uint32_t col) {
  const std::uint32_t p = r.multiplicity;
  assert(p <= kMaxDerivatives && std::abs(r.seriesC) <= 1.0);
  const T c = static_cast<T>(r.seriesC), tr = static_cast<T>(t);
  // |c| ≤ 1 and t ≤ 1: term m is at most 1/(pm)!, below 1e-40 for pm ≥ 36; a term below
  // 1e-36 of the sum (under every precision's rounding) ends the sum early (short patches:
  // c ~ 1e-10, two or three terms).
  const std::uint32_t terms = 36 / p + 2;
  T ctp = c;  // c t^p
  for (std::uint32_t q = 0; q < p; ++q) ctp = ctp * tr;
  std::array<T, kMaxDerivatives> y;
  T tk = T(1);  // t^k / k!
  for (std::uint32_t k = 0; k < p; ++k) {
    if (k > 0) tk = tk * tr / static_cast<T>(k);
    T term = tk, sum = tk;
    for (std::uint32_t m = 1; m < terms; ++m) {
      // term_m = term_{m-1} · c t^p / ((k+pm-p+1) ··· (k+pm)), the product exact in double
      double product = 1.0;
      for (std::uint32_t q = k + p * m - p + 1; q <= k + p * m; ++q) product *= q;
      term = term * ctp / static_cast<T>(product);
      sum += term;
      if (term * term <= T(1e-72) * sum * sum) break;
    }
    y[k] = sum;
  }
  for (std::uint32_t j = 0; j < jCount; ++j) {
    for (std::uint32_t k = 0; k < p; ++k) out(j, col + k) = y[k];
    const T first = c * y[p - 1];
    for (std::uint32_t k = p - 1; k > 0; --k) y[k] = y[k - 1];
    y[0] = first;
  }
}

}  // namespace

template <class M>
void ModeBasis::evaluate(double t, std::uint32_t maxDerivative, M& out) const {
  using T = typename M::Scalar;
  assert(maxDerivative < kMaxDerivatives);
  const std::uint32_t jCount = maxDerivative + 1;
  out.resize(jCount, size_);
  const std::vector<T>& binomTable = binomials<T>();
  std::array<std::complex<T>, kMaxDerivatives> muPow;
  thread_local std::vector<T> poly;  // poly[i * m + k] = d^i/dt^i p_k(x(t))
  std::uint32_t col = 0;
  for (std::size_t g = 0; g < roots_.size(); ++g) {
    const Root& r = roots_[g];
    if (r.series) {
      evaluateSeries<T>(r, t, jCount, out, col);
      col += r.multiplicity;
      continue;
    }
    const Recurrence& rec = recurrences_[g];
    const std::vector<T>* alphaT;
    const std::vector<T>* bT;
    if constexpr (std::is_same_v<T, double>) {
      alphaT = &rec.alphaD;
      bT = &rec.bD;
    } else if constexpr (std::is_same_v<T, Quad>) {
      alphaT = &rec.alphaQ;
      bT = &rec.bQ;
    } else {
      alphaT = &rec.alpha;
      bT = &rec.b;
    }
    const std::vector<T>& alpha = *alphaT;
    const std::vector<T>& bCoef = *bT;
    const std::uint32_t m = r.multiplicity;
    const bool growing = r.mu.real() > 0.0;
    const bool complexPair = r.mu.imag() != 0.0;
    // Differentiated recurrence: b_{k+1} p^{(i)}_{k+1} = (x - α_k) p^{(i)}_k + i p^{(i-1)}_k
    // - b_k p^{(i)}_{k-1}; x = t or 1 - t.
    const std::uint32_t iCount = std::min(jCount, m);
    const T x = growing ? T(1) - static_cast<T>(t) : static_cast<T>(t);
    poly.resize(static_cast<std::size_t>(iCount) * m);
    poly[0] = T(1) / bCoef[0];
    for (std::uint32_t i = 1; i < iCount; ++i) poly[i * m] = T(0);  // p_0 is constant
    for (std::uint32_t k = 0; k + 1 < m; ++k)
      for (std::uint32_t i = 0; i < iCount; ++i) {
        T v = (x - alpha[k]) * poly[i * m + k];
        if (i > 0) v += static_cast<T>(i) * poly[(i - 1) * m + k];
        if (k > 0) v -= bCoef[k] * poly[i * m + k - 1];
        poly[i * m + k + 1] = v / bCoef[k + 1];
      }
    if (growing)  // dx/dt = -1
      for (std::uint32_t i = 1; i < iCount; i += 2)
        for (std::uint32_t k = 0; k < m; ++k) poly[i * m + k] = -poly[i * m + k];
    const T c = growing ? T(1) : T(0);
    const T tr = static_cast<T>(t), re = static_cast<T>(r.mu.real()),
            im = static_cast<T>(r.mu.imag());
    using std::cos, std::exp, std::sin;  // Quad's by argument-dependent lookup
    const T e = exp(re * (tr - c));
    if (!complexPair) {
      // Real root: E^{(j)} = μ^j E.
      T pw[kMaxDerivatives];
      pw[0] = e;
      for (std::uint32_t j = 1; j < jCount; ++j) pw[j] = pw[j - 1] * re;
      for (std::uint32_t k = 0; k < m; ++k)
        for (std::uint32_t j = 0; j < jCount; ++j) {
          T sum = T(0);
          const std::uint32_t top = std::min(std::min(j, k), iCount - 1);
          for (std::uint32_t i = 0; i <= top; ++i)
            sum += binomTable[j * kMaxDerivatives + i] * poly[i * m + k] * pw[j - i];
          out(j, col + k) = static_cast<T>(sum);
        }
      col += m;
      continue;
    }
    const std::complex<T> mu(re, im);
    muPow[0] = std::complex<T>(e * cos(im * tr), e * sin(im * tr));
    for (std::uint32_t j = 1; j < jCount; ++j) muPow[j] = muPow[j - 1] * mu;
    for (std::uint32_t k = 0; k < m; ++k)
      for (std::uint32_t j = 0; j < jCount; ++j) {
        std::complex<T> sum = T(0);
        const std::uint32_t top = std::min(std::min(j, k), iCount - 1);
        for (std::uint32_t i = 0; i <= top; ++i)
          sum += binomTable[j * kMaxDerivatives + i] * poly[i * m + k] * muPow[j - i];
        out(j, col + k) = static_cast<T>(sum.real());
        out(j, col + m + k) = static_cast<T>(sum.imag());
      }
    col += 2 * m;
  }
  assert(col == size_);
}

template void ModeBasis::evaluate<SmallMatrix>(double, std::uint32_t, SmallMatrix&) const;
template void ModeBasis::evaluate<MatrixR>(double, std::uint32_t, MatrixR&) const;
template void ModeBasis::evaluate<MatrixQ>(double, std::uint32_t, MatrixQ&) const;

RowVectorR ModeBasis::row(double t, std::uint32_t derivative) const {
  MatrixR table;
  evaluate(t, derivative, table);
  return table.row(derivative);
}

}  // namespace pdesurf::spectral
