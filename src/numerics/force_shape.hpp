// The shape of a sculpting force along one parameter (seed eq. 9; docs/derivations.md §1.5).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pdesurf::detail {

struct ForceShape {
  double s, ds;  ///< sin(π t) and its derivative with respect to the patch parameter
};

/// sin(π t), t = (x - x0)/(x1 - x0), on [x0, x1] and 0 outside. Evaluated as
/// sin(π·min(t, 1-t)), which is exactly 0 at both ends of the region (sin(π) rounds to
/// 1.2e-16), so a force never moves a patch's border or the region's.
inline ForceShape forceShape(double x, double x0, double x1) {
  if (x < x0 || x > x1) return {0.0, 0.0};
  constexpr double kPi = std::numbers::pi;
  const double len = x1 - x0;
  const double t = (x - x0) / len;
  return {std::sin(kPi * std::min(t, 1.0 - t)), kPi / len * std::cos(kPi * t)};
}

}  // namespace pdesurf::detail
