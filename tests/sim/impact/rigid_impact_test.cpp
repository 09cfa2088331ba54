// The impact law of a rigid body on the wall (Stronge's energetic restitution, Coulomb friction), against
// closed forms written out in the test. Internal header: the engine's building block, tested on its own.
//
// Planar reference (x–z plane, rotation about y): for a body of mass m and moment I about y struck at the
// point r = (r_x, 0, r_z) from its centre of mass, the contact point's velocity changes by K·P with
//   K_xx = 1/m + r_z²/I,  K_zz = 1/m + r_x²/I,  K_xz = −r_x·r_z/I
// (from Δv = P/m, Δω = (r × P)_y/I). Along the normal impulse p the tangential impulse grows at −μ·s (sliding
// in direction s = ±1) or at −K_xz/K_xx (stuck, possible while |K_xz/K_xx| ≤ μ; otherwise the point slides
// again, in the direction of K_xz). Every rate is constant between events, so the velocities are linear and
// the normal impulse's work quadratic in p: the reference below walks the segments in closed form.
#include "../../../src/sim/impact/rigid_impact.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace repose::sim {
namespace {

struct Planar {
  double m, I, rx, rz, vx, vz, wy, e, mu;
};

struct PlanarResult {
  double Px = 0, Pz = 0, ux = 0, uz = 0;
  bool stuck = false, reversed = false;
};

PlanarResult planar_reference(const Planar& c) {
  const double kxx = 1 / c.m + c.rz * c.rz / c.I, kzz = 1 / c.m + c.rx * c.rx / c.I, kxz = -c.rx * c.rz / c.I;
  PlanarResult r;
  r.ux = c.vx + c.wy * c.rz;  // (ω × r)_x = ω_y·r_z
  r.uz = c.vz - c.wy * c.rx;  // (ω × r)_z = −ω_y·r_x
  double work = 0, target = 0;
  bool restitution = false;
  for (int segment = 0; segment < 10; ++segment) {
    double rate_t;  // dP_x/dp
    if (r.stuck) {
      rate_t = -kxz / kxx;
    } else {
      const double s = r.ux > 0 ? 1 : r.ux < 0 ? -1 : (kxz > 0 ? 1 : -1);
      rate_t = -c.mu * s;
    }
    const double dux = kxz + kxx * rate_t, duz = kzz + kxz * rate_t;
    // Candidate ends of this segment.
    double dp = INFINITY;
    int event = 0;
    if (!r.stuck && r.ux * dux < 0) {
      dp = -r.ux / dux;
      event = 1;
    }
    // Friction can make the normal velocity fall while the point slides (a jam, duz < 0): no compression end.
    if (!restitution && duz > 0 && -r.uz / duz < dp) {
      dp = -r.uz / duz;
      event = 2;
    }
    if (restitution) {
      const double need = target - work;  // uz·Δ + ½·duz·Δ² = need, the smaller root
      const double disc = r.uz * r.uz + 2 * duz * need;
      // Where the normal velocity falls to zero first (duz < 0), restitution ends there, short of its target.
      const double d = disc >= 0 ? 2 * need / (r.uz + std::sqrt(disc)) : -r.uz / duz;
      if (d < dp) {
        dp = d;
        event = 3;
      }
    }
    work += r.uz * dp + 0.5 * duz * dp * dp;
    r.Px += rate_t * dp;
    r.Pz += dp;
    r.ux += dux * dp;
    r.uz += duz * dp;
    if (event == 1) {
      r.ux = 0;
      if (std::abs(kxz / kxx) <= c.mu)
        r.stuck = true;
      else
        r.reversed = true;
    } else if (event == 2) {
      r.uz = 0;
      restitution = true;
      target = (1 - c.e * c.e) * work;
      if (c.e == 0) return r;
    } else if (event == 3) {
      return r;
    }
  }
  ADD_FAILURE() << "the reference did not end";
  return r;
}

ImpactOutcome collide_planar(const Planar& c) {
  const Mat3 inertia = Vec3(c.I, c.I, c.I).asDiagonal();  // only I_yy matters in a planar motion
  return collide(c.m, inertia, Vec3(c.rx, 0, c.rz), {Vec3(c.vx, 0, c.vz), Vec3(0, c.wy, 0)}, {c.e, c.mu});
}

// A slender rod (m = 1, length 1, I = 1/12) at 45° striking with its lower end: K_xz/K_xx = −0.6.
Planar rod(double vx, double mu, double e) {
  const double half = 0.5 / std::sqrt(2.0);
  return {1.0, 1.0 / 12, -half, -half, vx, -1.0, 0.0, e, mu};
}

void expect_matches_reference(const Planar& c, const PlanarResult& ref) {
  const ImpactOutcome out = collide_planar(c);
  // Every segment is linear, so the engine's integration is exact up to round-off: 1e-12 of the speeds.
  const double tol = 1e-12;
  EXPECT_NEAR(out.impulse.x(), ref.Px, tol);
  EXPECT_NEAR(out.impulse.z(), ref.Pz, tol);
  EXPECT_NEAR(out.speed_after.x(), ref.ux, tol);
  EXPECT_NEAR(out.speed_after.z(), ref.uz, tol);
  EXPECT_NEAR(out.after.velocity.x(), c.vx + ref.Px / c.m, tol);
  EXPECT_NEAR(out.after.velocity.z(), c.vz + ref.Pz / c.m, tol);
  EXPECT_NEAR(out.after.omega.y(), c.wy + (c.rz * ref.Px - c.rx * ref.Pz) / c.I, tol);
  EXPECT_EQ(out.stick, ref.stuck);
  EXPECT_FALSE(out.fallback);
}

TEST(RigidImpact, RodSlidingThroughoutMatchesTheClosedForm) {
  const Planar c = rod(2.0, 0.1, 0.6);
  const PlanarResult ref = planar_reference(c);
  ASSERT_FALSE(ref.stuck);
  ASSERT_GT(ref.ux, 0);  // still sliding forward at the end
  expect_matches_reference(c, ref);
}

TEST(RigidImpact, RodThatStopsSlidingSticksWhenFrictionSuffices) {
  const Planar c = rod(0.3, 0.8, 0.6);  // 0.8 ≥ 0.6: it sticks
  const PlanarResult ref = planar_reference(c);
  ASSERT_TRUE(ref.stuck);
  expect_matches_reference(c, ref);
}

TEST(RigidImpact, RodThatStopsSlidingReversesWhenFrictionDoesNot) {
  const Planar c = rod(0.2, 0.3, 0.6);  // 0.3 < 0.6: it slides back
  const PlanarResult ref = planar_reference(c);
  ASSERT_TRUE(ref.reversed);
  ASSERT_LT(ref.ux, 0);
  expect_matches_reference(c, ref);
}

TEST(RigidImpact, SpinningRodStrikingBackwardsMatchesTheClosedForm) {
  Planar c = rod(-0.5, 0.3, 0.9);
  c.wy = 2.0;
  expect_matches_reference(c, planar_reference(c));
}

// A grazing impact with friction above K_nn/|K_nt| (5/3 for this rod): sliding backwards, friction drives the
// point into the wall (du_n/dp = 2.5 − 1.5·μ < 0), so compression ends only after the slip stops, an impulse
// ~|u_t|/(μ·K_tt) that is 1000 times the frictionless compression impulse. The law integrated that far
// once fell back to the frictionless law (keeping all the energy) after its step limit; it must follow the
// closed form.
TEST(RigidImpact, GrazingImpactWithLargeFrictionStopsItsSlipBeforeCompressing) {
  const double half = 0.5 / std::sqrt(2.0);
  for (const double vz : {-0.001, -0.01}) {
    const Planar c{1.0, 1.0 / 12, -half, -half, -2.0, vz, 0.0, 0.5, 2.0};
    const PlanarResult ref = planar_reference(c);
    EXPECT_TRUE(ref.stuck) << vz;  // μ = 2 ≥ |K_xz/K_xx| = 0.6
    expect_matches_reference(c, ref);
  }
}

TEST(RigidImpact, FrictionlessImpactReversesTheNormalSpeedTimesE) {
  // μ = 0: the impulse is normal, P = (1 + E)·(−u_n)/K_nn with K_nn = 1/m + (r × n)·I⁻¹(r × n), and the
  // point's normal speed after is −E times before (Stronge's and Newton's coefficients agree without
  // friction). A general body: anisotropic inertia, point off every axis, spin.
  const double m = 2.5;
  const Mat3 inertia = (Mat3() << 0.9, 0.1, -0.05, 0.1, 0.7, 0.02, -0.05, 0.02, 0.4).finished();
  const Vec3 r(0.3, -0.2, -0.45), v(0.4, -0.1, -2.0), w(1.0, -0.5, 0.3);
  const double e = 0.7;
  const ImpactOutcome out = collide(m, inertia, r, {v, w}, {e, 0.0});
  const Vec3 arm = r.cross(Vec3::UnitZ());
  const double knn = 1 / m + arm.dot(inertia.inverse() * arm);
  const double un = (v + w.cross(r)).z();
  EXPECT_NEAR(out.impulse.z(), (1 + e) * -un / knn, 1e-12);
  EXPECT_NEAR(out.impulse.head<2>().norm(), 0, 1e-15);
  EXPECT_NEAR(out.speed_after.z(), -e * un, 1e-12);
  // E = 1 without friction conserves the kinetic energy.
  const ImpactOutcome elastic = collide(m, inertia, r, {v, w}, {1.0, 0.0});
  EXPECT_NEAR(kinetic_energy(m, inertia, elastic.after), kinetic_energy(m, inertia, {v, w}), 1e-12);
}

TEST(RigidImpact, ARestitutionWhoseSquareUnderflowsEndsLikeAPlasticImpact) {
  // E = 1e-200: E² is 0 in double precision, so restitution has no work to do and must end at once (not run
  // into the integration's step bound and the frictionless fallback).
  const Planar c = rod(2.0, 0.1, 0.0);
  Planar tiny = c;
  tiny.e = 1e-200;
  const ImpactOutcome plastic = collide_planar(c), almost = collide_planar(tiny);
  EXPECT_FALSE(almost.fallback);
  EXPECT_NEAR((almost.impulse - plastic.impulse).norm(), 0, 1e-12);
}

TEST(RigidImpact, APointLeavingTheWallIsNotStruck) {
  const Mat3 inertia = Mat3::Identity();
  const ImpactOutcome out =
      collide(1.0, inertia, Vec3(0, 0, -1), {Vec3(1, 0, 0.5), Vec3::Zero()}, {0.5, 0.3});
  EXPECT_EQ(out.impulse, Vec3::Zero());
  EXPECT_EQ(out.after.velocity, Vec3(1, 0, 0.5));
}

// Grazing impacts (u_n 1e-4 to 1e-2 of u_t) with μ in [0.5, 2]: jams among them, whose slip must stop before
// compression can end. The law once met its step bound in about one such impact in 3,000 and fell back to
// the frictionless law, keeping the energy friction should have taken. None may fall back; none creates
// energy or ends approaching.
TEST(RigidImpact, GrazingImpactsNeverFallBackToTheFrictionlessLaw) {
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> u(-1, 1), unit(0, 1);
  int jams = 0;
  for (int i = 0; i < 10000; ++i) {
    const Vec3 moments(0.05 + unit(rng), 0.05 + unit(rng), 0.05 + unit(rng));
    const Mat3 R = Quat(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
    const Mat3 inertia = R * moments.asDiagonal() * R.transpose();
    const double m = 0.5 + unit(rng), e = unit(rng), mu = 0.5 + 1.5 * unit(rng);
    const Vec3 r(u(rng), u(rng), -0.05 - unit(rng));
    const Vec3 omega = Vec3(u(rng), u(rng), u(rng));
    const Vec2 slide = Vec2(u(rng), u(rng)).normalized() * (0.5 + 2 * unit(rng));
    const double un = -slide.norm() * std::pow(10.0, -4 + 2 * unit(rng));
    // The centre of mass's velocity that gives the contact point the velocity (slide, un).
    const Vec3 point(slide.x(), slide.y(), un);
    const Motion before{point - omega.cross(r), omega};
    const Mat3 rx = (Mat3() << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0).finished();
    const Mat3 K = Mat3::Identity() / m - rx * inertia.inverse() * rx;
    if (K(2, 2) - mu * K.block<1, 2>(2, 0).dot(slide.normalized()) <= 0) ++jams;
    const ImpactOutcome out = collide(m, inertia, r, before, {e, mu});
    ASSERT_FALSE(out.fallback) << "impact " << i;
    const double k0 = kinetic_energy(m, inertia, before), k1 = kinetic_energy(m, inertia, out.after);
    ASSERT_LE(k1, k0 * (1 + 1e-12)) << "impact " << i;
    ASSERT_GE(out.speed_after.z(), -1e-12 * out.speed_before.norm()) << "impact " << i;
  }
  EXPECT_GT(jams, 100);
}

TEST(RigidImpact, NoImpactCreatesEnergyOrLeavesThePointApproaching) {
  // 10,000 random impacts: random bodies (a box's principal moments, turned at random), points, velocities,
  // spins, E in [0, 1] and μ in [0, 2] or infinite. The law's energy balance is exact (Stronge); the
  // integration's error is round-off (1e-12 of the energy), far below any energy an error in the law (a sign
  // of the friction, E instead of E²) would create.
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(-1, 1), size(0.2, 2), unit(0, 1);
  int sliding_at_end = 0, stuck = 0;
  for (int i = 0; i < 10000; ++i) {
    const double a = size(rng), b = size(rng), c = size(rng), m = size(rng);
    const Vec3 moments(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12);
    const Mat3 R = Quat(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
    const Mat3 inertia = R * moments.asDiagonal() * R.transpose();
    Vec3 r(u(rng), u(rng), -std::abs(u(rng)) - 0.05);
    Motion before{Vec3(u(rng), u(rng), u(rng)) * 2, Vec3(u(rng), u(rng), u(rng)) * 4};
    if ((before.velocity + before.omega.cross(r)).z() >= 0) before.velocity.z() -= 3;  // approaching
    const double e = unit(rng), mu = i % 10 == 0 ? INFINITY : 2 * unit(rng);
    const ImpactOutcome out = collide(m, inertia, r, before, {e, mu});
    const double k0 = kinetic_energy(m, inertia, before), k1 = kinetic_energy(m, inertia, out.after);
    ASSERT_LE(k1, k0 * (1 + 1e-12)) << "impact " << i << " e=" << e << " mu=" << mu;
    ASSERT_GE(out.speed_after.z(), -1e-12 * out.speed_before.norm()) << "impact " << i;
    // Coulomb: the tangential impulse is within the friction cone.
    if (std::isfinite(mu)) {
      ASSERT_LE(out.impulse.head<2>().norm(), mu * out.impulse.z() * (1 + 1e-9) + 1e-15);
    }
    ASSERT_FALSE(out.fallback) << "impact " << i;
    (out.stick ? stuck : sliding_at_end)++;
  }
  EXPECT_GT(stuck, 1000);  // both regimes are exercised
  EXPECT_GT(sliding_at_end, 1000);
}

TEST(RigidImpact, ImpulseCentreOfAFlatFaceLandingSquarelyIsBelowTheCentreOfMass) {
  // A unit cube (m = 1, I = 1/6) landing flat without spin: its four bottom corners at once, the impulses'
  // centre straight below the centre of mass (by symmetry), so the impact there leaves no rotation.
  const Mat3 inertia = Mat3::Identity() / 6;
  std::vector<Vec3> corners;
  for (double x : {-0.5, 0.5})
    for (double y : {-0.5, 0.5}) corners.emplace_back(x, y, -0.5);
  const Motion before{Vec3(0, 0, -3), Vec3::Zero()};
  const auto centre = impulse_centre(1.0, inertia, corners, before);
  ASSERT_TRUE(centre.has_value());
  EXPECT_NEAR(centre->x(), 0, 1e-12);
  EXPECT_NEAR(centre->y(), 0, 1e-12);
  EXPECT_NEAR(centre->z(), -0.5, 1e-12);
  // Landing on one edge with a spin that lifts one corner of it: that corner takes no impulse.
  const Motion tipping{Vec3(0, 0, -1), Vec3(4, 0, 0)};
  const std::vector<Vec3> edge = {Vec3(0.5, -0.5, -0.5), Vec3(0.5, 0.5, -0.5)};
  const auto c2 = impulse_centre(1.0, inertia, edge, tipping);
  ASSERT_TRUE(c2.has_value());
  // (ω × r)_z = ω_x·r_y: +2 at y = 0.5 (rising: −1 + 2 > 0), −2 at y = −0.5: only that corner is struck.
  EXPECT_NEAR(c2->y(), -0.5, 1e-12);
  EXPECT_FALSE(impulse_centre(1.0, inertia, corners, {Vec3(0, 0, 1), Vec3::Zero()}).has_value());
}

}  // namespace
}  // namespace repose::sim
