// Cross-section chains of sixth-order patches (seed 002 §3.2): method 2 (exact C2 by
// derivative matching) and method 1 (overlapping windows of six curves).
#include "spectral/eigen_warnings.hpp"  // first: see the file

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "spectral/internal.hpp"

namespace pdesurf {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;
using spectral::ConditionData;

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

ChainPatch makePatch(const SpectralOperator& op, std::uint32_t modes,
                     std::vector<ConditionData> conditions, std::uint32_t first,
                     std::uint32_t last) {
  ChainPatch p;
  p.patch = spectral::solveResolved(op, modes, 0.0, 1.0, std::move(conditions));
  p.firstCurve = first;
  p.lastCurve = last;
  p.shownFirstCurve = first;
  p.shownLastCurve = last;
  return p;
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

}  // namespace

CrossSectionChain buildCrossSectionChain(std::span<const CurveInput> curves,
                                         const CrossSectionOptions& options) {
  const SpectralOperator op = SpectralOperator::fu(options.a);
  const auto count = static_cast<std::uint32_t>(curves.size());
  const bool exact = options.method == ChainMethod::ExactC2;
  if (count < 4 || (!exact && count < 6))
    throw std::invalid_argument(std::string("a cross-section chain needs at least ") +
                                (exact ? "4" : "6 (method 1: windows of six)") + " curves, got " +
                                std::to_string(count));
  std::vector<ConditionData> data;
  for (std::uint32_t i = 0; i < count; ++i) {
    data.push_back(spectral::resolveCurve(curves[i], options.modes, options.parameterization,
                                          options.remainder, "curve " + std::to_string(i)));
    if (data.back().collapsed && i > 0 && i + 1 < count)
      throw std::invalid_argument("curve " + std::to_string(i) +
                                  ": degenerate section (all points coincide); only the first "
                                  "and last sections may collapse to a point");
  }
  CrossSectionChain chain;
  chain.method = options.method;
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
    // Derivatives in the chain parameter s (curve i at s = i): ∂s^k = ∂t^k / q^k.
    const double qa = a.lastCurve - a.firstCurve, qb = b.lastCurve - b.firstCurve;
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
