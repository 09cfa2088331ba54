// The wall-plane geometry of the stability test (section 2.4) against hand-computed distances: the signed
// margin of a point in a convex polygon, a segment and a point, and the polygon feature nearest an outside
// point. Internal header: the engine's building blocks, tested on their own. All values are exact in binary
// floating point or within a few ulps, hence 1e-15.
#include "../../../src/sim/wall/stability.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace repose::sim {
namespace {

// The unit square, counter-clockwise.
const std::vector<Vec2> kSquare = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};

// The downward ray from the centre of mass that picks the face a particle rests on (rest.cpp): it hits the
// unit right triangle in z = 0 from above inside and on its edges (1e-12 of the barycentric coordinates),
// misses it outside, behind the origin, and when it runs parallel to the plane (even through the triangle).
TEST(RayHitsTriangle, InsideAndOnTheEdgesButNotOutsideBehindOrParallel) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), down(0, 0, -1);
  EXPECT_TRUE(ray_hits_triangle(Vec3(0.25, 0.25, 1), down, a, b, c));
  EXPECT_TRUE(ray_hits_triangle(Vec3(0.5, 0.5, 1), down, a, b, c));  // on the hypotenuse
  EXPECT_TRUE(ray_hits_triangle(Vec3(0, 0, 1), down, a, b, c));      // on a corner
  EXPECT_FALSE(ray_hits_triangle(Vec3(0.5, 0.5 + 1e-9, 1), down, a, b, c));
  EXPECT_FALSE(ray_hits_triangle(Vec3(-1e-9, 0.5, 1), down, a, b, c));
  EXPECT_FALSE(ray_hits_triangle(Vec3(0.25, 0.25, -1), down, a, b, c));          // the triangle is behind it
  EXPECT_FALSE(ray_hits_triangle(Vec3(-1, 0.25, 0), Vec3(1, 0, 0), a, b, c));    // in the plane, across it
  EXPECT_FALSE(ray_hits_triangle(Vec3(0.25, 0.25, 1), Vec3(1, 0, 0), a, b, c));  // parallel, above it
}

TEST(PolygonMargin, InsideTheSquareItIsTheDistanceToTheNearestSide) {
  EXPECT_NEAR(polygon_margin(kSquare, Vec2(0.5, 0.5)), 0.5, 1e-15);
  EXPECT_NEAR(polygon_margin(kSquare, Vec2(0.25, 0.5)), 0.25, 1e-15);
  EXPECT_NEAR(polygon_margin(kSquare, Vec2(0.5, 0.875)), 0.125, 1e-15);
}

TEST(PolygonMargin, OutsideTheSquareItIsMinusTheDistanceToTheBoundary) {
  // Beside a side: the perpendicular distance; beyond a corner: the distance to the corner, not to the
  // sides' extensions (3-4-5 triangle from (1, 1) to (4, 5)).
  EXPECT_NEAR(polygon_margin(kSquare, Vec2(0.5, -2)), -2, 1e-15);
  EXPECT_NEAR(polygon_margin(kSquare, Vec2(4, 5)), -5, 1e-15);
  EXPECT_NEAR(polygon_margin(kSquare, Vec2(-3, -4)), -5, 1e-15);
}

TEST(PolygonMargin, ASegmentOrAPointHoldsNothing) {
  // A segment (collinear contacts): minus the distance to the segment, measured to its end beyond it.
  const std::vector<Vec2> segment = {{0, 0}, {2, 0}};
  EXPECT_NEAR(polygon_margin(segment, Vec2(1, 0.5)), -0.5, 1e-15);
  EXPECT_NEAR(polygon_margin(segment, Vec2(5, 4)), -5, 1e-15);
  EXPECT_NEAR(polygon_margin(segment, Vec2(-3, 0)), -3, 1e-15);
  EXPECT_NEAR(polygon_margin({Vec2(1, 1)}, Vec2(4, 5)), -5, 1e-15);
  EXPECT_EQ(polygon_margin({}, Vec2(0, 0)), -INFINITY);
}

TEST(ClosestFeature, AnEdgeWhenThePointProjectsInsideItElseACorner) {
  // Below the bottom side's middle: edge (0, 1); beyond the corner (1, 1): vertex 2; left of the left side:
  // edge (3, 0).
  const ClosestFeature below = closest_feature(kSquare, Vec2(0.5, -1));
  EXPECT_EQ(below.i, 0);
  EXPECT_EQ(below.j, 1);
  const ClosestFeature corner = closest_feature(kSquare, Vec2(3, 2));
  EXPECT_EQ(corner.i, 2);
  EXPECT_EQ(corner.j, -1);
  const ClosestFeature left = closest_feature(kSquare, Vec2(-1, 0.3));
  EXPECT_EQ(left.i, 3);
  EXPECT_EQ(left.j, 0);
  // A segment has one edge, not two.
  const ClosestFeature beside = closest_feature({Vec2(0, 0), Vec2(2, 0)}, Vec2(1.5, 1));
  EXPECT_EQ(beside.i, 0);
  EXPECT_EQ(beside.j, 1);
}

TEST(ConvexHull2d, DropsInteriorAndCollinearPointsAndKeepsCounterClockwiseOrder) {
  // The square's corners, its centre, a point in the middle of a side and a duplicate within tolerance.
  const std::vector<Vec2> hull =
      convex_hull_2d({{1, 1}, {0.5, 0.5}, {0, 0}, {0.5, 0}, {1, 0}, {0, 1}, {1 + 1e-13, 1}}, 1e-9);
  ASSERT_EQ(hull.size(), 4u);
  double twice_area = 0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Vec2& a = hull[i];
    const Vec2& b = hull[(i + 1) % hull.size()];
    twice_area += a.x() * b.y() - a.y() * b.x();
  }
  EXPECT_NEAR(twice_area, 2.0, 1e-12);  // positive: counter-clockwise; 2 × the unit area
  // Collinear points keep only their two extremes.
  const std::vector<Vec2> line = convex_hull_2d({{1, 1}, {0, 0}, {3, 3}, {2, 2}}, 1e-9);
  ASSERT_EQ(line.size(), 2u);
  EXPECT_NEAR(std::abs((line[1] - line[0]).norm()), std::sqrt(18.0), 1e-15);
}

}  // namespace
}  // namespace repose::sim
