// The PDE solve (seed 004 §3; docs/derivations.md §3.2, docs/bspline-pde.md): one mask equation per
// span pair, T_u P T_vᵀ = 0, split into the unknown block X and the given points:
// M X Nᵀ = Y = -T_u P₀ T_vᵀ (P₀: the net with its inner block zeroed), X = M⁻¹ Y N⁻ᵀ,
// evaluated in the low-rank form below (Y has rank ≤ 6 per component).
#include "numerics/eigen_warnings.hpp"  // first: before Eigen

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "bspline_pde/internal.hpp"

namespace pdesurf {
namespace bspline {

void validateNet(const ControlNet& net, bool innerExempt, std::string_view where) {
  const std::string prefix(where);
  if (net.nu < 3 || net.nv < 3)
    throw InvalidArgument(prefix + ": the net's last indices are nu = " + std::to_string(net.nu) +
                          ", nv = " + std::to_string(net.nv) +
                          "; both must be at least 3 (4 control points a direction)");
  const std::size_t expected =
      static_cast<std::size_t>(net.nu + 1) * static_cast<std::size_t>(net.nv + 1);
  if (net.points.size() != expected)
    throw InvalidArgument(prefix + ": a net with nu = " + std::to_string(net.nu) +
                          ", nv = " + std::to_string(net.nv) + " has " + std::to_string(expected) +
                          " points, got " + std::to_string(net.points.size()));
  for (std::uint32_t i = 0; i <= net.nu; ++i)
    for (std::uint32_t j = 0; j <= net.nv; ++j)
      if ((!innerExempt || net.given(i, j)) && !net(i, j).allFinite())
        throw InvalidArgument(prefix + ": control point (" + std::to_string(i) + ", " +
                              std::to_string(j) + ") is not finite");
}

namespace {

using Mask = std::array<double, 4>;

std::vector<Mask> masks(KnotType type, std::uint32_t n) {
  const std::vector<double> knots = cubicKnots(type, n);
  std::vector<Mask> out;
  out.reserve(n - 2);
  for (std::uint32_t s = 3; s <= n; ++s) out.push_back(thirdDerivativeMask(knots, s));
  return out;
}

/// M of docs/derivations.md §3.2 in band form: row a (span a+3) has t[r] at column a + r - 2.
BandedLu factoredSystem(const std::vector<Mask>& t, std::string_view direction) {
  const int m = static_cast<int>(t.size());
  BandedLu lu(m, 2, 1);
  for (int a = 0; a < m; ++a)
    for (int r = 0; r < 4; ++r) {
      const int c = a + r - 2;
      if (c >= 0 && c < m)
        lu.at(a, c) = t[static_cast<std::size_t>(a)][static_cast<std::size_t>(r)];
    }
  // Invertible for every n ≥ 3 (docs/bspline-pde.md: the 1-D kernel is the quadratics, fixed
  // by points 0, 1, n); a zero pivot would mean a bug, not bad input. Not a pdesurf::Error.
  if (!lu.factor())
    throw std::logic_error("BSplinePdeSolver: the " + std::string(direction) +
                           " system is singular (n = " + std::to_string(m + 2) + ")");
  return lu;
}

}  // namespace
}  // namespace bspline

ControlNet::ControlNet(std::uint32_t lastU, std::uint32_t lastV, const Vec3& fill)
    : nu(lastU),
      nv(lastV),
      points(static_cast<std::size_t>(lastU + 1) * static_cast<std::size_t>(lastV + 1), fill) {}

// The solve in low-rank form. Split the net's given points into the given rows
// Ku = {0, 1, nu} (all columns) and the given columns Kv = {0, 1, nv} of the inner rows
// (C = P[Iu, Kv]). With A_u = T_u[:, Ku] and A_v = T_v[:, Kv],
//   Y = -A_u B - M C A_vᵀ,   B = P[Ku, :] T_vᵀ,
// so X = M⁻¹ Y N⁻ᵀ = -F G - C Hᵀ with F = M⁻¹ A_u, H = N⁻¹ A_v (knots only: kept with the
// factors) and G = B N⁻ᵀ (3 × (nv-2) per component: 9 banded right-hand sides).
// Everything but the final rank-6 update is O(n); the update writes each inner point once.
struct BSplinePdeSolver::Impl {
  std::uint32_t nu = 0, nv = 0;
  BSplinePdeOptions options;
  std::vector<bspline::Mask> tu, tv;
  bspline::BandedLu mu, mv;
  bspline::RowMatrix f, h;  // (nu-2) × 3 and (nv-2) × 3
};

namespace bspline {
namespace {

/// M⁻¹ T[:, K], K = {0, 1, n}: the columns of the mask matrix on the given indices, solved.
RowMatrix givenColumnsSolved(const std::vector<Mask>& t, const BandedLu& lu, std::uint32_t n) {
  const int m = static_cast<int>(t.size());
  RowMatrix a = RowMatrix::Zero(m, 3);
  for (int s = 0; s < m; ++s)
    for (int r = 0; r < 4; ++r) {
      const auto k = static_cast<std::uint32_t>(s + r);
      const int column = k <= 1 ? static_cast<int>(k) : (k == n ? 2 : -1);
      if (column >= 0) a(s, column) = t[static_cast<std::size_t>(s)][static_cast<std::size_t>(r)];
    }
  lu.solve(a);
  return a;
}

}  // namespace
}  // namespace bspline

BSplinePdeSolver::BSplinePdeSolver(std::uint32_t nu, std::uint32_t nv,
                                   const BSplinePdeOptions& options)
    : impl_(std::make_unique<Impl>()) {
  if (nu < 3 || nv < 3)
    throw InvalidArgument("BSplinePdeSolver: nu = " + std::to_string(nu) + ", nv = " +
                          std::to_string(nv) + "; both last indices must be at least 3");
  impl_->nu = nu;
  impl_->nv = nv;
  impl_->options = options;
  impl_->tu = bspline::masks(options.uKnots, nu);
  impl_->tv = bspline::masks(options.vKnots, nv);
  impl_->mu = bspline::factoredSystem(impl_->tu, "u");
  impl_->mv = bspline::factoredSystem(impl_->tv, "v");
  impl_->f = bspline::givenColumnsSolved(impl_->tu, impl_->mu, nu);
  impl_->h = bspline::givenColumnsSolved(impl_->tv, impl_->mv, nv);
}

BSplinePdeSolver::~BSplinePdeSolver() = default;
BSplinePdeSolver::BSplinePdeSolver(BSplinePdeSolver&&) noexcept = default;
BSplinePdeSolver& BSplinePdeSolver::operator=(BSplinePdeSolver&&) noexcept = default;
std::uint32_t BSplinePdeSolver::nu() const { return impl_->nu; }
std::uint32_t BSplinePdeSolver::nv() const { return impl_->nv; }

void BSplinePdeSolver::solveInPlace(ControlNet& net) const {
  const Impl& s = *impl_;
  bspline::validateNet(net, true, "solve");
  if (net.nu != s.nu || net.nv != s.nv)
    throw InvalidArgument("BSplinePdeSolver: factored for nu = " + std::to_string(s.nu) +
                          ", nv = " + std::to_string(s.nv) + ", given a net with nu = " +
                          std::to_string(net.nu) + ", nv = " + std::to_string(net.nv));
  const std::uint32_t nu = s.nu, nv = s.nv;
  const int mu = static_cast<int>(nu) - 2, mv = static_cast<int>(nv) - 2;
  const std::array<std::uint32_t, 3> ku = {0, 1, nu}, kv = {0, 1, nv};
  // Gᵀ = N⁻¹ Bᵀ, Bᵀ(b, 3k + c) = Σ_q t_b[q] P(ku[k], b + q)[c].
  bspline::RowMatrix g(mv, 9);
  for (int b = 0; b < mv; ++b) {
    const bspline::Mask& t = s.tv[static_cast<std::size_t>(b)];
    const auto j = static_cast<std::uint32_t>(b);
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = ku[static_cast<std::size_t>(k)];
      const Vec3 sum =
          t[0] * net(i, j) + t[1] * net(i, j + 1) + t[2] * net(i, j + 2) + t[3] * net(i, j + 3);
      for (int c = 0; c < 3; ++c) g(b, 3 * k + c) = sum[c];
    }
  }
  s.mv.solve(g);
  // X(a, b) = -Σ_k F(a, k) G(k, b) - Σ_k C(a, k) H(b, k).
  for (int a = 0; a < mu; ++a) {
    const auto i = static_cast<std::uint32_t>(a + 2);
    const Vec3 c0 = net(i, kv[0]), c1 = net(i, kv[1]), c2 = net(i, kv[2]);
    const double f0 = s.f(a, 0), f1 = s.f(a, 1), f2 = s.f(a, 2);
    Vec3* row = &net(i, 2);
    for (int b = 0; b < mv; ++b) {
      const double* gb = g.row(b).data();
      const double* hb = s.h.row(b).data();
      for (int c = 0; c < 3; ++c)
        row[b][c] = -(f0 * gb[c] + f1 * gb[3 + c] + f2 * gb[6 + c]) -
                    (hb[0] * c0[c] + hb[1] * c1[c] + hb[2] * c2[c]);
    }
  }
}

BSplineSurface BSplinePdeSolver::solve(const ControlNet& net) const {
  ControlNet out = net;
  solveInPlace(out);
  return BSplineSurface(std::move(out), impl_->options.uKnots, impl_->options.vKnots);
}

BSplineSurface solve(const ControlNet& net, const BSplinePdeOptions& options) {
  bspline::validateNet(net, true, "solve");
  return BSplinePdeSolver(net.nu, net.nv, options).solve(net);
}

}  // namespace pdesurf
