// The damping moment of Eq 4 (−C·ω) against closed forms. A box tipping about a bottom edge is an inverted
// pendulum I·φ'' + C·φ' = m·g·d·sin φ (φ: tilt of the centre of mass from the vertical through the edge), so
// damping shows in the rate at which it leaves its balance and in the energy it removes. Units are CGS:
// cm, g, s, g = 981 cm/s²; box 1 × 2 × 3 cm of density 1 g/cm³ (m = 6 g).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <repose/model/particle.hpp>
#include <repose/sim/settle.hpp>
#include <vector>

#include "../support/pendulum.hpp"
#include "gravity.hpp"

namespace repose {
namespace {

// Box 1 × 2 × 3 tilted about x by θ pivots on its edge at body (·, −1, −1.5): the centre of mass is
// d = sqrt(1 + 1.5²) from it and above it at θc = atan(1/1.5). Closed forms (m = 6): I about the edge =
// m·(2² + 3²)/3 = 26 g·cm².
struct EdgePendulum {
  static constexpr double m = 6.0, inertia = 26.0;
  static double d() { return std::sqrt(1 + 1.5 * 1.5); }
  static double theta_c() { return std::atan(1.0 / 1.5); }
  static const Particle& box() {
    static const Particle p = load_particle("box:x=1,y=2,z=3", 1.0);
    return p;
  }
  static SettleParams params(double damping, Integrator integrator) {
    SettleParams p;
    p.gravity = test::kGravityCGS;
    p.damping = damping;
    p.integrator = integrator;
    return p;
  }
  static Quat tilt(double theta) { return Quat(Eigen::AngleAxisd(theta, Vec3::UnitX())); }
  // Damping of the same order as the pendulum's own rate: C/I = λ0 = sqrt(m·g·d/I), so λ = 0.618·λ0 and a
  // damping moment off by a factor of two moves λ by 20-25 %.
  static double damping() { return inertia * std::sqrt(m * test::kGravityCGS * d() / inertia); }
};

// Every test runs with both integrators: the paper's fixed step and the adaptive one.
class Damping : public ::testing::TestWithParam<Integrator> {
 protected:
  static SettleParams params(double damping) { return EdgePendulum::params(damping, GetParam()); }
  static bool paper() { return GetParam() == Integrator::paper; }
};

TEST_P(Damping, BoxLeavesItsEdgeBalanceAtTheDampedPendulumRate) {
  // Started from rest at tilts δ1 < δ2 past the balance, the two runs follow the same trajectory once the
  // decaying mode (rate −C/I − λ) has died, δ2/δ1 apart in amplitude: the first reaches every later state
  // ln(δ2/δ1)/λ after the second, with λ = (−C/I + sqrt((C/I)² + 4·m·g·d/I))/2. Both land on the 1 × 3 face.
  // Measured relative error of the time difference: paper 5.8e-8 (the trapezoidal rule's O(dt²) phase
  // error), adaptive 5.3e-9 (its local error bound 1e-9); tolerances 5e-7 and
  // 2e-8. A damping off by 1 %
  // moves λ by 0.45 %.
  const Particle& box = EdgePendulum::box();
  ASSERT_NEAR(box.mass.mass, EdgePendulum::m, 1e-12);
  const double C = EdgePendulum::damping();
  const double lambda = pendulum::escape_rate(EdgePendulum::inertia, C,
                                              EdgePendulum::m * test::kGravityCGS * EdgePendulum::d());
  const double d1 = 1e-6, d2 = 1e-4;
  const SettleResult r1 = settle(box, params(C), EdgePendulum::tilt(EdgePendulum::theta_c() + d1));
  const SettleResult r2 = settle(box, params(C), EdgePendulum::tilt(EdgePendulum::theta_c() + d2));
  for (const SettleResult* r : {&r1, &r2}) {
    ASSERT_EQ(r->status, Status::rest);
    EXPECT_LT((r->down_normal_body - Vec3(0, -1, 0)).norm(), 1e-9);
  }
  const double expected = std::log(d2 / d1) / lambda;
  std::cout << "time difference " << r1.time - r2.time << ", ln(100)/λ = " << expected << ", relative error "
            << (r1.time - r2.time - expected) / expected << "\n";
  EXPECT_NEAR(r1.time - r2.time, expected, (paper() ? 5e-7 : 2e-8) * expected);
}

TEST_P(Damping, EnergyLostEqualsTheWorkOfTheDampingMoment) {
  // Between impacts dE/dt = −C·|ω|² (the damping moment −C·ω against ω; about a line, its component along
  // the axis, where ω lies). Tipping about its edge from 0.05 rad past the balance to just before the 1 × 3
  // face lands, the box's energy drop E(0) − E(t) must equal ∫ C·ω² dt, here by the trapezoidal rule over
  // the samples. Energies computed in the test: ½·I·ω² with I = 26 about the edge, and m·g·z of the centre
  // of mass. The adaptive run is sampled every 1e-3·sqrt(L/g) (its dense output), as the paper's steps.
  // Measured largest mismatch: paper 8.5e-8 of the work, adaptive 1.5e-7 (the O(dt²) errors of the
  // integration and, for the adaptive run, mostly of this quadrature); tolerance 5e-7.
  const Particle& box = EdgePendulum::box();
  const double C = 0.5 * EdgePendulum::damping();
  std::vector<Sample> samples;
  const SettleResult r = settle(
      box, params(C), EdgePendulum::tilt(EdgePendulum::theta_c() + 0.05),
      [&](const Sample& s) { samples.push_back(s); }, default_sample_dt(box, params(C)));
  ASSERT_EQ(r.status, Status::rest);
  ASSERT_GT(samples.size(), 100u);
  auto energy = [&](const Sample& s) {
    return 0.5 * EdgePendulum::inertia * s.omega.squaredNorm() +
           EdgePendulum::m * test::kGravityCGS * s.com.z();
  };
  double work = 0, worst = 0;
  const double e0 = energy(samples.front());
  for (std::size_t i = 1; i + 1 < samples.size(); ++i) {  // the last sample is after the landing impact
    const Sample& a = samples[i - 1];
    const Sample& b = samples[i];
    // ω stays along the edge (world x): the rotation is about the fixed line.
    ASSERT_LT(std::hypot(b.omega.y(), b.omega.z()), 1e-12 * b.omega.norm() + 1e-300);
    work += 0.5 * (b.t - a.t) * C * (a.omega.squaredNorm() + b.omega.squaredNorm());
    worst = std::max(worst, std::abs(e0 - energy(b) - work));
  }
  std::cout << "damping work " << work << " erg of E0 " << e0 << "; largest mismatch " << worst / work
            << " of the work\n";
  EXPECT_LT(worst, 5e-7 * work);
  EXPECT_GT(work, 0.01 * e0);  // the damping did matter
}

TEST_P(Damping, HeavierDampingMakesTheSameFallSlowerAsThePendulumSays) {
  // The whole fall about the edge from 0.05 rad past the balance to the landing on the 1 × 3 face at
  // θ = π/2 (φ from 0.05 to π/2 − θc), undamped and damped, against a fine integration of the pendulum
  // equation written here (classical RK4, 2·10⁵ steps: its error is < 1e-10 relative, checked by halving).
  // Measured relative errors of the engine's landing time: paper 6.8e-8, 5.1e-8, 2.7e-9,
  // adaptive 1.1e-9, 8.0e-10, 4.1e-10 (the landing located on the dense output, a 4th-order interpolant);
  // tolerances 5e-7 and 1e-8.
  const Particle& box = EdgePendulum::box();
  const double mgd = EdgePendulum::m * test::kGravityCGS * EdgePendulum::d(), I = EdgePendulum::inertia;
  const double phi0 = 0.05, phi_land = std::numbers::pi / 2 - EdgePendulum::theta_c();
  for (double C : {0.0, 0.25 * EdgePendulum::damping(), EdgePendulum::damping()}) {
    // Time to reach phi_land: RK4 on (φ, φ') with the landing located by linear interpolation of the last
    // step.
    auto fall_time = [&](int steps) {
      const double h = 2.0 / steps;  // 2 s is beyond every landing here
      double phi = phi0, w = 0, t = 0;
      auto acc = [&](double p, double v) { return (mgd * std::sin(p) - C * v) / I; };
      for (int i = 0; i < steps; ++i) {
        const double k1p = w, k1w = acc(phi, w);
        const double k2p = w + h / 2 * k1w, k2w = acc(phi + h / 2 * k1p, w + h / 2 * k1w);
        const double k3p = w + h / 2 * k2w, k3w = acc(phi + h / 2 * k2p, w + h / 2 * k2w);
        const double k4p = w + h * k3w, k4w = acc(phi + h * k3p, w + h * k3w);
        const double next_phi = phi + h / 6 * (k1p + 2 * k2p + 2 * k3p + k4p);
        const double next_w = w + h / 6 * (k1w + 2 * k2w + 2 * k3w + k4w);
        if (next_phi >= phi_land) return t + h * (phi_land - phi) / (next_phi - phi);
        phi = next_phi;
        w = next_w;
        t += h;
      }
      return double(INFINITY);
    };
    const double reference = fall_time(200000);
    ASSERT_NEAR(reference, fall_time(400000), 1e-9 * reference);
    const SettleResult r = settle(box, params(C), EdgePendulum::tilt(EdgePendulum::theta_c() + phi0));
    ASSERT_EQ(r.status, Status::rest);
    std::cout << "C = " << C << ": time " << r.time << ", pendulum " << reference << ", relative error "
              << (r.time - reference) / reference << "\n";
    EXPECT_NEAR(r.time, reference, (paper() ? 5e-7 : 1e-8) * reference) << "C = " << C;
  }
}

INSTANTIATE_TEST_SUITE_P(Integrators, Damping, ::testing::Values(Integrator::paper, Integrator::adaptive),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace repose
