// The automatic time limit (SettleParams::max_time = 0, docs/method.md "Termination"): 2000·sqrt(L/g) for
// the settling, plus the flight before it. For a toss thrown up at u from height h the flight to the wall is
// the ballistic closed form (u + sqrt(u² + 2·g·h))/g, and its bounces with restitution E take at most
// (1 + E)/(1 − E) times that (a ball's series: each rebound flies E times as long as the one before, twice).
// White box: the limit is read from the engine's tolerances (sim::Run::tol).
#include <gtest/gtest.h>

#include <cmath>
#include <repose/model/particle.hpp>
#include <repose/poses/sampling.hpp>

#include "../../src/sim/engine.hpp"

namespace repose {
namespace {

TEST(TimeLimit, AnUpwardTossGetsItsBallisticFlightAndItsBouncesOnTopOfTheSettlingAllowance) {
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1.0);
  for (const double e : {0.0, 0.5, 0.9}) {
    for (const double h : {0.0, 0.3, 20.0}) {
      SettleParams p;
      p.gravity = 981.0;
      p.restitution = e;
      p.drop_height = h * cube.length;
      const double tau = std::sqrt(cube.length / p.gravity);
      const double u = 3 * std::sqrt(p.gravity * cube.length);
      p.velocity = Vec3(0.2 * u, 0, u);
      const sim::Engine engine(cube, p, drop_orientation(1, 0));
      const double flight = (u + std::sqrt(u * u + 2 * p.gravity * p.drop_height)) / p.gravity;
      const double expected = 2000 * tau + flight * (1 + e) / (1 - e);
      EXPECT_NEAR(engine.run().tol.max_time, expected, 1e-12 * expected) << "E " << e << " h " << h;
    }
  }
}

}  // namespace
}  // namespace repose
