// Zeno's capture at the return (frictional_impulses.cpp, resolve_impacts): a rebound E·u that the point's
// normal acceleration a_n turns back within the band, (E·u)² ≤ 2·|a_n|·band, is plastic. A cube landing flat
// on its face from rest at height h has a_n = −g at every corner and strikes at u = sqrt(2·g·h): its rebound
// would rise E²·h, so it is captured at once iff E²·h ≤ band. Just above, one rebound flies (free flight:
// it returns at the speed it left with, E·u) and the next, rising E⁴·h ≤ band, is captured.
#include <gtest/gtest.h>

#include <cmath>
#include <repose/model/particle.hpp>

#include "../../../src/sim/engine.hpp"

namespace repose::sim {
namespace {

SettleResult flat_landing(const Particle& cube, double rise_in_bands, double e) {
  SettleParams p;
  p.friction = 0.5;
  p.restitution = e;
  const double band = tol::kFrictionalBand * cube.length;
  p.drop_height = rise_in_bands * band / (e * e);  // the first rebound would rise rise_in_bands·band
  Engine engine(cube, p, Quat::Identity());
  while (engine.step()) {
  }
  return engine.result();
}

TEST(ZenoCapture, AFlatLandingsReboundIsCapturedIffItWouldRiseWithinTheBand) {
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1000.0);
  const double e = 0.5, g = SettleParams{}.gravity, band = tol::kFrictionalBand * cube.length;
  // E²·h = 0.8·band: captured at the first impact (the factor 2 of the rule, a rise of (E·u)²/(2g)).
  const SettleResult below = flat_landing(cube, 0.8, e);
  ASSERT_EQ(below.status, Status::rest);
  ASSERT_TRUE(below.frictional);
  EXPECT_EQ(below.impacts.size(), 1u);
  EXPECT_EQ(below.frictional->zeno_captures, 1);
  // E²·h = 1.25·band: the first rebound flies, its return is captured (E⁴·h = 0.31·band).
  const SettleResult above = flat_landing(cube, 1.25, e);
  ASSERT_EQ(above.status, Status::rest);
  ASSERT_EQ(above.impacts.size(), 2u);
  EXPECT_EQ(above.frictional->zeno_captures, 1);
  const double u = std::sqrt(2 * g * 1.25 * band / (e * e));
  // Each corner's speed at the first impact and at the return (free flight: the speed it left with, E·u);
  // the touch is located to 2^-44 of a step, the speeds to 1e-6 of u.
  EXPECT_NEAR(-above.impacts[0].normal_speed_before, u, 1e-6 * u);
  EXPECT_NEAR(-above.impacts[1].normal_speed_before, e * u, 1e-6 * u);
}

}  // namespace
}  // namespace repose::sim
