// Unstable balances are not rests (issue 12, "no snaps"): a particle started exactly on one, with no motion,
// is tipped off by the documented rule (src/sim/tolerances.hpp, tol::kBalanceOffset: its centre of mass moved
// 1e-8·L beyond the edge) and falls from there as an inverted pendulum, whatever its surface rules (faceted
// or smooth).
#include <gtest/gtest.h>

#include <cmath>

#include "../support/pendulum.hpp"
#include "../support/zero_margin_prism.hpp"
#include "gravity.hpp"
#include "repose/model/particle.hpp"
#include "repose/sim/settle.hpp"

namespace repose {
namespace {

// A sphere mesh is a smooth surface (the engine's smooth rules). Its vertices are all at the same distance
// from the centre, so an edge's midpoint direction is perpendicular to the edge: turning that direction
// straight down puts the edge on the wall, level, with the centre of mass exactly above it. Undamped, it
// leaves the balance as the pendulum about the edge does from the rule's offset: at the quadrature's time
// for a tilt φ1 = 0.02 rad (before a neighbouring facet can land, ~0.1 rad away), the tilt is φ1.
TEST(Balance, SmoothSphereOnAnEdgeIsTippedOffByTheRuleAndFallsAsAPendulum) {
  const Particle sphere = load_particle("ellipsoid:a=1,b=1,c=1,n=4", 1.0);
  ASSERT_TRUE(is_smooth_surface(sphere));
  const HullFace& face = sphere.hull.faces.front();
  const Vec3 a = sphere.hull.vertices[static_cast<std::size_t>(face.loop[0])];
  const Vec3 b = sphere.hull.vertices[static_cast<std::size_t>(face.loop[1])];
  ASSERT_NEAR(a.norm(), b.norm(), 1e-12);
  const Vec3 mid = 0.5 * (a + b), e = (b - a).normalized();
  const double d = mid.norm();
  const double inertia = (e.dot(sphere.mass.inertia * e) + sphere.mass.mass * d * d) / sphere.mass.mass;
  const Quat q = Quat::FromTwoVectors(mid.normalized(), Vec3(0, 0, -1));

  SettleParams params;
  params.damping = 0;
  const double phi0 = std::asin(1e-8 * sphere.length / d), phi1 = 0.02;
  const double time = pendulum::undamped_tip_time(inertia, test::kGravitySI * d, phi0, phi1);
  Settler run(sphere, params, q);
  const Vec3 pivot = run.sample().com + run.sample().orientation * (mid - Vec3::Zero());  // on the wall
  ASSERT_NEAR(pivot.z(), 0, 1e-12);
  run.advance_to(time);
  const Vec3 arm = run.sample().com - pivot;
  const double tilt = std::atan2(std::hypot(arm.x(), arm.y()), arm.z());
  // Measured error 3.9e-8 rad (the tilt grows as e^(λt), so this is a time error of 1.3e-7 relative, as in
  // the cylinder's tip in settle_test.cpp); 4e-7 is 10×. Left to round-off, the tilt here is 2e-12 rad.
  EXPECT_NEAR(tilt, phi1, 4e-7) << "at t = " << time;

  // And it goes on to rest on a facet, its centre of mass the facet's distance from the centre above it.
  const SettleResult r = run.run();
  ASSERT_EQ(r.status, Status::rest) << to_string(r.status) << " at t = " << r.time;
  double nearest = INFINITY;
  for (const HullFace& f : sphere.hull.faces) nearest = std::min(nearest, std::abs(r.com.z() - f.offset));
  EXPECT_LT(nearest, 1e-9 * sphere.length);
}

// A face whose stability margin is exactly 0 (the triangular prism of frictional_balance_test.cpp: section
// A(0,0), B(1,0), C(2,1), centroid x = 1 over the edge B of AB), started at rest on AB with the paper's
// rolling contact (friction inf). It used to stay balanced there until the step limit (10,000 steps, 634 s);
// the rule now tips it outwards over B and it rolls onto BC about the fixed edge: the centre of mass ends at
// x = d·sin(π/4), d = |BG| = 1/3 (1e-9·L: the flush snap), on the face BC.
TEST(Balance, FaceOfZeroMarginIsTippedOffOverTheEdgeUnderTheCentreOfMass) {
  const Particle prism = test_shapes::zero_margin_prism();
  const SettleResult r = settle(prism, SettleParams{}, Quat::Identity());
  ASSERT_EQ(r.status, Status::rest);
  EXPECT_TRUE(r.down_normal_body.isApprox(Vec3(1, 0, -1).normalized(), 1e-9));
  EXPECT_NEAR(r.com.x(), std::sin(3.141592653589793 / 4) / 3, 1e-9 * prism.length);
  EXPECT_LT(r.steps, 1000);
}

// The same tip at the prism's four quarter turns about the vertical (the rule's choice of the edge under the
// centre of mass must not depend on where the face lies on the wall: edge A is 1 from the pivot B at the
// origin, edge B 0), and the motion after it planar by the prism's mirror symmetry in its depth: it turns
// about its edge B alone, ω parallel to it at every sample (1e-9 relative: round-off of the rotation; a point
// support at the pivot corner would turn it about that corner too). It rests on BC with the centre of mass
// d·sin(π/4) from the edge's line, which passes through the origin.
TEST(Balance, ZeroMarginTipIsTheSameAtEveryQuarterTurnAndTurnsAboutTheEdgeAlone) {
  const Particle prism = test_shapes::zero_margin_prism();
  for (int quarter = 0; quarter < 4; ++quarter) {
    const Quat q(Eigen::AngleAxisd(quarter * 3.141592653589793 / 2, Vec3::UnitZ()));
    const Vec3 edge = q * Vec3::UnitY();
    double worst = 0;
    const SettleResult r = settle(prism, SettleParams{}, q, [&](const Sample& s) {
      worst = std::max(worst, s.omega.cross(edge).norm() / std::max(s.omega.norm(), 1e-300));
    });
    ASSERT_EQ(r.status, Status::rest) << "quarter turn " << quarter;
    EXPECT_TRUE(r.down_normal_body.isApprox(Vec3(1, 0, -1).normalized(), 1e-9)) << "quarter turn " << quarter;
    const Vec3 across = edge.cross(Vec3::UnitZ());  // horizontal, normal to the edge
    EXPECT_NEAR(std::abs(r.com.dot(across)), std::sin(3.141592653589793 / 4) / 3, 1e-9 * prism.length)
        << "quarter turn " << quarter;
    EXPECT_LT(worst, 1e-9) << "quarter turn " << quarter;
    EXPECT_LT(r.steps, 1000) << "quarter turn " << quarter;
  }
}

}  // namespace
}  // namespace repose
