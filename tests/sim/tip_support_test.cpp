// After the tip-off rule turns a balanced body off a face whose stability margin is 0 (docs/method.md, "An
// edge balance is not a rest"), the body turns about the boundary edge it was tipped over: its support is
// that edge, a line of two touching vertices along the edge's direction, from the tip on (the geometry is
// the reference: the zero-margin prism's edge B, along body y, stays on the wall until the face BC lands).
// White box: sim::Engine driven step by step.
#include <gtest/gtest.h>

#include <cmath>

#include "../../src/sim/engine.hpp"
#include "../support/zero_margin_prism.hpp"

namespace repose {
namespace {

TEST(TipSupport, AfterTheTipThePrismTurnsAboutItsEdge) {
  const Particle prism = test_shapes::zero_margin_prism();
  sim::Engine engine(prism, SettleParams{}, Quat::Identity());
  int turning_steps = 0;
  for (int step = 0; step < 1000 && engine.status() == Status::running; ++step) {
    engine.step();
    const auto* contact = std::get_if<sim::Contact>(&engine.phase());
    if (contact == nullptr || engine.status() != Status::running || engine.run().t == 0) continue;
    const sim::Support& s = contact->support();
    ++turning_steps;
    EXPECT_TRUE(s.line) << "step " << step << ", t = " << engine.run().t;
    EXPECT_NEAR(std::abs(s.axis.dot(engine.run().q * Vec3::UnitY())), 1, 1e-9) << "step " << step;
  }
  EXPECT_EQ(engine.status(), Status::rest);
  EXPECT_GT(turning_steps, 0);
}

}  // namespace
}  // namespace repose
