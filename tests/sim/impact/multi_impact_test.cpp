// Several points striking the wall at once with Coulomb friction at each (src/sim/impact/multi_impact.hpp),
// against closed forms worked out here for a unit cube (m = 1, edge 1, I = 1/6 about every axis through its
// centre) landing on its bottom face's four corners (arms (±1/2, ±1/2, −1/2)).
#include "../../../src/sim/impact/multi_impact.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace repose::sim {
namespace {

const Mat3 kCubeInertia = Mat3::Identity() / 6;

// An asymmetric body's inertia about its centre of mass (principal moments 0.05 to 1.05), turned at random.
Mat3 random_inertia(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1), unit(0, 1);
  const Vec3 moments(0.05 + unit(rng), 0.05 + unit(rng), 0.05 + unit(rng));
  const Mat3 R = Quat(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
  return R * moments.asDiagonal() * R.transpose();
}

std::vector<Vec3> bottom_corners() {
  std::vector<Vec3> corners;
  for (double x : {-0.5, 0.5})
    for (double y : {-0.5, 0.5}) corners.emplace_back(x, y, -0.5);
  return corners;
}

// A cube landing flat (v_z = −1) while spinning about z at ω: by symmetry each corner takes λ = m·v/4 and,
// while it slides (its slip ω·r along the circle of radius r = √2/2), a friction impulse μ·λ against it. The
// torsional impulse 4·μ·(m·v/4)·r = μ·m·v·r takes Δω = μ·m·v·r/I = 6·μ·v·r = 3√2·μ·v off the spin, or stops
// it. The impulses' centre (the old rule) gave no torsion at all: ω stayed 4.
TEST(MultiImpact, SpinningFaceLandingFlatLosesSpinToTorsionalFriction) {
  for (const double mu : {0.1, 0.5, 2.0}) {
    const Motion before{Vec3(0, 0, -1), Vec3(0, 0, 4)};
    const MultiImpactOutcome out = collide_points(1.0, kCubeInertia, bottom_corners(), before, {0.0, mu});
    ASSERT_TRUE(out.converged);
    const double expected = std::max(0.0, 4 - 3 * std::sqrt(2.0) * mu);
    // Every quantity is the fixed point of a linear map per block: round-off, 1e-12 of the speeds.
    EXPECT_NEAR(out.after.omega.z(), expected, 1e-12) << "mu " << mu;
    EXPECT_NEAR(out.after.velocity.norm(), 0, 1e-12) << "mu " << mu;
    EXPECT_NEAR(out.after.omega.head<2>().norm(), 0, 1e-12) << "mu " << mu;
    for (const Vec3& u : out.speed_after) EXPECT_NEAR(u.z(), 0, 1e-12);
  }
}

// A cube landing flat while sliding, v = (1, 0, −1), E = 0: all four corners slide the same way, so the
// friction impulse is μ·m·v_n = μ against the slip and v_x falls to 1 − μ. Its moment about the centre of
// mass (μ·1/2 about y) is taken up by more normal impulse at the front corners than at the back, which stay
// pressed while μ·h ≤ b/2 (here μ ≤ 1): no pitch, ω = 0. The impulses' centre with the one-point law pitched
// the cube (ω_y 1.05 at μ = 0.3).
TEST(MultiImpact, FaceLandingWhileSlidingDoesNotPitch) {
  for (const double mu : {0.3, 0.8}) {
    const Motion before{Vec3(1, 0, -1), Vec3::Zero()};
    const MultiImpactOutcome out = collide_points(1.0, kCubeInertia, bottom_corners(), before, {0.0, mu});
    ASSERT_TRUE(out.converged);
    EXPECT_NEAR(out.after.velocity.x(), 1 - mu, 1e-12) << mu;
    EXPECT_NEAR(out.after.velocity.y(), 0, 1e-12) << mu;
    EXPECT_NEAR(out.after.velocity.z(), 0, 1e-12) << mu;
    EXPECT_NEAR(out.after.omega.norm(), 0, 1e-12) << mu;
    // The normal impulses: 1/2 ± μ/2 on the front and back pairs (moment balance about y: the friction's
    // μ·1/2 against (front − back)·1/2). How each pair shares its part is not determined (four corners, three
    // constraints), only the sums.
    double front = 0, back = 0;
    for (std::size_t i = 0; i < 4; ++i) (bottom_corners()[i].x() > 0 ? front : back) += out.impulses[i].z();
    EXPECT_NEAR(front, 0.5 + mu / 2, 1e-12) << mu;
    EXPECT_NEAR(back, 0.5 - mu / 2, 1e-12) << mu;
  }
}

// Issue 48: friction's impulse is μ times the normal impulse, not μ: the same plastic landing with a normal
// impulse that is not 1 (mass m, landing at v_z = −w: the normal impulse is m·w and friction takes μ·w off
// v_x, at most all of it). A cone taken as μ alone (a planted bug) passed the test above, whose impulse is 1.
TEST(MultiImpact, SlidingLandingLosesMuTimesTheNormalImpulse) {
  for (const double mass : {0.5, 3.0})
    for (const double w : {0.4, 2.5})
      for (const double mu : {0.1, 0.3}) {
        const Motion before{Vec3(1, 0, -w), Vec3::Zero()};
        const MultiImpactOutcome out =
            collide_points(mass, mass * kCubeInertia, bottom_corners(), before, {0.0, mu});
        ASSERT_TRUE(out.converged);
        EXPECT_NEAR(out.after.velocity.x(), std::max(0.0, 1 - mu * w), 1e-12)
            << mass << " " << w << " " << mu;
        EXPECT_NEAR(out.after.velocity.z(), 0, 1e-12);
        double normal = 0, tangential = 0;
        for (const Vec3& p : out.impulses) normal += p.z(), tangential += p.x();
        EXPECT_NEAR(normal, mass * w, 1e-12 * mass * w);
        EXPECT_NEAR(-tangential, mass * std::min(1.0, mu * w), 1e-12 * mass);
      }
}

// The same landing with E = 0.5: restitution gives each corner half its compression normal impulse (0.5 in
// all, the front pair 0.325, the back 0.175) with friction on the cone against the slip still left (0.7):
// μ·0.5 = 0.15 more off v_x, and the pair's imbalance (0.325 − 0.175)·1/2 = 0.075 again balances the
// friction's moment 0.15·1/2: v = (0.55, 0, 0.5), no rotation.
TEST(MultiImpact, RestitutionWithFrictionKeepsSlidingWithoutPitch) {
  const Motion before{Vec3(1, 0, -1), Vec3::Zero()};
  const MultiImpactOutcome out = collide_points(1.0, kCubeInertia, bottom_corners(), before, {0.5, 0.3});
  ASSERT_TRUE(out.converged);
  EXPECT_NEAR(out.after.velocity.x(), 0.55, 1e-12);
  EXPECT_NEAR(out.after.velocity.y(), 0, 1e-12);
  EXPECT_NEAR(out.after.velocity.z(), 0.5, 1e-12);
  EXPECT_NEAR(out.after.omega.norm(), 0, 1e-12);
}

// Friction large enough to stop the slide within the impact: the cube ends at rest (sticking at all four).
TEST(MultiImpact, FaceLandingWithEnoughFrictionSticks) {
  const Motion before{Vec3(0.5, 0.2, -1), Vec3(0, 0, 0.3)};
  const MultiImpactOutcome out = collide_points(1.0, kCubeInertia, bottom_corners(), before, {0.0, 1.5});
  ASSERT_TRUE(out.converged);
  EXPECT_NEAR(out.after.velocity.norm(), 0, 1e-12);
  EXPECT_NEAR(out.after.omega.norm(), 0, 1e-12);
}

// Frictionless: a flat landing keeps its horizontal velocity and spin (no tangential impulse anywhere), and
// Poisson's E at each corner sends the cube up at E·v.
TEST(MultiImpact, FrictionlessFlatLandingReboundsStraightUpAtE) {
  const Motion before{Vec3(0.7, -0.3, -2), Vec3(0, 0, 1.5)};
  const MultiImpactOutcome out = collide_points(1.0, kCubeInertia, bottom_corners(), before, {0.5, 0.0});
  EXPECT_NEAR(out.after.velocity.x(), 0.7, 1e-12);
  EXPECT_NEAR(out.after.velocity.y(), -0.3, 1e-12);
  EXPECT_NEAR(out.after.velocity.z(), 1.0, 1e-12);
  EXPECT_NEAR(out.after.omega.z(), 1.5, 1e-12);
  EXPECT_NEAR(out.after.omega.head<2>().norm(), 0, 1e-12);
}

// Coulomb's law in restitution: the restitution impulse (the impact's with E, less the same impact's with
// E = 0, whose compression is identical) lies on the cone against the point's final slip, P_t = −μ·P_n·û,
// wherever the point still slides at the end. One point of an asymmetric body (anisotropic W_tt, so a wrong
// direction rule shows), at random.
TEST(MultiImpact, RestitutionFrictionOpposesTheFinalSlip) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), unit(0, 1);
  int checked = 0;
  for (int k = 0; k < 500 && checked < 100; ++k) {
    const Mat3 inertia = random_inertia(rng);
    const std::vector<Vec3> arm = {Vec3(u(rng), u(rng), -0.1 - unit(rng))};
    const Motion before{Vec3(3 * u(rng), 3 * u(rng), -1 - unit(rng)), Vec3(u(rng), u(rng), u(rng))};
    const double mu = 0.05 + 0.3 * unit(rng), e = 0.3 + 0.6 * unit(rng);
    const MultiImpactOutcome plastic = collide_points(1.0, inertia, arm, before, {0.0, mu});
    const MultiImpactOutcome full = collide_points(1.0, inertia, arm, before, {e, mu});
    const Vec2 slip = full.speed_after[0].head<2>();
    if (slip.norm() < 0.1) continue;  // stopped, or nearly: the direction is not defined
    const Vec3 restitution = full.impulses[0] - plastic.impulses[0];
    if (!(restitution.z() > 1e-6)) continue;
    ++checked;
    const Vec2 expected = -mu * restitution.z() * slip.normalized();
    EXPECT_NEAR((restitution.head<2>() - expected).norm(), 0, 1e-10 * (1 + restitution.norm()))
        << "impact " << k;
  }
  EXPECT_GE(checked, 50);
}

// Random bodies landing on random sets of 2 to 8 points (a face's polygon at random heights of the arms):
// no impact creates kinetic energy, none leaves a struck point approaching after a plastic impact, and every
// impulse is in its friction cone.
TEST(MultiImpact, NoMultiPointImpactCreatesEnergy) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1, 1), unit(0, 1);
  for (int k = 0; k < 2000; ++k) {
    const Mat3 inertia = random_inertia(rng);
    const double m = 0.3 + unit(rng), e = k % 2 ? 0.0 : unit(rng), mu = 2 * unit(rng);
    const double depth = -0.1 - unit(rng);
    std::vector<Vec3> arms(2 + k % 7);
    for (Vec3& a : arms) a = Vec3(u(rng), u(rng), depth);
    const Motion before{Vec3(2 * u(rng), 2 * u(rng), -0.2 - 2 * unit(rng)), Vec3(u(rng), u(rng), u(rng)) * 3};
    const MultiImpactOutcome out = collide_points(m, inertia, arms, before, {e, mu});
    const double k0 = kinetic_energy(m, inertia, before), k1 = kinetic_energy(m, inertia, out.after);
    ASSERT_LE(k1, k0 * (1 + 1e-12)) << "impact " << k;
    for (std::size_t i = 0; i < arms.size(); ++i) {
      ASSERT_GE(out.impulses[i].z(), -1e-12) << "impact " << k;
      ASSERT_LE(out.impulses[i].head<2>().norm(), mu * out.impulses[i].z() * (1 + 1e-9) + 1e-14)
          << "impact " << k;
      if (e == 0 && out.converged) {
        ASSERT_GE(out.speed_after[i].z(), -1e-9) << "impact " << k << " point " << i;
      }
    }
  }
}

// A body rolling across an edge or a rim (a polygonal cylinder's, a grain's): the points on the wall nearly
// at rest while the body turns, their speeds 1e-3 to 1e-12 of its own. Plastic, each must end as Moreau's
// impact with Coulomb friction has it: no point approaching, none pressed while leaving (λ·u_n = 0), each
// impulse in its cone and, where the point slides after, on the cone's edge against the slip, and so no
// kinetic energy gained. Tolerances: 1e-9 of the body's speed scale (the points' values are differences of
// terms of that size; Gauss–Seidel's round-off floor is 64 ulps of them). Found as an energy rise of
// 2.8e-8·m·g·L in the 10,000-toss property sweep (a 64-sided cylinder, μ 0.98): Gauss–Seidel missed its
// 1e-14 tolerance by round-off and Lemke's method, on the edge's singular Delassus matrix, returned
// impulses pressing a leaving point.
TEST(MultiImpact, PointsNearlyAtRestOnATurningBodyEndAsMoreausImpact) {
  std::mt19937_64 rng(34);
  std::uniform_real_distribution<double> u(-1, 1), unit(0, 1);
  for (int k = 0; k < 2000; ++k) {
    const Mat3 inertia = random_inertia(rng);
    const double m = 0.3 + unit(rng), mu = 0.2 + 1.8 * unit(rng);
    const double depth = -0.1 - unit(rng);
    // Two to four points of a short edge or a small facet near the first one.
    std::vector<Vec3> arms(2 + k % 3);
    arms[0] = Vec3(u(rng), u(rng), depth);
    for (std::size_t i = 1; i < arms.size(); ++i) arms[i] = arms[0] + 0.2 * Vec3(u(rng), u(rng), 0);
    // Turning about the first point, which moves at 10^−(3…12) of the body's speed, down and along.
    const Vec3 omega = 3 * Vec3(u(rng), u(rng), 0.1 * u(rng));
    const double tiny = std::pow(10.0, -3 - 9 * unit(rng));
    const Vec3 drift(tiny * u(rng), tiny * u(rng), -tiny * unit(rng));
    const Motion before{drift - omega.cross(arms[0]), omega};
    double speed = before.velocity.norm();
    for (const Vec3& a : arms) speed = std::max(speed, (before.velocity + omega.cross(a)).norm());
    bool approaching = false;
    for (const Vec3& a : arms) approaching = approaching || (before.velocity + omega.cross(a)).z() < 0;
    if (!approaching) continue;
    const MultiImpactOutcome out = collide_points(m, inertia, arms, before, {0.0, mu});
    const double k0 = kinetic_energy(m, inertia, before), k1 = kinetic_energy(m, inertia, out.after);
    ASSERT_LE(k1, k0 * (1 + 1e-12)) << "impact " << k;
    if (!out.converged) continue;  // the frictionless fallback: checked for energy only
    const double tol = 1e-9 * speed;
    for (std::size_t i = 0; i < arms.size(); ++i) {
      const Vec3& P = out.impulses[i];
      const Vec3& after = out.speed_after[i];
      ASSERT_GE(after.z(), -tol) << "impact " << k << " point " << i;
      ASSERT_GE(P.z(), -1e-14) << "impact " << k << " point " << i;
      if (P.z() > 1e-12 * m * speed) {
        ASSERT_LE(after.z(), tol) << "impact " << k << " point " << i << ": pressed while leaving";
      }
      ASSERT_LE(P.head<2>().norm(), mu * P.z() * (1 + 1e-9) + 1e-14) << "impact " << k;
      if (after.head<2>().norm() > 1e-6 * speed && P.z() > 1e-9 * m * speed) {
        const Vec2 expected = -mu * P.z() * after.head<2>().normalized();
        ASSERT_NEAR((P.head<2>() - expected).norm(), 0, 1e-6 * mu * P.z())
            << "impact " << k << " point " << i;
      }
    }
  }
}

// An impact whose data are not finite (a NaN velocity: the contact problem's answer is not finite either) is
// flagged not converged, never passed off as a solution.
TEST(MultiImpact, AnUnsolvedImpactIsFlagged) {
  for (const double mu : {0.0, 0.5}) {
    const Motion before{Vec3(NAN, 0, -1), Vec3::Zero()};
    const MultiImpactOutcome out = collide_points(1.0, kCubeInertia, bottom_corners(), before, {0.0, mu});
    EXPECT_FALSE(out.converged) << "μ = " << mu;
  }
}

}  // namespace
}  // namespace repose::sim
