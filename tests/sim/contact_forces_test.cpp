// Contact forces with Coulomb friction on the wall (src/sim/contact_forces.hpp): the instantaneous
// accelerations and forces against closed forms worked out here. m = 1, g = 9.81 throughout.
#include "../../src/sim/contact_forces.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace repose::sim {
namespace {

constexpr double g = 9.81;
// Values of the order of g·(1 + μ) solved to 1e-14 of the scale, then a few operations: 1e-12.
constexpr double kTol = 1e-12;

// A box a × b × h (x, y, z), m = 1, resting on its bottom face: its four bottom corners.
ContactBody box(double a, double b, double h) {
  return {1.0, Vec3((b * b + h * h) / 12, (a * a + h * h) / 12, (a * a + b * b) / 12).asDiagonal(), g, 0.0};
}
std::vector<Vec3> bottom(double a, double b, double h) {
  std::vector<Vec3> corners;
  for (double x : {-a / 2, a / 2})
    for (double y : {-b / 2, b / 2}) corners.emplace_back(x, y, -h / 2);
  return corners;
}
double pair_sum(const ContactForces& f, const std::vector<Vec3>& arms, bool front) {
  double sum = 0;
  for (std::size_t i = 0; i < arms.size(); ++i)
    if ((arms[i].x() > 0) == front) sum += f.forces[i].z();
  return sum;
}

// A box sliding flat along +x decelerates at μ·g: a = (−μg, 0, 0), no rotation, as long as its back edge
// stays pressed. The friction μ·m·g at the base, h/2 below the centre of mass, tilts the normal forces: front
// and back pairs take m·g·(1/2 ± μ·h/(2a)).
TEST(ContactForces, BoxSlidingFlatDeceleratesAtMuG) {
  for (const double mu : {0.2, 0.5, 0.9}) {
    const auto arms = bottom(1, 1, 1);
    const ContactForces f = contact_forces(box(1, 1, 1), {Vec3(1, 0, 0), Vec3::Zero()}, arms, mu, 1e-12);
    ASSERT_TRUE(f.converged);
    EXPECT_EQ(f.painleve, 0);
    EXPECT_NEAR(f.acceleration.x(), -mu * g, kTol) << mu;
    EXPECT_NEAR(f.acceleration.y(), 0, kTol) << mu;
    EXPECT_NEAR(f.acceleration.z(), 0, kTol) << mu;
    EXPECT_NEAR(f.angular_acceleration.norm(), 0, kTol) << mu;
    EXPECT_NEAR(pair_sum(f, arms, true), g * (0.5 + mu / 2), kTol) << mu;
    EXPECT_NEAR(pair_sum(f, arms, false), g * (0.5 - mu / 2), kTol) << mu;
    for (ContactMode m : f.modes) EXPECT_EQ(m, ContactMode::slide);
  }
}

// A tall box (1 × 1 × 3) sliding on its end: the back pair's share m·g·(1/2 − μ·h/(2a)) = g·(1/2 − 1.5·μ)
// reaches zero at μ = 1/3 (half its base over its centre of mass's height). Below, it slides upright; above,
// its back lifts (open) and it starts to tip forward (α_y > 0: the top moves ahead in +x).
TEST(ContactForces, TallBoxSlidingOnItsEndTipsIfAndOnlyIfMuExceedsAThird) {
  const auto arms = bottom(1, 1, 3);
  const Motion sliding{Vec3(2, 0, 0), Vec3::Zero()};
  for (const double mu : {0.2, 0.3, 0.33}) {
    const ContactForces f = contact_forces(box(1, 1, 3), sliding, arms, mu, 1e-12);
    EXPECT_NEAR(pair_sum(f, arms, false), g * (0.5 - 1.5 * mu), kTol) << mu;
    EXPECT_NEAR(f.angular_acceleration.norm(), 0, kTol) << mu;
    EXPECT_NEAR(f.acceleration.x(), -mu * g, kTol) << mu;
  }
  for (const double mu : {0.34, 0.5, 1.0}) {
    const ContactForces f = contact_forces(box(1, 1, 3), sliding, arms, mu, 1e-12);
    EXPECT_NEAR(pair_sum(f, arms, false), 0, kTol) << mu;
    for (std::size_t i = 0; i < arms.size(); ++i) {
      if (arms[i].x() < 0) {
        EXPECT_EQ(f.modes[i], ContactMode::open) << mu;
      }
    }
    EXPECT_GT(f.angular_acceleration.y(), 0) << mu;
    EXPECT_NEAR(f.acceleration.z() + f.angular_acceleration.cross(Vec3(0.5, 0, -1.5)).z(), 0, kTol)
        << "the front edge stays on the wall";
  }
}

// A uniform rod (length 1, m = 1, I = 1/12 about its centre) standing on its foot at θ from the vertical, at
// rest. Pinned, it would turn at α = 3g·sinθ/2 and need F_x = (3g/4)·sinθ·cosθ against N = g·(1 −
// (3/4)sin²θ): it sticks while F_x/N = 3·sinθ·cosθ/(4 − 3·sin²θ) ≤ μ, else its foot slides back (F_x = μ·N on
// the cone). μ = 0: no horizontal force, the centre of mass falls straight down.
TEST(ContactForces, RodOnItsFootSticksOrSlipsAtTheClosedFormRatio) {
  const ContactBody rod{1.0, Mat3::Identity() / 12, g, 0.0};
  for (const double theta : {0.1, 0.3, 0.6, 1.0}) {
    const double s = std::sin(theta), c = std::cos(theta);
    const double ratio = 3 * s * c / (4 - 3 * s * s);
    const std::vector<Vec3> foot = {-0.5 * Vec3(s, 0, c)};  // the top leans towards +x
    for (const double mu : {0.0, 0.5 * ratio, 2 * ratio}) {
      const ContactForces f = contact_forces(rod, {Vec3::Zero(), Vec3::Zero()}, foot, mu, 1e-12);
      ASSERT_TRUE(f.converged);
      if (mu >= ratio) {
        EXPECT_EQ(f.modes[0], ContactMode::stick) << theta << " " << mu;
        EXPECT_NEAR(f.forces[0].x(), 0.75 * g * s * c, kTol) << theta;
        EXPECT_NEAR(f.forces[0].z(), g * (1 - 0.75 * s * s), kTol) << theta;
        EXPECT_NEAR(f.angular_acceleration.y(), 1.5 * g * s, kTol) << theta;
      } else {
        EXPECT_EQ(f.modes[0], ContactMode::slide) << theta << " " << mu;
        EXPECT_NEAR(f.forces[0].x(), mu * f.forces[0].z(), kTol) << theta << " " << mu;
        EXPECT_NEAR(f.acceleration.x(), mu * f.forces[0].z(), kTol) << theta << " " << mu;
        // The foot stays on the wall: a_n = 0.
        const Vec3 a_foot = f.acceleration + f.angular_acceleration.cross(foot[0]);
        EXPECT_NEAR(a_foot.z(), 0, kTol) << theta << " " << mu;
        EXPECT_GT(f.forces[0].z(), 0);
      }
    }
  }
}

// The same rod turning about its stuck foot at ω (falling towards +x: ω_y > 0). The pin gives no moment about
// the foot, so α = 3g·sinθ/2 still; the centre of mass (L/2 from the foot) adds the centripetal ω²·L/2
// towards the foot: F_x = (L/2)·(α·cosθ − ω²·sinθ), N = g − (L/2)·(α·sinθ + ω²·cosθ) (m = 1, L = 1).
TEST(ContactForces, TurningRodAddsTheCentripetalForce) {
  const ContactBody rod{1.0, Mat3::Identity() / 12, g, 0.0};
  const double theta = 0.3, omega = 2.0, s = std::sin(theta), c = std::cos(theta);
  const std::vector<Vec3> foot = {-0.5 * Vec3(s, 0, c)};
  // The foot at rest: v = −ω × r_foot.
  const Vec3 w(0, omega, 0);
  const Motion turning{-w.cross(foot[0]), w};
  const ContactForces f = contact_forces(rod, turning, foot, 10.0, 1e-12);
  const double alpha = 1.5 * g * s;
  EXPECT_EQ(f.modes[0], ContactMode::stick);
  EXPECT_NEAR(f.angular_acceleration.y(), alpha, kTol);
  EXPECT_NEAR(f.forces[0].x(), 0.5 * (alpha * c - omega * omega * s), kTol);
  EXPECT_NEAR(f.forces[0].z(), g - 0.5 * (alpha * s + omega * omega * c), kTol);
}

// Painlevé's rod: its foot sliding towards −x under the top leaning to +x at 45°. The normal force that keeps
// the foot on the wall is N = −f_n/d with d = (1 + 3·sin²θ − 3·μ·sinθ·cosθ)/m, which turns negative for μ
// above (1 + 3·sin²θ)/(3·sinθ·cosθ) = 5/3: no consistent force, counted.
TEST(ContactForces, PainleveRodHasNoConsistentNormalForce) {
  const ContactBody rod{1.0, Mat3::Identity() / 12, g, 0.0};
  const double s = std::sqrt(0.5);
  const std::vector<Vec3> foot = {-0.5 * Vec3(s, 0, s)};
  const Motion sliding{Vec3(-1, 0, 0), Vec3::Zero()};
  EXPECT_EQ(contact_forces(rod, sliding, foot, 1.6, 1e-12).painleve, 0);
  EXPECT_EQ(contact_forces(rod, sliding, foot, 1.7, 1e-12).painleve, 1);
  // Below the bound, the force is the closed form's: N = g / (1 + 3s² − 3μs²)·(1) for the rod at rest
  // otherwise.
  const ContactForces f = contact_forces(rod, sliding, foot, 1.0, 1e-12);
  EXPECT_NEAR(f.forces[0].z(), g / (1 + 1.5 - 1.5), kTol);
  EXPECT_NEAR(f.forces[0].x(), 1.0 * f.forces[0].z(), kTol);  // against the slip (−x): +x
}

}  // namespace
}  // namespace repose::sim
