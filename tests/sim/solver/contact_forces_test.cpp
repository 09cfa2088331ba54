// Contact forces with Coulomb friction on the wall (src/sim/solver/contact_forces.hpp): the instantaneous
// accelerations and forces against closed forms worked out here. m = 1, g = 9.81 throughout.
#include "../../../src/sim/solver/contact_forces.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

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

// Two sliding points with μ from 1.5 to 3, at random places on a body of random inertia moving at random:
// where Gauss–Seidel's sweeps need not contract. The normal forces against enumeration of the four
// complementary sets of the 2×2 LCP that Newton–Euler's equations give for the normal accelerations (built
// here from the forces, not from the code's Delassus blocks). Where it has exactly one solution the forces
// must be it (1e-9 of m·g: a pivot on a 2×2 of condition below ~1e4); where it has none, the case is
// Painlevé's, flagged at a point driven into the wall, with no force applied.
TEST(ContactForces, SlidingPairWithLargeFrictionMatchesTheEnumeratedLcp) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int unique = 0, none = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const double mu = 1.5 + 0.75 * (u(rng) + 1);
    const Mat3 R =
        Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
    const Mat3 inertia =
        R *
        Vec3(0.05 + 0.1 * (u(rng) + 1), 0.05 + 0.1 * (u(rng) + 1), 0.05 + 0.1 * (u(rng) + 1)).asDiagonal() *
        R.transpose();
    const ContactBody body{1.0, inertia, g, 0.0};
    const double depth = -0.3 - 0.2 * (u(rng) + 1);
    const std::vector<Vec3> arms = {Vec3(u(rng), u(rng), depth), Vec3(u(rng), u(rng), depth)};
    const Motion motion{Vec3(u(rng), u(rng), 0), Vec3(0, 0, 3 * u(rng))};
    std::vector<Vec2> slip(2);
    for (int i = 0; i < 2; ++i)
      slip[i] = (motion.velocity + motion.omega.cross(arms[i])).head<2>().normalized();
    // The normal accelerations for normal forces λ: affine, its columns read off at λ = 0, e_1, e_2.
    const auto normal_accelerations = [&](const Vec2& lambda) {
      Vec3 force = Vec3::Zero(), moment = -motion.omega.cross(inertia * motion.omega);
      for (int i = 0; i < 2; ++i) {
        const Vec3 f = lambda(i) * Vec3(-mu * slip[i].x(), -mu * slip[i].y(), 1);
        force += f;
        moment += arms[i].cross(f);
      }
      const Vec3 a = force - Vec3(0, 0, g), alpha = inertia.inverse() * moment;
      Vec2 an;
      for (int i = 0; i < 2; ++i)
        an(i) = (a + alpha.cross(arms[i]) + motion.omega.cross(motion.omega.cross(arms[i]))).z();
      return an;
    };
    const Vec2 q = normal_accelerations(Vec2::Zero());
    Eigen::Matrix2d M;
    M.col(0) = normal_accelerations(Vec2(1, 0)) - q;
    M.col(1) = normal_accelerations(Vec2(0, 1)) - q;
    std::vector<Vec2> solutions;
    for (int mask = 0; mask < 4; ++mask) {
      Vec2 z = Vec2::Zero();
      if (mask == 3) {
        if (std::abs(M.determinant()) < 1e-9) continue;
        z = M.lu().solve(-q);
      } else if (mask != 0) {
        const int i = mask - 1;
        z(i) = -q(i) / M(i, i);
      }
      const Vec2 w = M * z + q;
      if (z.minCoeff() >= -1e-12 && w.minCoeff() >= -1e-9 * g) solutions.push_back(z);
    }
    std::vector<PointCondition> conditions(2);
    for (int i = 0; i < 2; ++i) conditions[i].rule = PointRule::sliding, conditions[i].direction = slip[i];
    const ContactForces f = contact_forces(body, motion, arms, mu, conditions);
    if (solutions.size() == 1) {
      ++unique;
      for (int i = 0; i < 2; ++i)
        EXPECT_NEAR(f.forces[i].z(), solutions[0](i), 1e-9 * g)
            << "trial " << trial << " M " << M << " q " << q.transpose() << " painleve " << f.painleve;
    } else if (solutions.empty()) {
      ++none;
      EXPECT_TRUE(f.inconsistent[0] || f.inconsistent[1]) << "trial " << trial;
      for (int i = 0; i < 2; ++i) {
        if (f.inconsistent[i]) {
          EXPECT_EQ(f.forces[i].z(), 0.0) << "trial " << trial;
        }
      }
    }
  }
  EXPECT_GT(unique, 100);
  EXPECT_GT(none, 5);
}

}  // namespace
}  // namespace repose::sim
