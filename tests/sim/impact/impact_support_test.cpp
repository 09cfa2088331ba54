// The support after an impact that leaves several points on the wall, against hand computation. Internal
// header: the engine's building block, tested on its own.
//
// The hand computation: with no spin before the impact (ω = 0) and centre-of-mass velocity v, the angular
// momentum about a new support point P is m·r × v (r = G − P), conserved by the impact. About a line through
// P along the horizontal unit vector e the rotation is ω' = ℓ/(eᵀ·I_P·e)·e with ℓ = e·(m·r × v) = m·v·(e ×
// r), so a point T on the wall moves vertically at (ω' × (T − P))_z, whose sign is that of ℓ·(e × (T − P))_z:
// the sign of a triple product, whatever the inertia. About a point P, with an isotropic body inertia k·1,
// I_P = (k + m·|r|²)·1 − m·r·rᵀ and m·r × v ⟂ r, so ω' = (m·r × v)/(k + m·|r|²): T (at the wall's height)
// moves vertically at a positive multiple of −D·(T − P), D = r_z·v_xy − v_z·r_xy (both in the wall plane).
#include "../../../src/sim/impact/impact_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace repose::sim {
namespace {

Body test_body() {
  Body b;
  b.mass = 1;
  b.inertia = 0.1 * Mat3::Identity();  // isotropic: see the file comment
  b.gravity = 9.81;
  return b;
}

// A touching point at world (x, y, height), body frame relative to the centre of mass `com` (q = 1).
WallVertex touch(int vertex, double x, double y, double height, const Vec3& com) {
  const Vec3 w(x, y, height);
  return {vertex, w, w - com, height};
}

// The touching points A (0, 0), B (2, 0), C (0, 2) on the wall, vertices first, first + 1, first + 2.
std::vector<WallVertex> triangle_abc(const Vec3& com, int first = 0) {
  return {touch(first, 0, 0, 0, com), touch(first + 1, 2, 0, 0, com), touch(first + 2, 0, 2, 0, com)};
}

TEST(ImpactSupport, AFarSideEdgeIsChosenWhenTheNearestEdgeAndTheFirstEdgeWouldDriveAPointDown) {
  // Touching points A (0, 0), B (2, 0), C (0, 2) (their polygon is A, B, C in that order), centre of mass
  // G = (−0.2, 1, 1) just outside edge CA, arriving at v = (2, 0.5, −1) with no spin. By the file comment's
  // triple products:
  //   about CA (nearest; P = C, e = (0, −1, 0)): e × r = (−1, 0, −0.2), ℓ ∝ v·(e × r) = −1.8 < 0, and B moves
  //     at the sign of ℓ·(e × (B − C))_z = ℓ·2: down;
  //   about AB (the polygon's first edge; P = A, e = (1, 0, 0)): e × r = (0, −1, 1), ℓ ∝ −1.5, C moves at
  //   ℓ·2:
  //     down;
  //   about BC (P = B, e = (−1, 1, 0)/√2): e × r = (1, 1, 1.2)/√2, ℓ ∝ 1.3 > 0, A moves at ℓ·2/√2: up.
  // So the support is the line BC, through B.
  const Body body = test_body();
  const Vec3 com(-0.2, 1, 1);
  const SwitchState impact{body, Quat::Identity(), com, Vec3::Zero(), Vec3(2, 0.5, -1), 1.0, 1e-9, 1e-6};
  const std::vector<WallVertex> touching = triangle_abc(com, 10);
  Support about_ca{touching[2].world, touching[2].body, true, Vec3(0, -1, 0)};
  Support about_ab{touching[0].world, touching[0].body, true, Vec3(1, 0, 0)};
  Support about_bc{touching[1].world, touching[1].body, true, Vec3(-1, 1, 0).normalized()};
  EXPECT_FALSE(others_separate(impact, touching, about_ca));
  EXPECT_FALSE(others_separate(impact, touching, about_ab));
  EXPECT_TRUE(others_separate(impact, touching, about_bc));

  const SupportChoice c = choose_from_touching(impact, touching, Vec2(com.x(), com.y()));
  EXPECT_EQ(c.vertex, 11);
  EXPECT_TRUE(c.support.line);
  EXPECT_NEAR(std::abs(c.support.axis.dot(Vec3(-1, 1, 0).normalized())), 1.0, 1e-15);
  EXPECT_EQ(c.support.axis.z(), 0.0);
}

TEST(ImpactSupport, FromRestTheNearestFeatureLetsTheOthersLiftOff) {
  // No motion: only gravity, which acts like v = (0, 0, −1) in the file comment (D ∝ r_xy). The centre of
  // mass G = (3, 0.5, 1) is beyond corner B (2, 0) of the triangle A (0, 0), B, C (0, 2) (in B's normal cone:
  // (G − B)·(A − B) = −2 < 0, (G − B)·(C − B) = −1 < 0), so the particle tips about B alone and A and C rise.
  const Body body = test_body();
  const Vec3 com(3, 0.5, 1);
  const SwitchState impact{body, Quat::Identity(), com, Vec3::Zero(), Vec3::Zero(), 1.0, 1e-9, 1e-6};
  const std::vector<WallVertex> touching = triangle_abc(com);
  const SupportChoice c = choose_from_touching(impact, touching, Vec2(com.x(), com.y()));
  EXPECT_EQ(c.vertex, 1);
  EXPECT_FALSE(c.support.line);
  EXPECT_EQ(c.support.world, touching[1].world);
  EXPECT_FALSE(c.stop);
}

TEST(ImpactSupport, WhenNoFeatureLetsTheOthersLiftTheNearestEdgeKeepsTwoPointsOnTheWall) {
  // From rest with the centre of mass G = (0.5, 0.6, 1) inside the triangle A (0, 0), B (2, 0), C (0, 2),
  // every feature drives a point down (file comment, v = (0, 0, −1), D ∝ r_xy): about an edge the third
  // vertex is on G's side, so it turns down with G; about a corner P, −D·(T − P) < 0 for both other
  // vertices (about A: −(0.5, 0.6)·(2, 0) = −1 and −(0.5, 0.6)·(0, 2) = −1.2; B and C likewise). The fallback
  // is the edge nearest G: CA (distance 0.5; AB is 0.6, BC |0.5 + 0.6 − 2|/√2 = 0.64), along y.
  const Body body = test_body();
  const Vec3 com(0.5, 0.6, 1);
  const SwitchState impact{body, Quat::Identity(), com, Vec3::Zero(), Vec3::Zero(), 1.0, 1e-9, 1e-6};
  const std::vector<WallVertex> touching = triangle_abc(com);
  for (const WallVertex& p : touching)
    EXPECT_FALSE(others_separate(impact, touching, Support{p.world, p.body}));
  EXPECT_FALSE(
      others_separate(impact, touching, Support{touching[0].world, touching[0].body, true, Vec3(1, 0, 0)}));
  EXPECT_FALSE(
      others_separate(impact, touching, Support{touching[0].world, touching[0].body, true, Vec3(0, 1, 0)}));
  EXPECT_FALSE(others_separate(
      impact, touching, Support{touching[1].world, touching[1].body, true, Vec3(-1, 1, 0).normalized()}));
  const SupportChoice c = choose_from_touching(impact, touching, Vec2(com.x(), com.y()));
  EXPECT_TRUE(c.vertex == 0 || c.vertex == 2) << c.vertex;
  EXPECT_TRUE(c.stop);
  EXPECT_TRUE(c.support.line);
  EXPECT_NEAR(std::abs(c.support.axis.y()), 1.0, 1e-15);
  EXPECT_EQ(c.support.axis.z(), 0.0);
}

TEST(ImpactSupport, WhenNoFeatureLetsTheOthersLiftTheMotionStopsAndGravityChooses) {
  // The centre of mass G = (−0.5, −0.5, 1) beyond corner A of the triangle A (0, 0), B (2, 0), C (0, 2),
  // arriving at v = (1, 1, −1) (towards the triangle) with no spin. By the file comment:
  //   about A: D = (v_x + 0.5·v_z, v_y + 0.5·v_z) = (0.5, 0.5), D·(B − A) = 1 > 0: B goes down;
  //   about B: D = (v_x + 2.5·v_z, v_y + 0.5·v_z) = (−1.5, 0.5), D·(A − B) = 3 > 0: A goes down;
  //   about C: D = (v_x + 0.5·v_z, v_y + 2.5·v_z) = (0.5, −1.5), D·(A − C) = 3 > 0: A goes down;
  //   about AB (P = A, e = x): e × r = (0, −1, −0.5), ℓ ∝ −v_y − 0.5·v_z = −0.5 < 0: C goes down;
  //   about CA (P = C, e = −y): e × r = (−1, 0, −0.5), ℓ ∝ −0.5 < 0: B goes down;
  //   about BC (P = B, e ∝ (−1, 1, 0)): e × r ∝ (1, 1, 3), ℓ ∝ v_x + v_y + 3·v_z = −1 < 0: A goes down.
  // Nothing lets the others lift: the approaching points are struck together, plastically, and the motion
  // stops. From rest G beyond A tips the particle about A alone, B and C rising (as in
  // FromRestTheNearestFeatureLetsTheOthersLiftOff). (Before, the motion was kept about the edge AB, which
  // drove C into the wall at once, step after step: a tossed die that never came to rest.)
  const Body body = test_body();
  const Vec3 com(-0.5, -0.5, 1);
  const SwitchState impact{body, Quat::Identity(), com, Vec3::Zero(), Vec3(1, 1, -1), 1.0, 1e-9, 1e-6};
  const std::vector<WallVertex> touching = triangle_abc(com);
  for (const WallVertex& p : touching)
    EXPECT_FALSE(others_separate(impact, touching, Support{p.world, p.body}));
  EXPECT_FALSE(
      others_separate(impact, touching, Support{touching[0].world, touching[0].body, true, Vec3(1, 0, 0)}));
  EXPECT_FALSE(
      others_separate(impact, touching, Support{touching[2].world, touching[2].body, true, Vec3(0, -1, 0)}));
  EXPECT_FALSE(others_separate(
      impact, touching, Support{touching[1].world, touching[1].body, true, Vec3(-1, 1, 0).normalized()}));
  const SupportChoice c = choose_from_touching(impact, touching, Vec2(com.x(), com.y()));
  EXPECT_TRUE(c.stop);
  EXPECT_EQ(c.vertex, 0);
  EXPECT_FALSE(c.support.line);
  SwitchState still = impact;
  still.com_velocity = Vec3::Zero();
  EXPECT_TRUE(others_separate(still, touching, c.support));
}

TEST(ImpactSupport, APointRisingSlowerThanTheVelocityToleranceOrPulledBackAtOnceDoesNotSeparate) {
  // A hinge along x through P = (0, 0, 0); the other touching point T = (0, 1, 0); centre of mass
  // G = (0, 0.5, 1), no translation, spin w about x before. By hand (file comment, isotropic k = 0.1, m = 1):
  // ℓ = k·w, I about the hinge = k + m·(0.5² + 1²) = 1.35, so ω = (k·w/1.35, 0, 0) and T rises at
  // v_z = ω_x·1; gravity's moment about x is (G − P) × (0, 0, −m·g) = −0.5·m·g, so T is pulled down at
  // a_z = −0.5·g/1.35 (no centripetal part: T − P is horizontal). The rule (impact_support.hpp): a point
  // rising at ≤ 1e-9·sqrt(g·L) with a_z < −1e-9·g does not separate; nor does one that a_z brings back
  // within a tenth of the window dt (2·v_z/(−a_z) < 0.1·dt).
  const Body body = test_body();
  const Vec3 com(0, 0.5, 1);
  const WallVertex p = touch(0, 0, 0, 0, com), t = touch(1, 0, 1, 0, com);
  const Support hinge{p.world, p.body, true, Vec3(1, 0, 0)};
  const double g = body.gravity, a_z = -0.5 * g / 1.35;
  auto separates = [&](double v_z, double dt, double length = 1.0) {
    const Vec3 spin(1.35 * v_z / 0.1, 0, 0);
    const SwitchState impact{body, Quat::Identity(), com, spin, Vec3::Zero(), length, 1e-9, dt};
    return others_separate(impact, {p, t}, hinge);
  };
  const double slow = 1e-7 * std::sqrt(g);   // 100× the velocity tolerance
  const double back = 2 * slow / -a_z;       // 1.7e-7 s until T is back on the wall
  EXPECT_TRUE(separates(slow, 5 * back));    // a tenth of the window is 0.5·back: it stays up longer
  EXPECT_FALSE(separates(slow, 20 * back));  // pulled back within 2·back, a tenth of this window
  EXPECT_FALSE(separates(1e-10 * std::sqrt(g), 1e-15));  // below the velocity tolerance, a_z down
  EXPECT_FALSE(separates(-slow, 1e-15));                 // moving down
  // The tolerance is a speed, 1e-9·sqrt(g·L): for L = 100 (the rule reads L only there) it is
  // 1e-8·sqrt(g), so a point rising at 3e-9·sqrt(g) still does not separate; for L = 1e-2 it is
  // 1e-10·sqrt(g), so the same point does (it stays up far longer than a tenth of this window).
  EXPECT_FALSE(separates(3e-9 * std::sqrt(g), 1e-15, 100.0));
  EXPECT_TRUE(separates(3e-9 * std::sqrt(g), 1e-15, 1e-2));
}

TEST(ImpactSupport, ASmoothParticlePivotsOnItsLowestNewTouch) {
  // Current support C0 (0, 1) and two new touches, A (0, 0) 2e-12 below the wall and
  // B (1, 0) 1e-12 below: the pivot is the lowest, A, listed between the others so that list order cannot
  // pass for depth. Centre of mass G = (0.6, 0.6, 1), arriving at v = (−2, −2, −1): about A, D = r_z·v_xy −
  // v_z·r_xy = (−2, −2) + (0.6, 0.6) = (−1.4, −1.4), and B − A = (1, 0), C0 − A = (0, 1) both have
  // D·(T − A) < 0: both rise, so A alone is the support. (About B instead, D = (−2.4, −1.4) and A − B =
  // (−1, 0) gives +2.4: A would be driven into the wall.)
  const Body body = test_body();
  const Vec3 com(0.6, 0.6, 1);
  const SwitchState impact{body, Quat::Identity(), com, Vec3::Zero(), Vec3(-2, -2, -1), 1.0, 1e-9, 1e-6};
  const WallVertex current = touch(5, 0, 1, 0, com);
  const std::vector<WallVertex> touching = {current, touch(6, 0, 0, -2e-12, com),
                                            touch(7, 1, 0, -1e-12, com)};
  const SupportChoice c = choose_smooth(impact, touching, current, Vec2(com.x(), com.y()));
  EXPECT_EQ(c.vertex, 6);
  EXPECT_FALSE(c.support.line);
  Support about_b{touching[2].world, touching[2].body, false, Vec3::UnitX()};
  EXPECT_FALSE(others_separate(impact, touching, about_b));
  // Two new touches at exactly the same height: the first listed is "the lowest" (the engine lists touching
  // points by vertex index, so the choice is deterministic).
  const std::vector<WallVertex> tie = {current, touch(6, 0, 0, -2e-12, com), touch(7, 1, 0, -2e-12, com)};
  const SupportChoice first = choose_smooth(impact, tie, current, Vec2(com.x(), com.y()));
  EXPECT_EQ(first.vertex, 6);
  EXPECT_FALSE(first.support.line);  // A alone (B would fail, and the fallback hinges on the edge AB)
  // Alone on the wall, the current support stays the pivot.
  const SupportChoice alone = choose_smooth(impact, {current}, current, Vec2(com.x(), com.y()));
  EXPECT_EQ(alone.vertex, 5);
  EXPECT_FALSE(alone.support.line);
}

}  // namespace
}  // namespace repose::sim
