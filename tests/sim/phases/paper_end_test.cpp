// Where the paper's own run ends: the first instant its stability test (§2.4) passes, reported as
// SettleResult::stable_time, against the closed form of a cube tipping off its edge.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../../support/pendulum.hpp"
#include "gravity.hpp"
#include "repose/model/particle.hpp"
#include "repose/sim/settle.hpp"

namespace repose {
namespace {

class PaperEnd : public ::testing::TestWithParam<Integrator> {};

// A unit cube on its edge (along x), tilted δ past the 45° balance, undamped, tips about the edge as an
// inverted pendulum (d = √2/2, I = 2m/3) onto its −y face. Until the face's far edge comes within ε·L of the
// wall only the two pivot vertices are contacts (the paper's tests need three); then the four vertices of
// the face are, the downward ray from the centre of mass hits that face, and the test passes: the face is
// then at θ = asin(ε·L) from the wall (edge 1), the centre of mass tilted φ = π/4 − θ from the vertical.
// The time is the pendulum's quadrature from δ to that φ. Measured relative error (δ = 1e-3 and 0.2):
// adaptive 4.8e-8 and 5.3e-8, paper 7.9e-8 and 4.1e-8, the same as of the landing time; tolerance 5e-7,
// 6× the largest. (The band's 1e-9·L margin moves the time by ~1e-9 relative.)
TEST_P(PaperEnd, CubeTippingOffItsEdgeIsStableWhenItsFaceEntersTheBand) {
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1.0);
  SettleParams params;
  params.integrator = GetParam();
  const double d = std::numbers::sqrt2 / 2, inertia = 2.0 / 3.0;  // per unit mass
  for (double delta : {1e-3, 0.2}) {
    const Quat q(Eigen::AngleAxisd(std::numbers::pi / 4 + delta, Vec3::UnitX()));
    const SettleResult r = settle(cube, params, q);
    ASSERT_EQ(r.status, Status::rest);
    const double theta = std::asin(params.contact_threshold * cube.length);
    const double expected =
        pendulum::undamped_tip_time(inertia, test::kGravitySI * d, delta, std::numbers::pi / 4 - theta);
    const double tol = 5e-7;
    EXPECT_NEAR(r.stable_time, expected, tol * expected) << "delta " << delta;
    // The paper stops there; repose finishes the rotation onto the face, later.
    const double landing =
        pendulum::undamped_tip_time(inertia, test::kGravitySI * d, delta, std::numbers::pi / 4);
    EXPECT_NEAR(r.time, landing, tol * landing) << "delta " << delta;
  }
}

// A cube placed flat rests at once, and the paper's test passes at once too: its end is t = 0, not "never".
TEST_P(PaperEnd, AFlatStartIsStableAtOnce) {
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1.0);
  SettleParams params;
  params.integrator = GetParam();
  const SettleResult r = settle(cube, params, Quat::Identity());
  EXPECT_EQ(r.status, Status::rest);
  EXPECT_EQ(r.time, 0);
  EXPECT_EQ(r.stable_time, 0);
}

// A smooth particle rests by its own rule (three points landed around the centre of mass): the paper's test
// is not run, so there is no paper end to report.
TEST_P(PaperEnd, SmoothParticlesReportNone) {
  const Particle sphere = load_particle("ellipsoid:a=1,b=0.8,c=0.6,n=6", 1.0);
  ASSERT_TRUE(is_smooth_surface(sphere));
  SettleParams params;
  params.integrator = GetParam();
  params.damping = 0.5;
  const SettleResult r = settle(sphere, params, Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 0).normalized())));
  EXPECT_EQ(r.status, Status::rest);
  EXPECT_EQ(r.stable_time, -1);
}

INSTANTIATE_TEST_SUITE_P(Integrators, PaperEnd, ::testing::Values(Integrator::paper, Integrator::adaptive),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace repose
