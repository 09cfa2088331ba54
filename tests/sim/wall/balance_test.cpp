// The tip-off rule (src/sim/wall/balance.hpp) on a unit cube balanced on an edge, against closed forms: the
// turn puts the centre of mass the offset beyond the edge, on the side asked for, at the height left by a
// rigid turn about it; a turn that would take a face past the wall stops where it lies flush (π/4 for a cube
// on an edge). Internal header. The poses are exact to a few ulps of L = 1, hence 1e-15.
#include "../../../src/sim/wall/balance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace repose::sim {
namespace {

// The unit cube turned by 45° about x: balanced on its edge along x, which lies on the wall (z = 0) at y = 0.
struct CubeOnEdge {
  std::vector<Vec3> vertices;
  Quat q = Quat(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitX()));
  Vec3 com = Vec3(0, 0, std::sqrt(0.5));
  Vec3 pivot = Vec3(-0.5, 0, 0);  // an end of the edge
  CubeOnEdge() {
    for (int i = 0; i < 8; ++i)
      vertices.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
  }
  // The pose after the turn: the centre of mass and the lowest vertex's height.
  std::pair<Vec3, double> after(const BalanceTurn& tip) const {
    const Quat q1 = (tip.turn * q).normalized();
    const Vec3 c1 = pivot + tip.turn * (com - pivot);
    double lowest = INFINITY;
    for (const Vec3& v : vertices) lowest = std::min(lowest, (c1 + q1 * v).z());
    return {c1, lowest};
  }
};

TEST(TipOffTurn, PutsTheCentreOfMassTheOffsetBeyondTheEdgeOnEitherSide) {
  const CubeOnEdge cube;
  const double offset = 1e-3, h = std::sqrt(0.5);
  for (const double side : {1.0, -1.0}) {
    const BalanceTurn tip =
        tip_off_turn(cube.vertices, cube.q, cube.com, cube.pivot, Vec2(1, 0), side, offset, 1e-9);
    EXPECT_EQ(tip.axis, Vec3(1, 0, 0));
    EXPECT_NEAR(tip.angle, -side * std::asin(offset / h), 1e-15);  // left of +x is +y: a turn by −α about x
    const auto [com, lowest] = cube.after(tip);
    EXPECT_NEAR(com.y(), side * offset, 1e-15);
    EXPECT_NEAR(com.z(), std::sqrt(h * h - offset * offset), 1e-15);
    EXPECT_NEAR(com.x(), 0.0, 1e-15);
    EXPECT_NEAR(lowest, 0.0, 1e-15);  // the edge stays on the wall, nothing goes below it
  }
}

// An offset of 0.6 > sin(π/4)·h would turn the cube by asin(0.6/h) ≈ 58°, past the face that lands flush
// after 45°: the turn stops there.
TEST(TipOffTurn, StopsWhereTheFirstVertexReachesTheWall) {
  const CubeOnEdge cube;
  for (const double side : {1.0, -1.0}) {
    const BalanceTurn tip =
        tip_off_turn(cube.vertices, cube.q, cube.com, cube.pivot, Vec2(1, 0), side, 0.6, 1e-9);
    EXPECT_NEAR(tip.angle, -side * std::numbers::pi / 4, 1e-15);
    const auto [com, lowest] = cube.after(tip);
    EXPECT_NEAR(lowest, 0.0, 1e-15);
    EXPECT_NEAR(com.z(), 0.5, 1e-15);  // flat on the next face
    EXPECT_NEAR(com.y(), side * 0.5, 1e-15);
  }
}

// The edge's other end lies on the line only to round-off: 1e-12 beyond it on the side the turn lowers and
// 1e-10 below the pivot, so atan2(x, z) ≈ π would stop the turn at once. Within `on_line` of the line it is
// on it, and the turn is the one without it.
TEST(TipOffTurn, AVertexOnTheLineByRoundOffDoesNotStopIt) {
  CubeOnEdge cube;
  const BalanceTurn clean =
      tip_off_turn(cube.vertices, cube.q, cube.com, cube.pivot, Vec2(1, 0), 1.0, 1e-3, 1e-9);
  cube.vertices.push_back(cube.q.conjugate() * (Vec3(0.5, 1e-12, -1e-10) - cube.com));
  const BalanceTurn tip =
      tip_off_turn(cube.vertices, cube.q, cube.com, cube.pivot, Vec2(1, 0), 1.0, 1e-3, 1e-9);
  EXPECT_EQ(tip.angle, clean.angle);
  EXPECT_EQ(tip_off_turn(cube.vertices, cube.q, cube.com, cube.pivot, Vec2(1, 0), 1.0, 1e-3, 0.0).angle, 0.0);
}

}  // namespace
}  // namespace repose::sim
