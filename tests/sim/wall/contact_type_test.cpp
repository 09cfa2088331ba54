// Algorithm 1's best-fit line and contact type against hand-computed scatter: the principal direction and
// the residual sum of squared distances (RSS) of small point sets. Internal header: these are the engine's
// building blocks, tested on their own.
#include "../../../src/sim/wall/contact_type.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace repose::sim {
namespace {

TEST(LineFit, PointsOnALineGiveItsDirectionAndNoResidual) {
  // Three points on the line through (1, 2, 0) along (3, 4, 0)/5, in the wall plane (the engine's case) and
  // tilted out of it (the general 3-D path).
  for (const Vec3& d : std::vector<Vec3>{Vec3(3, 4, 0) / 5, Vec3(2, -1, 2) / 3}) {
    const Vec3 o(1, 2, 0);
    const LineFit f = fit_line({o - 2 * d, o + 0.5 * d, o + 4 * d});
    EXPECT_NEAR(std::abs(f.direction.dot(d)), 1.0, 1e-14);
    EXPECT_NEAR(f.rss, 0.0, 1e-13);
    EXPECT_LT((f.centroid - (o + 2.5 / 3 * d)).norm(), 1e-14);
  }
}

TEST(LineFit, ARectangleOfPointsLeavesTheShortSidesSpread) {
  // Corners of an a × b rectangle (a > b) centred at c: the best line runs along a, through c, and each
  // corner is b/2 from it, so RSS = 4·(b/2)² = b². Rotated by 0.3 rad in the plane, and stood up out of the
  // plane.
  const double a = 3, b = 1;
  const Vec3 c(0.5, -1, 0);
  const Vec3 u(std::cos(0.3), std::sin(0.3), 0), v(-std::sin(0.3), std::cos(0.3), 0);
  for (const Vec3& w : std::vector<Vec3>{v, Vec3(0, 0, 1)}) {
    std::vector<Vec3> pts;
    for (double s : {-1.0, 1.0})
      for (double t : {-1.0, 1.0}) pts.push_back(c + s * a / 2 * u + t * b / 2 * w);
    const LineFit f = fit_line(pts);
    EXPECT_NEAR(std::abs(f.direction.dot(u)), 1.0, 1e-14);
    EXPECT_NEAR(f.rss, b * b, 1e-13);
    EXPECT_EQ(classify_contact(pts, 0.99 * b * b), ContactType::surface);
    EXPECT_EQ(classify_contact(pts, 1.01 * b * b), ContactType::line);
  }
}

TEST(LineFit, CoincidentPointsStillGiveAUnitDirection) {
  // Two contact points with the same footprint (a vertical edge inside the contact band): no spread at all.
  // The direction is arbitrary but must be a unit vector, or a line contact would rotate about a zero axis.
  const LineFit f = fit_line({Vec3(1, 1, 0), Vec3(1, 1, 0)});
  EXPECT_NEAR(f.direction.norm(), 1.0, 1e-15);
  EXPECT_EQ(f.rss, 0.0);
  EXPECT_EQ(classify_contact({Vec3(1, 1, 0)}, 1.0), ContactType::point);
}

}  // namespace
}  // namespace repose::sim
