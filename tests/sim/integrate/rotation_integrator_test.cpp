// The adaptive integrator on its own (src/sim/integrate/rotation_integrator.hpp) against a closed form: a
// free axisymmetric top. With the support at the centre of mass the weight has no moment, so the motion is
// torque free: for inertia diag(I1, I1, I3), R(t) = Rot(L̂, |L|·t/I1) · R0 · Rot(e3, L3·(1/I3 − 1/I1)·t), with
// L the (constant) angular momentum and L3 its body-axis-3 component (the classical precession and spin).
#include "../../../src/sim/integrate/rotation_integrator.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace repose::sim {
namespace {

TEST(RotationIntegrator, FreeSymmetricTopFollowsTheClosedForm) {
  const double i1 = 2.0, i3 = 0.5, length = 1.0;
  Body body{1.0, Vec3(i1, i1, i3).asDiagonal(), 9.81, 0.0};
  Support support;  // at the centre of mass: world = body = 0, a point
  const Quat q0 = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())).normalized();
  const Vec3 momentum(0.3, -1.1, 2.0);  // world frame (kg·m²/s)
  Rotation start{q0, Vec3::Zero(), momentum};
  const double tau = std::sqrt(length / body.gravity);
  RotationIntegrator integrator(body, length, 1e-11, 0.05 * tau);
  integrator.start(support, start, 0.0, 1e-3 * tau);

  const double l3 = (q0.conjugate() * momentum).z();
  const double precession = momentum.norm() / i1, spin = l3 * (1 / i3 - 1 / i1);
  auto exact = [&](double t) {
    return Quat(Eigen::AngleAxisd(precession * t, momentum.normalized())) * q0 *
           Quat(Eigen::AngleAxisd(spin * t, Vec3::UnitZ()));
  };
  // Compared at the middle and the end of every step for 2 s (a third of a turn of precession, 128 steps).
  // Measured largest angle between the integrated and the exact orientation 3.3e-11 rad; tolerance 3e-10. The
  // energy ½·ω·L = |L|²/(2·I1) + L3²·(1/I3 − 1/I1)/2 depends only on L3, which errors of spin or precession
  // leave alone: measured equal to round-off; tolerance 1e-13.
  const double energy0 = 0.5 * integrator.state_at(0.0).omega.dot(momentum);
  double worst_angle = 0, worst_energy = 0;
  int steps = 0;
  while (integrator.time() < 2.0 && steps < 100000) {
    const auto [t0, t1] = integrator.step();
    ++steps;
    for (double t : {0.5 * (t0 + t1), t1}) {
      const Rotation r = integrator.state_at(t);
      EXPECT_NEAR(r.q.norm(), 1.0, 1e-15);
      worst_angle = std::max(worst_angle, r.q.angularDistance(exact(t)));
      EXPECT_NEAR((r.momentum - momentum).norm(), 0.0, 1e-14 * momentum.norm());  // no torque: L constant
      worst_energy = std::max(worst_energy, std::abs(0.5 * r.omega.dot(r.momentum) - energy0) / energy0);
    }
  }
  std::printf("%d steps: largest angle error %.3g rad, energy error %.3g\n", steps, worst_angle,
              worst_energy);
  EXPECT_GT(steps, 10);
  EXPECT_LT(worst_angle, 3e-10);
  EXPECT_LT(worst_energy, 1e-13);
}

}  // namespace
}  // namespace repose::sim
