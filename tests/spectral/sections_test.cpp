// Sections taken as they come (include/pdesurf/sections.hpp): the prepared sections do not
// depend on where each loop starts, which way it runs or how it is sampled; the first starts
// on the reference ray, later ones with the least twist; bad loops are named.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "pdesurf/sections.hpp"

namespace pdesurf {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// A star-shaped loop at height z: ρ(θ) = r (1 + 0.2 cos 3θ), turned by `turn`.
Vec3 starPoint(double z, double theta, double turn = 0.0) {
  const double r = (1.0 + 0.2 * z) * (1.0 + 0.2 * std::cos(3.0 * (theta - turn)));
  return {r * std::cos(theta), r * std::sin(theta), z};
}

/// The loop sampled at `count` angles from `start`, counter-clockwise or not, with the
/// angles bunched towards the start when `bunched` (a non-uniform sampling).
std::vector<Vec3> sampledStar(double z, int count, double start, bool ccw, bool bunched,
                              double turn = 0.0) {
  std::vector<Vec3> points;
  for (int j = 0; j < count; ++j) {
    double s = static_cast<double>(j) / count;
    if (bunched) s = s * s;
    points.push_back(starPoint(z, start + (ccw ? 1 : -1) * kTwoPi * s, turn));
  }
  return points;
}

double angleOf(const Vec3& p) { return std::atan2(p.y(), p.x()); }

/// Angular distance on the circle.
double angleGap(double a, double b) {
  const double d = std::fmod(std::abs(a - b), kTwoPi);
  return std::min(d, kTwoPi - d);
}

TEST(Sections, PreparedLoopsDoNotDependOnStartDirectionOrSampling) {
  const std::vector<double> zs = {0.0, 0.4, 0.9, 1.5, 2.0};
  std::vector<std::vector<Vec3>> canonical, scrambled;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(0.0, kTwoPi);
  for (std::size_t i = 0; i < zs.size(); ++i) {
    canonical.push_back(sampledStar(zs[i], 720, 0.0, true, false));
    scrambled.push_back(
        sampledStar(zs[i], 500 + 97 * static_cast<int>(i), angle(rng), i % 2 == 0, i % 3 == 1));
  }
  SectionPrepOptions o;
  o.points = 128;
  o.direction = Vec3::UnitZ();
  const auto a = prepareSections(canonical, o), b = prepareSections(scrambled, o);
  ASSERT_EQ(a.size(), zs.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].points.size(), 128u);
    ASSERT_EQ(b[i].points.size(), 128u);
    // Same points in the same order: up to the polygons' own chord error and the arc-length
    // shift a different sampling makes (a fraction of one of the 128 steps).
    double worst = 0.0;
    for (std::size_t j = 0; j < 128; ++j)
      worst = std::max(worst, (a[i].points[j] - b[i].points[j]).norm());
    EXPECT_LT(worst, 0.02) << "section " << i;  // a step is 2π·1.2/128 ≈ 0.06
    // Counter-clockwise about +z, whatever the input's direction.
    Vec3 area = Vec3::Zero();
    for (std::size_t j = 0; j < 128; ++j) area += b[i].points[j].cross(b[i].points[(j + 1) % 128]);
    EXPECT_GT(area.z(), 0.0);
    EXPECT_DOUBLE_EQ(b[i].v[1], kTwoPi / 128);
  }
}

TEST(Sections, FirstStartsOnTheReferenceRayAndLaterOnesWithTheLeastTwist) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(0.0, kTwoPi);
  SectionPrepOptions o;
  o.reference = Vec3(1, 0, 0);
  // Ellipses of one orientation, scaled and moved along z, each sampled from a random start:
  // the least twist puts every start on the same side, where the first one starts (the ray
  // along +x from its centroid meets it at angle 0).
  std::vector<std::vector<Vec3>> ellipses;
  for (int i = 0; i < 6; ++i) {
    const double s = 1.0 + 0.1 * i, start = angle(rng);
    std::vector<Vec3> loop;
    for (int j = 0; j < 300 + 40 * i; ++j) {
      const double t = start + kTwoPi * j / (300 + 40 * i);
      loop.emplace_back(1.3 * s * std::cos(t), 0.8 * s * std::sin(t), 0.4 * i);
    }
    ellipses.push_back(loop);
  }
  const auto aligned = prepareSections(ellipses, o);
  EXPECT_NEAR(aligned[0].points[0].y(), 0.0, 1e-9);
  EXPECT_GT(aligned[0].points[0].x(), 0.0);
  for (std::size_t i = 1; i < aligned.size(); ++i)
    EXPECT_LT(angleGap(angleOf(aligned[i].points[0]), 0.0), 0.01) << "section " << i;
  // Stars turned by a growing angle: no start of a section twists less against the section
  // before it than the one chosen (checked against 720 starts along each loop).
  std::vector<std::vector<Vec3>> stars;
  for (int i = 0; i < 6; ++i)
    stars.push_back(sampledStar(0.3 * i, 900, angle(rng), true, false, 0.15 * i));
  const auto prepared = prepareSections(stars, o);
  // The twist: the summed squared distances between the loops' points in order, each loop
  // centred and scaled to unit RMS radius (as a 3 × n matrix: columns less their mean, over
  // the Frobenius norm / √n).
  auto twist = [](const std::vector<Vec3>& p, const std::vector<Vec3>& q) {
    auto shape = [](const std::vector<Vec3>& x) {
      const auto n = static_cast<Eigen::Index>(x.size());
      const Eigen::Matrix3Xd m = Eigen::Map<const Eigen::Matrix3Xd>(x.front().data(), 3, n);
      const Eigen::Matrix3Xd centred = m.colwise() - m.rowwise().mean();
      return Eigen::Matrix3Xd(centred * (std::sqrt(static_cast<double>(n)) / centred.norm()));
    };
    return (shape(p) - shape(q)).squaredNorm();
  };
  for (std::size_t i = 1; i < prepared.size(); ++i) {
    const double chosen = twist(prepared[i - 1].points, prepared[i].points);
    const std::vector<Vec3>& q = prepared[i].points;
    for (int k = 1; k < 720; ++k) {
      // The same loop started k/720 of the way round (its 128 points, linearly between).
      std::vector<Vec3> other;
      for (std::size_t j = 0; j < q.size(); ++j) {
        const double x = static_cast<double>(j) + k * q.size() / 720.0;
        const auto j0 = static_cast<std::size_t>(std::floor(x));
        const double f = x - std::floor(x);
        other.push_back((1 - f) * q[j0 % q.size()] + f * q[(j0 + 1) % q.size()]);
      }
      EXPECT_LE(chosen, twist(prepared[i - 1].points, other) + 1e-6)
          << "section " << i << " start " << k;
    }
  }
}

TEST(Sections, BadLoopsAreNamed) {
  auto expectError = [](std::vector<std::vector<Vec3>> loops, const std::string& what) {
    try {
      prepareSections(loops);
      FAIL() << "accepted: " << what;
    } catch (const SectionError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  const std::vector<Vec3> good = sampledStar(0, 40, 0, true, false);
  // A figure eight: two lobes through the origin.
  std::vector<Vec3> eight;
  for (int j = 0; j < 40; ++j) {
    const double t = kTwoPi * j / 40;
    eight.emplace_back(std::sin(t), std::sin(t) * std::cos(t), 1.0);
  }
  expectError({good, eight}, "section 1: is not a simple closed curve: its edges");
  expectError({good, {Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 0, 1)}}, "section 1: has 2 distinct");
  expectError({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)}, good}, "section 0: encloses no area");
  std::vector<Vec3> nan = good;
  nan[3].x() = std::nan("");
  expectError({good, good, nan}, "section 2: point 3 is not finite");
}

}  // namespace
}  // namespace pdesurf
