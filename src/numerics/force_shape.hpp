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

/// The amplitude k of the particular solution k sin(πs) sin(πt) that a force f0 on a region
/// of lengths lu × lv gives, per component, for the frame's a1 and a2 (seed eq. 12;
/// docs/derivations.md §1.5): k = -f0 / (π² (a1 / lu² + a2 / lv²)); 0 where f0 is 0.
inline double forceAmplitude(double f0, double a1, double a2, double lu, double lv) {
  if (f0 == 0.0) return 0.0;  // no force in this component: nothing to solve
  constexpr double kPi = std::numbers::pi;
  return -f0 / (kPi * kPi * (a1 / (lu * lu) + a2 / (lv * lv)));
}

/// The force f0 whose amplitude is k (the inverse of forceAmplitude).
inline double forceOfAmplitude(double k, double a1, double a2, double lu, double lv) {
  constexpr double kPi = std::numbers::pi;
  return -kPi * kPi * (k * (a1 / (lu * lu) + a2 / (lv * lv)));
}

}  // namespace pdesurf::detail
