// The spherical helpers (src/poses/spherical.hpp) differentiated automatically (Eigen's AutoDiffScalar), as
// the design's exact gradients will be (docs/inverse-design.md): against central finite differences, and the
// double instantiation against closed forms.
#include <gtest/gtest.h>

#include <Eigen/Core>  // before AutoDiff, which does not include it itself
#include <cmath>
#include <numbers>
#include <random>
#include <unsupported/Eigen/AutoDiff>
#include <vector>

#include "poses/spherical.hpp"

namespace repose::detail {
namespace {

using Ad = Eigen::AutoDiffScalar<Eigen::Vector3d>;

// An octant is an eighth of the sphere; the triangle of the north pole and two equator points α apart is half
// a lune of angle α, whose area is 2α.
TEST(SphericalArea, AnOctantAndHalfALuneHaveTheirClosedFormAreas) {
  const std::vector<Vec3> octant{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  EXPECT_NEAR(spherical_area(octant), 4 * std::numbers::pi / 8, 1e-15);
  for (const double alpha : {0.01, 0.7, 2.5}) {
    const std::vector<Vec3> half_lune{Vec3::UnitZ(), Vec3::UnitX(),
                                      Vec3(std::cos(alpha), std::sin(alpha), 0)};
    EXPECT_NEAR(spherical_area(half_lune), alpha, 1e-14) << alpha;
  }
}

// The area of a random convex spherical polygon (a clipped cap) as a function of one corner's direction: the
// automatic gradient equals the central difference of the double version to 1e-6 relative (step 1e-6: the
// difference's truncation error ~h² ≈ 1e-12 and its round-off ~1e-16/h ≈ 1e-10 of the area).
TEST(SphericalArea, ItsAutomaticGradientEqualsCentralDifferences) {
  std::mt19937_64 rng(50);
  std::normal_distribution<double> normal;
  int compared = 0;
  for (int trial = 0; trial < 200; ++trial) {
    // A convex polygon: a cap around a random axis cut by a few random half-spaces through the origin.
    const Vec3 axis = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    const Vec3 u = axis.unitOrthogonal(), w = axis.cross(u);
    std::vector<Vec3> polygon;
    for (int i = 0; i < 6; ++i) {
      const double phi = 2 * std::numbers::pi * i / 6 + 0.3 * normal(rng) / 6;
      polygon.push_back((axis + 0.8 * (std::cos(phi) * u + std::sin(phi) * w)).normalized());
    }
    std::vector<Vec3> clipped;
    clip_polygon(polygon, Vec3(axis + 0.5 * Vec3(normal(rng), normal(rng), normal(rng))).normalized(),
                 clipped);
    if (clipped.size() < 3) continue;
    // One corner moves: its three coordinates are the variables (the polygon stays convex for small moves).
    const std::size_t moved = static_cast<std::size_t>(trial) % clipped.size();
    std::vector<Vec3T<Ad>> ad(clipped.size());
    for (std::size_t i = 0; i < clipped.size(); ++i)
      for (int k = 0; k < 3; ++k)
        ad[i][k] = i == moved ? Ad(clipped[i][k], 3, k) : Ad(clipped[i][k], Eigen::Vector3d::Zero());
    const Ad area = spherical_area(ad);
    // The same value (Eigen may sum the dot products of doubles in another order: round-off apart).
    EXPECT_NEAR(area.value(), spherical_area(clipped), 1e-14);
    const double h = 1e-6;
    for (int k = 0; k < 3; ++k) {
      std::vector<Vec3> plus = clipped, minus = clipped;
      plus[moved][k] += h;
      minus[moved][k] -= h;
      const double fd = (spherical_area(plus) - spherical_area(minus)) / (2 * h);
      EXPECT_NEAR(area.derivatives()[k], fd, 1e-6 * std::max(1.0, std::abs(fd)))
          << "trial " << trial << ", " << k;
    }
    ++compared;
  }
  EXPECT_GE(compared, 150);
}

}  // namespace
}  // namespace repose::detail
