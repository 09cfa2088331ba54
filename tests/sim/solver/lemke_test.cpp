// Lemke's method (src/sim/solver/lemke.hpp) and the contact problem solved as one LCP (contact_problem.hpp),
// against enumeration of every complementary basis (an independent reference: 2^n linear solves) and closed
// forms.
#include "../../../src/sim/solver/lemke.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "../../../src/sim/solver/contact_problem.hpp"

namespace repose::sim {
namespace {

// Every solution of LCP(M, q) by enumeration of the 2^n sets of positive unknowns; a solution is kept where
// z ≥ −1e-10·scale and w ≥ −1e-10·scale (round-off of a linear solve of a well-conditioned n ≤ 8 system).
std::vector<Eigen::VectorXd> enumerate(const Eigen::MatrixXd& M, const Eigen::VectorXd& q) {
  const int n = static_cast<int>(q.size());
  const double scale = std::max(1.0, q.cwiseAbs().maxCoeff());
  std::vector<Eigen::VectorXd> out;
  for (int mask = 0; mask < (1 << n); ++mask) {
    std::vector<int> on;
    for (int k = 0; k < n; ++k)
      if (mask >> k & 1) on.push_back(k);
    Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
    if (!on.empty()) {
      const auto m = static_cast<Eigen::Index>(on.size());
      Eigen::MatrixXd A(m, m);
      Eigen::VectorXd b(m);
      for (Eigen::Index a = 0; a < m; ++a) {
        b(a) = -q(on[static_cast<std::size_t>(a)]);
        for (Eigen::Index c = 0; c < m; ++c)
          A(a, c) = M(on[static_cast<std::size_t>(a)], on[static_cast<std::size_t>(c)]);
      }
      const Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
      if (!lu.isInvertible()) continue;
      const Eigen::VectorXd x = lu.solve(b);
      for (Eigen::Index a = 0; a < m; ++a) z(on[static_cast<std::size_t>(a)]) = x(a);
    }
    const Eigen::VectorXd w = M * z + q;
    if (z.minCoeff() >= -1e-10 * scale && w.minCoeff() >= -1e-10 * scale) out.push_back(z);
  }
  return out;
}

// P-matrices (symmetric positive definite, and non-symmetric with a dominant diagonal): each LCP has exactly
// one solution (Cottle, Pang & Stone, Thm 3.3.7), which Lemke's method must find. Tolerance 1e-9 of the
// solution's scale: pivots on matrices of condition below ~1e3.
TEST(Lemke, SolvesPMatrixProblemsAsEnumerationDoes) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  int nontrivial = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 8;
    Eigen::MatrixXd M(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) M(i, j) = u(rng);
    if (trial % 2 == 0) {
      M = M * M.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    } else {
      for (int i = 0; i < n; ++i) M(i, i) = 0.1 + M.row(i).cwiseAbs().sum();
    }
    Eigen::VectorXd q(n);
    for (int i = 0; i < n; ++i) q(i) = u(rng);
    const auto all = enumerate(M, q);
    ASSERT_EQ(all.size(), 1u) << "trial " << trial;
    const auto z = solve_lcp(M, q, 1000);
    ASSERT_TRUE(z) << "trial " << trial;
    EXPECT_LE((*z - all[0]).norm(), 1e-9 * std::max(1.0, all[0].norm())) << "trial " << trial;
    if (all[0].norm() > 0) ++nontrivial;
  }
  EXPECT_GT(nontrivial, 150);
}

// No solution: Lemke's method ends on a ray and says so. w = −z − 1 can never be ≥ 0; and a 2×2 whose
// every basis fails (det −3: z = (−1, −1) on both, the single ones leave the other w at −3).
TEST(Lemke, ReportsProblemsWithoutSolution) {
  EXPECT_FALSE(solve_lcp(Eigen::MatrixXd::Constant(1, 1, -1), Eigen::VectorXd::Constant(1, -1), 100));
  Eigen::MatrixXd M(2, 2);
  M << 1, -2, -2, 1;
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(2, -1);
  ASSERT_TRUE(enumerate(M, q).empty());
  EXPECT_FALSE(solve_lcp(M, q, 100));
}

// A block on an incline, as the contact problem's LCP: a cube (m = 1, side 1) resting on its face, gravity
// tilted by θ about y (the incline's frame), its four corners at rest on the wall with μ. It sticks (all
// accelerations zero) if tan θ ≤ μ, else slides down at g·(sin θ − μ·cos θ) without turning while its back
// corners stay pressed (the pyramid has an edge along x, so μ is exact there). Redundant contacts (four
// corners, three constraints) make the LCP degenerate: the lexicographic rule must still end. Tolerance
// 1e-10·g: pivots on a 56-unknown tableau of entries O(1).
TEST(Lemke, BlockOnAnInclineSticksOrSlidesAtTheClosedForm) {
  constexpr double g = 9.81;
  for (const double mu : {0.3, 0.7})
    for (const double theta : {0.1, 0.25, 0.5, 0.7}) {
      ContactProblem p;
      p.mass = 1;
      p.inverse_inertia = 6 * Mat3::Identity();  // I = m·(1 + 1)/12 about every axis
      for (double x : {-0.5, 0.5})
        for (double y : {-0.5, 0.5}) p.arms.emplace_back(x, y, -0.5);
      p.friction = mu;
      p.scale = g;
      const Vec3 gravity(g * std::sin(theta), 0, -g * std::cos(theta));
      const auto s = solve_contacts_by_pivoting(p, gravity, Vec3::Zero(), std::vector<PointCondition>(4));
      ASSERT_TRUE(s) << "mu " << mu << " theta " << theta;
      const double slide = std::tan(theta) <= mu ? 0.0 : g * (std::sin(theta) - mu * std::cos(theta));
      EXPECT_NEAR(s->lin.x(), slide, 1e-10 * g) << "mu " << mu << " theta " << theta;
      EXPECT_NEAR(s->lin.y(), 0, 1e-10 * g);
      EXPECT_NEAR(s->lin.z(), 0, 1e-10 * g);
      EXPECT_LE(s->ang.norm(), 1e-10 * g);
      Vec3 total = Vec3::Zero();
      for (const Vec3& r : s->reactions) {
        EXPECT_GE(r.z(), -1e-12);
        EXPECT_LE(r.head<2>().norm(), mu * r.z() * (1 + 1e-12) + 1e-12);
        total += r;
      }
      EXPECT_NEAR(total.z(), g * std::cos(theta), 1e-10 * g);
    }
}

// The plastic impact that broke the 10,000-toss sweep (case 9731: a 64-sided cylinder, r 1.236, h 0.9293,
// density 1.2 g/cm³, rolling over an edge of its rim at μ 0.98): two points of one edge, the first at rest,
// the second approaching at 2e-3 while the body moves at 3e-2. The edge's two points make the Delassus matrix
// singular (their distance is rigid), and Lemke's pivoting on the friction pyramid lost the answer: it
// returned a normal impulse at the first point while it left the wall at 0.019 (w = −0.022 in the LCP). The
// answer is now checked against the problem: pivoting returns a complementary solution or none, and the
// whole solve (Gauss–Seidel, stopped at round-off) one with no point pressed while leaving or approaching.
TEST(Lemke, PivotingOnAnEdgesSingularMatrixReturnsAComplementarySolutionOrNone) {
  ContactProblem p;
  p.mass = 5.3435039006498206;
  Mat3 inertia;
  inertia << 2.4220901855984254, 3.9380244369603353e-13, 6.9720264765919962e-07, 3.9380244369971505e-13,
      2.4220901855986567, 9.3286289929623663e-07, 6.9720264765919983e-07, 9.3286289929623642e-07,
      4.0750733878770591;
  p.inverse_inertia = inertia.inverse();
  p.arms = {Vec3(0.69046788928915603, 1.0251581758807851, -0.46465086977790071),
            Vec3(0.7876261952223933, 0.95254405058985814, -0.46465086977790349)};
  p.friction = 0.98289805334939551;
  const Vec3 v(0.025588952597763955, 0.02092808456519115, 0.084198587864471972);
  const Vec3 w(-0.045040726506615454, 0.055070944538016198, 1.8564697431553982e-07);
  p.scale = 0;
  for (std::size_t i = 0; i < 2; ++i) p.scale = std::max(p.scale, point_value(p, i, v, w).norm());
  const std::vector<PointCondition> at_rest(2);
  // Complementary to 1e-9 of the body's speed (the points' values are differences of terms of that size).
  const double tol = 1e-9 * (v.norm() + w.norm() * p.arms[0].norm());
  const auto check = [&](const ContactSolution& s, const char* how) {
    for (std::size_t i = 0; i < 2; ++i) {
      const Vec3 u = point_value(p, i, s.lin, s.ang);
      EXPECT_GE(u.z(), -tol) << how << " point " << i;
      if (s.reactions[i].z() > 0) {
        EXPECT_LE(u.z(), tol) << how << " point " << i << " pressed while leaving";
      }
    }
  };
  if (const auto pivoted = solve_contacts_by_pivoting(p, v, w, at_rest)) {
    check(*pivoted, "pivoting");
  }
  const ContactSolution solved = solve_contacts(p, v, w, at_rest);
  ASSERT_TRUE(solved.solved);
  EXPECT_TRUE(solved.converged);
  check(solved, "solve_contacts");
}

}  // namespace
}  // namespace repose::sim
