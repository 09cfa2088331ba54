// The contact problem's solver (src/sim/solver/contact_problem.hpp) on its hardest case: an edge pressed at
// the limit of its friction cone while the body turns about it. The two points share their tangential force
// along the edge (a unit force there moves the body alike from either point), and block Gauss–Seidel creeps:
// on a 1 × 2 × 3 box tossed at μ 0.3 it took 5,000 sweeps and handed the problem to Lemke's pyramid (peer
// benchmark, box123 drop 49). The answer is checked here against Coulomb's law and complementarity directly,
// not against the solver.
#include "../../../src/sim/solver/contact_problem.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace repose::sim {
namespace {

// Coulomb's law and complementarity at every point of a solution for unilateral points, within `tol` of the
// problem's scale (values) and of mass·scale (reactions); the body's velocities recomputed from the
// reactions. Returns the first violation, empty if none.
std::string coulomb_violation(const ContactProblem& p, const Vec3& lin, const Vec3& ang,
                              const ContactSolution& s, double tol) {
  Vec3 body_lin = lin, body_ang = ang;
  for (std::size_t i = 0; i < p.arms.size(); ++i) {
    body_lin += s.reactions[i] / p.mass;
    body_ang += p.inverse_inertia * p.arms[i].cross(s.reactions[i]);
  }
  const double value_tol = tol * p.scale, force_tol = tol * p.mass * p.scale;
  if ((body_lin - s.lin).norm() > value_tol || (body_ang - s.ang).norm() > value_tol)
    return "velocities not those of the reactions";
  for (std::size_t i = 0; i < p.arms.size(); ++i) {
    const Vec3 x = point_value(p, i, body_lin, body_ang);
    const Vec3& R = s.reactions[i];
    const std::string at = " at point " + std::to_string(i);
    if (R.z() < -force_tol) return "pulling" + at;
    if (x.z() < -value_tol) return "entering the wall" + at;
    if (R.z() > force_tol && x.z() > value_tol) return "pressed while leaving" + at;
    if (R.head<2>().norm() > p.friction * R.z() + force_tol) return "outside the cone" + at;
    const Vec2 slip = x.head<2>();
    // A slipping point's friction is on the cone's edge, against its slip (maximal dissipation).
    if (slip.norm() > value_tol &&
        (R.head<2>() + p.friction * R.z() * slip.normalized()).norm() > force_tol + 1e-9 * R.z())
      return "friction not against the slip" + at;
  }
  return {};
}

// A rigid body pressed on one edge while it turns about it, its tangential load near the edge's stick limit:
// gravity plus a random horizontal pull on the centre of mass, the same angular acceleration as before.
struct EdgeCase {
  ContactProblem problem;
  Vec3 lin, ang;
};

EdgeCase random_edge(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  EdgeCase c;
  const Mat3 R =
      Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
  const Vec3 moments(0.3 + 0.2 * u(rng), 0.4 + 0.2 * u(rng), 0.5 + 0.2 * u(rng));
  c.problem.mass = 1;
  c.problem.inverse_inertia = R * moments.cwiseInverse().asDiagonal() * R.transpose();
  c.problem.friction = 0.2 + 0.15 * (u(rng) + 1);
  c.problem.scale = 9.81;
  const double depth = -0.8 - 0.3 * u(rng);
  const Vec3 along = Vec3(u(rng), u(rng), 0).normalized();
  const Vec3 first(u(rng), u(rng), depth);
  const Vec3 second = first + (1 + 0.5 * u(rng)) * along;
  c.problem.arms = {first, second};
  // The body turns about the edge: both points have the same centripetal part ω × (ω × r).
  const Vec3 omega = 1.5 * u(rng) * along;
  c.problem.offsets = {omega.cross(omega.cross(first)), omega.cross(omega.cross(second))};
  // A pull of about μ·g across the edge (and some along it): near the limit where the edge starts to slip.
  const Vec3 across = Vec3::UnitZ().cross(along);
  c.lin = Vec3(0, 0, -9.81) + 9.81 * c.problem.friction * (1 + 0.05 * u(rng)) * across +
          2 * u(rng) * c.problem.friction * along;
  c.ang = Vec3(u(rng), u(rng), 0.1 * u(rng));
  return c;
}

// Tolerance: the values are solved to 1e-14 of the scale; the checks above add a few operations on values
// and reactions of the order of the scale, and the slip direction is taken from values down to the
// tolerance itself: 1e-9 leaves room for that without admitting a pyramid's answer (its friction up to 3.4 %
// off the cone, or off the slip's direction).
constexpr double kProblemTolerance = 1e-9;

TEST(ContactProblem, EdgeAtTheLimitOfItsConeMeetsCoulombsLawExactly) {
  std::mt19937_64 rng(34);
  int pressed = 0, slipping = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const EdgeCase c = random_edge(rng);
    const std::vector<PointCondition> unilateral(2);
    const ContactSolution s = solve_contacts(c.problem, c.lin, c.ang, unilateral);
    ASSERT_TRUE(s.solved) << "trial " << trial;
    EXPECT_TRUE(s.converged) << "trial " << trial;
    EXPECT_EQ(coulomb_violation(c.problem, c.lin, c.ang, s, kProblemTolerance), "") << "trial " << trial;
    if (s.reactions[0].z() > 0 && s.reactions[1].z() > 0) ++pressed;
    if (point_value(c.problem, 0, s.lin, s.ang).head<2>().norm() > kProblemTolerance * c.problem.scale)
      ++slipping;
  }
  // The cases are the hard ones: both points pressed, and many of them slipping.
  EXPECT_GT(pressed, 700) << slipping;
  EXPECT_GT(slipping, 200) << pressed;
}

// Newton's method converges from near a solution: from the sweeps' reactions each moved by up to 1e-3 of the
// weight, it meets Coulomb's law to the same tolerance on its own.
TEST(ContactProblem, NewtonsMethodConvergesFromNearASolution) {
  std::mt19937_64 rng(35);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 500; ++trial) {
    const EdgeCase c = random_edge(rng);
    const std::vector<PointCondition> unilateral(2);
    const PointList<Vec3> solved = solve_contacts(c.problem, c.lin, c.ang, unilateral).reactions;
    std::vector<Vec3> start(solved.begin(), solved.end());
    for (Vec3& r : start) r += 1e-3 * c.problem.mass * c.problem.scale * Vec3(u(rng), u(rng), u(rng));
    const std::optional<PointList<Vec3>> newton =
        solve_contacts_by_newton(c.problem, c.lin, c.ang, unilateral, start);
    ASSERT_TRUE(newton);
    ContactSolution s;
    s.reactions = *newton;
    s.lin = c.lin;
    s.ang = c.ang;
    for (std::size_t i = 0; i < 2; ++i) {
      s.lin += s.reactions[i] / c.problem.mass;
      s.ang += c.problem.inverse_inertia * c.problem.arms[i].cross(s.reactions[i]);
    }
    EXPECT_EQ(coulomb_violation(c.problem, c.lin, c.ang, s, kProblemTolerance), "") << "trial " << trial;
  }
}

// One point's sliding reaction against Coulomb's law written out (not against the secular equation it
// solves): on the cone's edge, |R_t| = μ·R_n; unilateral, the point's normal value after it 0; and its slip
// after it, x_t = f_t + (W·R)_t, along −R_t (friction opposes the slip). Blocks of a point mass (W = I/m: the
// closed form R = (−μ·λ·f̂_t, λ), λ = −m·f_n) and random Delassus blocks; 1e-12 relative: a bracketed root to
// 4 ulps.
TEST(SlidingReaction, MeetsCoulombsLawOnTheConesEdge) {
  const double m = 2, mu = 0.4;
  const Vec3 f(3, -1, -0.5);
  const std::optional<Vec3> point = sliding_reaction(Mat3::Identity() / m, f, mu, -1);
  ASSERT_TRUE(point.has_value());
  const Vec2 slip = f.head<2>().normalized();
  EXPECT_LT((*point - Vec3(-mu * m * 0.5 * slip.x(), -mu * m * 0.5 * slip.y(), m * 0.5)).norm(), 1e-12);
  const std::optional<Vec3> given = sliding_reaction(Mat3::Identity() / m, Vec3(3, -1, 0.7), mu, 0.25);
  ASSERT_TRUE(given.has_value());
  EXPECT_LT((*given - Vec3(-mu * 0.25 * slip.x(), -mu * 0.25 * slip.y(), 0.25)).norm(), 1e-12);

  std::mt19937_64 rng(48);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 arm(u(rng), u(rng), -0.5 + 0.4 * u(rng));
    const Mat3 inverse_inertia =
        (Mat3::Identity() * 1.5 + 0.5 * Vec3(u(rng), u(rng), u(rng)).asDiagonal().toDenseMatrix());
    const Mat3 W = delassus_block(1.0, inverse_inertia, arm);
    const Vec3 value(3 * u(rng), 3 * u(rng), -0.1 - std::abs(u(rng)));
    const double friction = 0.05 + std::abs(u(rng));
    const Vec3 stick = -W.ldlt().solve(value);
    if (stick.head<2>().norm() <= friction * stick.z()) continue;  // sticks: no sliding reaction asked
    const std::optional<Vec3> R = sliding_reaction(W, value, friction, -1);
    ASSERT_TRUE(R.has_value()) << trial;
    const Vec3 after = value + W * *R;
    const double scale = value.norm() + (W * *R).norm();
    EXPECT_NEAR(R->head<2>().norm(), friction * R->z(), 1e-12 * R->norm()) << trial;
    EXPECT_NEAR(after.z(), 0, 1e-12 * scale) << trial;
    const Vec2 along = after.head<2>();
    EXPECT_GE(-along.dot(R->head<2>()), 0) << trial;
    EXPECT_LE(std::abs(along.x() * R->y() - along.y() * R->x()), 1e-10 * scale * R->norm()) << trial;
  }
}

// Data that are not finite have no reaction (the caller then counts the point unresolved): a slip of infinite
// speed, on a block whose tangential directions are coupled (its slip equation's bracket then runs to
// infinity and back to NaN), with a finite normal value; and a NaN block.
TEST(SlidingReaction, DataThatAreNotFiniteHaveNone) {
  Mat3 W;
  W << 2, 0.5, 0, 0.5, 1, 0, 0, 0, 1.5;
  EXPECT_FALSE(sliding_reaction(W, Vec3(INFINITY, 0, -1), 0.5, -1).has_value());
  EXPECT_FALSE(sliding_reaction(W, Vec3(NAN, 0, -1), 0.5, -1).has_value());
  EXPECT_FALSE(sliding_reaction(W, Vec3(1, 0, -1), 0.5, NAN).has_value());
  Mat3 bad = W;
  bad(0, 1) = NAN;
  EXPECT_FALSE(sliding_reaction(bad, Vec3(1, 0, -1), 0.5, -1).has_value());
}

}  // namespace
}  // namespace repose::sim
