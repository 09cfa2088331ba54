// The face model's stick test against an independent threshold (issue 48: a stick test taking half the cone
// passed every other test). A tetrahedron on its base turns about the vertical through one base vertex (the
// one its apex leans over, which carries most of the weight), at rest there; the two others slide. Written
// in the pivot's frame the motion is planar — the face stays flush, so α = β·ẑ — and six unknowns (β, the
// pivot's tangential force f and the three normal forces) follow from Newton–Euler's six equations, with
// I·α = β·I·ẑ and ω × I·ω = ω²·ẑ × I·ẑ, the inertia in closed form (a tetrahedron's second moment about its
// centroid is m/20·Σ v_i·v_iᵀ over its vertices). The pivot sticks while |f| ≤ μ·N_pivot: the threshold μ* is
// the root of |f(μ)| − μ·N_pivot(μ), found by bisection on the reference alone. The library must stick 2 %
// above μ* (with the reference's forces) and slide on the cone 2 % below it.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>
#include <optional>
#include <repose/model/particle.hpp>

#include "../../../src/sim/solver/contact_forces.hpp"
#include "../../../src/sim/solver/sliding_face.hpp"
#include "../../gravity.hpp"

namespace repose::sim {
namespace {

// The reference's forces solve a 6×6 system exactly; the library's a face system of 11 unknowns: both to
// round-off, 1e-9 of m·g leaves six orders of margin over their condition numbers (below 1e3 here).
constexpr double kPivotForceTolerance = 1e-9;

struct PivotReference {
  double beta = 0;  // the vertical angular acceleration
  Vec2 f = Vec2::Zero();
  Vec3 normals = Vec3::Zero();
  double excess(double mu) const { return f.norm() - mu * normals(0); }  // > 0: the pivot cannot stick
};

// arms[0] is the pivot, all three on the base plane below the centre of mass; spin ω about ẑ.
PivotReference pivot_reference(const std::array<Vec3, 3>& arms, double mass, const Mat3& inertia, double g,
                               double omega, double mu) {
  const Vec3 d0(arms[0].x(), arms[0].y(), 0);
  // Unknowns x = (β, f_x, f_y, N0, N1, N2). The centre of mass's acceleration keeps the pivot still:
  // a = −β·ẑ × d0 + ω²·d0, linear in β.
  const Vec3 a_per_beta = -Vec3::UnitZ().cross(d0), a_const = omega * omega * d0;
  // The force at each point per unknown: F_0 = (f, N0), F_i = N_i·(−μ·ŝ_i, 1) with ŝ_i along ω·ẑ × (r_i −
  // r_0).
  std::array<Eigen::Matrix<double, 3, 6>, 3> force;
  for (auto& F : force) F.setZero();
  force[0](0, 1) = force[0](1, 2) = force[0](2, 3) = 1;
  for (int i = 1; i < 3; ++i) {
    const Vec3 slip = (omega * Vec3::UnitZ()).cross(arms[i] - arms[0]).normalized();
    force[i].col(3 + i) = Vec3(-mu * slip.x(), -mu * slip.y(), 1);
  }
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
  // m·a − ΣF = −m·g·ẑ.
  A.block<3, 1>(0, 0) = mass * a_per_beta;
  rhs.head<3>() = -mass * a_const - Vec3(0, 0, mass * g);
  // β·I·ẑ − Σ r × F = −ω²·ẑ × I·ẑ.
  A.block<3, 1>(3, 0) = inertia.col(2);
  rhs.tail<3>() = -omega * omega * Vec3::UnitZ().cross(inertia.col(2));
  for (int i = 0; i < 3; ++i) {
    A.topRows<3>() -= force[i];
    for (int c = 0; c < 6; ++c) A.block<3, 1>(3, c) -= arms[i].cross(Vec3(force[i].col(c)));
  }
  const Eigen::Matrix<double, 6, 1> x = A.fullPivLu().solve(rhs);
  return {x(0), Vec2(x(1), x(2)), Vec3(x(3), x(4), x(5))};
}

// The tetrahedron on its base, its three base vertices' arms from the centroid, the closed-form centroid and
// inertia (independent of the model's quadrature), and its spin about the pivot (arms[0]): the other two
// slide along their velocities.
struct TurningTetrahedron {
  const std::array<Vec3, 4> vertices{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-0.3, -0.3, 0.6)};
  Particle particle;
  double mass = 0;
  Mat3 inertia = Mat3::Zero();
  std::array<Vec3, 3> arms;

  TurningTetrahedron() {
    MeshOptions options;
    options.inertia = InertiaModel::convex;
    particle = make_particle(TriangleMesh{std::vector<Vec3>(vertices.begin(), vertices.end()), {}},
                             "tetrahedron", 1.0, options);
    mass = particle.mass.mass;
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& v : vertices) centroid += v / 4;
    Mat3 second = Mat3::Zero();
    for (const Vec3& v : vertices) second += mass / 20 * (v - centroid) * (v - centroid).transpose();
    inertia = second.trace() * Mat3::Identity() - second;
    for (std::size_t i = 0; i < 3; ++i) arms[i] = vertices[i] - centroid;
  }
  // μ*: the reference's excess falls through zero once on [0.05, 2] for this body (checked at the ends).
  double threshold(double g, double omega) const {
    const auto excess = [&](double mu) {
      return pivot_reference(arms, mass, inertia, g, omega, mu).excess(mu);
    };
    double lo = 0.05, hi = 2;
    EXPECT_GT(excess(lo), 0);
    EXPECT_LT(excess(hi), 0);
    for (int k = 0; k < 100; ++k) (excess(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
    return 0.5 * (lo + hi);
  }
  Motion motion(double omega) const {
    return {-(omega * Vec3::UnitZ()).cross(arms[0]), omega * Vec3::UnitZ()};
  }
  std::vector<PointCondition> conditions(const Motion& motion) const {
    std::vector<PointCondition> c(3);
    for (std::size_t k = 1; k < 3; ++k) {
      c[k].rule = PointRule::sliding;
      c[k].direction = (motion.velocity + motion.omega.cross(arms[k])).head<2>().normalized();
    }
    return c;
  }
  std::vector<Vec3> arm_list() const { return {arms.begin(), arms.end()}; }
};

TEST(FaceStickThreshold, TetrahedronTurningAboutABaseVertexSticksAboveTheClosedFormThresholdAndSlidesBelow) {
  const double omega = 4, g = repose::test::kGravitySI;
  const TurningTetrahedron tet;
  const double mass = tet.mass;
  const Mat3& inertia = tet.inertia;
  const auto& arms = tet.arms;
  ASSERT_LT((tet.particle.mass.inertia - inertia).norm(), 1e-12 * inertia.norm());
  const double threshold = tet.threshold(g, omega);
  std::cout << "μ* = " << threshold << "\n";

  const ContactBody body{mass, tet.particle.mass.inertia, g, 0.0};
  const Motion motion = tet.motion(omega);
  const std::vector<PointCondition> conditions = tet.conditions(motion);
  const std::vector<Vec3> arm_list = tet.arm_list();
  for (const double factor : {1.02, 0.98}) {
    const double mu = factor * threshold;
    // The face model itself (contact_forces falls back on the complementarity problem where it gives no
    // answer, which would hide a wrong stick test), then the forces the engine takes.
    const std::optional<ContactForces> face = sliding_face(body, motion, arm_list, mu, conditions);
    ASSERT_TRUE(face.has_value()) << "μ = " << mu << ": the face model gave no answer";
    for (const ContactForces& forces : {*face, contact_forces(body, motion, arm_list, mu, conditions)}) {
      ASSERT_EQ(forces.forces.size(), 3u);
      if (factor > 1) {
        const PivotReference ref = pivot_reference(arms, mass, inertia, g, omega, mu);
        EXPECT_EQ(forces.modes[0], ContactMode::stick) << "μ = " << mu << " above μ* = " << threshold;
        const double tol = kPivotForceTolerance * mass * g;
        EXPECT_NEAR(forces.forces[0].x(), ref.f.x(), tol);
        EXPECT_NEAR(forces.forces[0].y(), ref.f.y(), tol);
        for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(forces.forces[k].z(), ref.normals(k), tol) << k;
        EXPECT_NEAR(forces.angular_acceleration.z(), ref.beta, kPivotForceTolerance * g);
      } else {
        EXPECT_EQ(forces.modes[0], ContactMode::slide) << "μ = " << mu << " below μ* = " << threshold;
        EXPECT_NEAR(forces.forces[0].head<2>().norm(), mu * forces.forces[0].z(),
                    kPivotForceTolerance * mass * g);
      }
    }
  }
}

// The start of the slip in any units (dimensional analysis, an answer independent of the code): a time unit
// k^(-1/2) times the second's scales g by k and the spin by k^(1/2), lengths and the mass unchanged; the
// motion is the same, so the forces scale by k, the slip's direction not at all. Below μ* the pivot starts
// to slide in a direction found by solving for it; a "no slip acceleration" test that is not relative to g
// takes any direction as the answer where g is small (k = 1e-8) and none where it is large (k = 1e8).
TEST(FaceStickThreshold, TheStartOfTheSlipIsTheSameInAnyUnits) {
  const double omega = 4, g = repose::test::kGravitySI;
  const TurningTetrahedron tet;
  const double mu = 0.98 * tet.threshold(g, omega);
  const auto forces_at = [&](double k) {
    const Motion motion = tet.motion(omega * std::sqrt(k));
    const ContactBody body{tet.mass, tet.particle.mass.inertia, k * g, 0.0};
    return sliding_face(body, motion, tet.arm_list(), mu, tet.conditions(motion));
  };
  const std::optional<ContactForces> si = forces_at(1);
  ASSERT_TRUE(si.has_value());
  ASSERT_EQ(si->modes[0], ContactMode::slide);
  for (const double k : {1e-8, 1e8}) {
    const std::optional<ContactForces> scaled = forces_at(k);
    ASSERT_TRUE(scaled.has_value()) << "k = " << k;
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(scaled->modes[i], si->modes[i]) << "k = " << k << ", point " << i;
      // Both solves to round-off (condition numbers below 1e3, as above): 1e-9 of m·g.
      EXPECT_LT((scaled->forces[i] / k - si->forces[i]).norm(), kPivotForceTolerance * tet.mass * g)
          << "k = " << k << ", point " << i;
    }
  }
}

}  // namespace
}  // namespace repose::sim
