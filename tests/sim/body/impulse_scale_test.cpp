// The scale that keeps changed impulses from adding energy (body/kinematics.hpp: energy_minimising_scale),
// against closed forms on a body whose kinetic energy along the scale is a known parabola.
#include <gtest/gtest.h>

#include "../../../src/sim/body/kinematics.hpp"

namespace repose::sim {
namespace {

// A body of mass 2 and world inertia diag(1, 2, 3), its point r = (0.5, 0, -0.5) moving with u0. The
// least-norm impulse that stops the point is P* = −K⁻¹·u0 (K the point's Delassus block, written here from
// its definition 1/m − [r]× I⁻¹ [r]×); along P = k·P* the energy is K0 − k·s·c + ½·k²·s²·c (c = u0ᵀK⁻¹u0):
// above K0 at s = 1 for an overshoot k > 2, least at s = 1/k, the exact stop; for k < 2, P takes energy: s
// = 1.
TEST(ImpulseScale, AnOvershootingImpulseIsScaledBackToTheExactStop) {
  const double mass = 2;
  const Mat3 inertia = Vec3(1, 2, 3).asDiagonal();
  const Vec3 r(0.5, 0, -0.5);
  const Motion m{Vec3(0.3, -0.2, -1.0), Vec3(0.4, 0.1, -0.2)};
  Mat3 skew;
  skew << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  const Mat3 K = Mat3::Identity() / mass - skew * inertia.inverse() * skew;
  const Vec3 stop = -K.inverse() * point_velocity(m, r);
  for (const double k : {1.0, 1.5, 3.0, 7.0}) {  // (k = 2 leaves the energy as it was: a tie)
    const double s = energy_minimising_scale(mass, inertia, m, {r}, {k * stop});
    const double expected = k > 2 ? 1 / k : 1.0;
    // round-off of a 3×3 inverse and of kinetic energies of order 1: 1e-12
    EXPECT_NEAR(s, expected, 1e-12) << "overshoot " << k;
    if (k > 2) {
      const Motion after = apply_impulses(mass, inertia.inverse(), m, {r}, {k * stop}, s);
      EXPECT_NEAR(point_velocity(after, r).norm(), 0, 1e-12) << "overshoot " << k;
    }
  }
}

// Impulses that push the points on (P·u > 0) only add energy: no scale but 0 takes none.
TEST(ImpulseScale, ImpulsesAlongTheVelocitiesAreDroppedAndSeveralPointsCount) {
  const double mass = 1;
  const Mat3 inertia = Mat3::Identity();
  const Motion m{Vec3(1, 0, 0), Vec3::Zero()};
  EXPECT_EQ(energy_minimising_scale(mass, inertia, m, {Vec3(0, 0, -1)}, {Vec3(0.5, 0, 0)}), 0.0);
  // Two points on equal and opposite arms (their moments cancel), each taking 1.5·m·v: together three times
  // the stop, the body sent back at twice its speed; least energy at s = 1/3, where it stops. Each point
  // counts: the second's impulse alone would not overshoot.
  const std::vector<Vec3> arms{Vec3(0, 1, 0), Vec3(0, -1, 0)};
  const std::vector<Vec3> impulses{Vec3(-1.5, 0, 0), Vec3(-1.5, 0, 0)};
  EXPECT_NEAR(energy_minimising_scale(mass, inertia, m, arms, impulses), 1.0 / 3, 1e-15);
}

}  // namespace
}  // namespace repose::sim
