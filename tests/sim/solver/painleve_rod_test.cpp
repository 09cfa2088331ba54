// Painlevé's rod (Painlevé 1895; Génot & Brogliato 1999): the normal compliance of a sliding point under its
// own friction, W_nn − μ·W_nt·ŝ (contact_problem.hpp, sliding_compliance), against the closed form of a
// uniform rod. The frictional contact phase decides Painlevé's case and the dynamic jam by it
// (tolerances.hpp, kJamCompliance).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../../../src/sim/solver/contact_forces.hpp"
#include "../../../src/sim/solver/contact_problem.hpp"

namespace repose::sim {
namespace {

// A uniform rod of mass m and half-length l in the xz-plane at angle θ to the wall, its lower end on the
// wall and the centre of mass at +x of it, the end sliding towards −x (away from under the centre of mass):
// a normal force N at the end with friction μ·N along +x gives the end a normal acceleration
// (N/m)·(1 + 3·cos²θ − 3·μ·sinθ·cosθ) (the moment about the centre of mass, I = m·l²/3), which vanishes at
// μ = (1 + 3·cos²θ)/(3·sinθ·cosθ), whose least value is 4/3 at tan θ = 2.
double rod_compliance(double mass, double theta, double mu) {
  const double c = std::cos(theta), s = std::sin(theta);
  return (1 + 3 * c * c - 3 * mu * s * c) / mass;
}

TEST(PainleveRod, SlidingComplianceIsTheClosedForm) {
  const double m = 2.5, l = 0.7;
  for (const double theta : {0.2, 0.6, std::atan(2.0), 1.2, 1.45}) {
    // Inertia about the centre of mass: m·l²/3 about the axes normal to the rod (y among them), and a thin
    // rod's small axial one, in the world frame (the rod's axis along (cos θ, 0, sin θ)).
    const Vec3 axis(std::cos(theta), 0, std::sin(theta));
    const Mat3 inertia = m * l * l / 3 * (Mat3::Identity() - axis * axis.transpose()) +
                         1e-3 * m * l * l * axis * axis.transpose();
    const Vec3 end = -l * axis;  // from the centre of mass to the lower end
    const Mat3 W = delassus_block(m, inertia.inverse(), end);
    for (const double mu : {0.0, 0.5, 4.0 / 3, 2.0}) {
      const double expected = rod_compliance(m, theta, mu);
      // Round-off of a 3 × 3 inverse and two products: 1e-12 of the frictionless compliance 4/m.
      EXPECT_NEAR(sliding_compliance(W, mu, Vec2(-1, 0)), expected, 1e-12 * 4 / m)
          << "θ = " << theta << ", μ = " << mu;
      // Sliding the other way, friction adds to the compliance: (1 + 3·cos²θ + 3·μ·sinθ·cosθ)/m.
      EXPECT_NEAR(sliding_compliance(W, mu, Vec2(1, 0)), rod_compliance(m, theta, -mu), 1e-12 * 4 / m);
    }
  }
  // The least critical μ is 4/3, at tan θ = 2: the compliance is 0 there and positive below it.
  const double critical = std::atan(2.0);
  const Vec3 axis(std::cos(critical), 0, std::sin(critical));
  const Mat3 inertia = m * l * l / 3 * (Mat3::Identity() - axis * axis.transpose()) +
                       1e-3 * m * l * l * axis * axis.transpose();
  const Mat3 W = delassus_block(m, inertia.inverse(), -l * axis);
  EXPECT_NEAR(sliding_compliance(W, 4.0 / 3, Vec2(-1, 0)), 0.0, 1e-12 * 4 / m);
  EXPECT_GT(sliding_compliance(W, 1.3, Vec2(-1, 0)), 0.0);
  EXPECT_LT(sliding_compliance(W, 1.4, Vec2(-1, 0)), 0.0);
}

// The rod's lower end as an edge of two corners (±w across the rod), both sliding towards −x under gravity,
// no spin: the end's free normal acceleration is −g, so the two corners together carry
// N = m·g / (1 + 3·cos²θ − 3·μ·sinθ·cosθ), half each by symmetry, with friction μ·N along +x — and for μ
// above the critical value no normal force holds them (Painlevé's inconsistent case, decided by the
// problem: both corners flagged, no force).
TEST(PainleveRod, TwoCornersOfASlidingEndTakeTheClosedFormForceOrArePainleves) {
  const double m = 2.5, l = 0.7, w = 0.05, g = 9.81, theta = std::atan(2.0);
  const Vec3 axis(std::cos(theta), 0, std::sin(theta));
  ContactBody body;
  body.mass = m;
  body.inertia = m * l * l / 3 * (Mat3::Identity() - axis * axis.transpose()) +
                 1e-3 * m * l * l * axis * axis.transpose();
  body.gravity = g;
  const std::vector<Vec3> arms{-l * axis + Vec3(0, w, 0), -l * axis - Vec3(0, w, 0)};
  const Motion motion{Vec3(-1, 0, 0), Vec3::Zero()};
  const std::vector<PointCondition> sliding(2, PointCondition{PointRule::sliding, Vec2(-1, 0), 0.0});
  for (const double mu : {0.3, 1.0, 1.3}) {
    const ContactForces f = contact_forces(body, motion, arms, mu, sliding);
    ASSERT_EQ(f.forces.size(), 2u);
    // The corners' offset ±w·ŷ adds a moment about the rod's axis only, which the small axial inertia
    // takes without changing the end's normal acceleration: the closed form holds to round-off (1e-9).
    const double N =
        m * g / (1 + 3 * std::cos(theta) * std::cos(theta) - 3 * mu * std::sin(theta) * std::cos(theta));
    for (const Vec3& F : f.forces) {
      EXPECT_NEAR(F.z(), N / 2, 1e-9 * N) << "μ = " << mu;
      EXPECT_NEAR(F.x(), mu * N / 2, 1e-9 * N) << "μ = " << mu;
      EXPECT_NEAR(F.y(), 0, 1e-9 * N) << "μ = " << mu;
    }
    EXPECT_EQ(f.painleve, 0);
  }
  const ContactForces jammed = contact_forces(body, motion, arms, 2.0, sliding);
  ASSERT_EQ(jammed.inconsistent.size(), 2u);
  EXPECT_TRUE(jammed.inconsistent[0] && jammed.inconsistent[1]);
  EXPECT_EQ(jammed.forces[0], Vec3::Zero());
  EXPECT_EQ(jammed.forces[1], Vec3::Zero());
}

}  // namespace
}  // namespace repose::sim
