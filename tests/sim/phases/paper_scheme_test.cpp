// The paper's fixed-step scheme (Eqs 10-16): the pseudo-time iteration of its trapezoidal step and the count
// of steps whose iteration hit its bound.
#include <gtest/gtest.h>

#include "repose/model/orientation.hpp"
#include "repose/model/particle.hpp"
#include "repose/sim/settle.hpp"

namespace repose {
namespace {

SettleParams paper_params() {
  SettleParams p;
  p.gravity = 981.0;  // cgs
  p.integrator = Integrator::paper;
  return p;
}

// The count of steps whose pseudo-time iteration hit its bound (SettleResult::unconverged_steps): none at the
// defaults (the iteration converges in a few passes), and every rotation step with a bound of one pass (the
// iteration never stops before its second pass, docs/method.md). A cube tilted 0.3 rad on an edge, touching
// from rest: no fall, so every step is a rotation step.
TEST(PseudoTimeIteration, StepsThatHitTheIterationBoundAreCounted) {
  // The paper's integrator only: the adaptive one has no pseudo-time iteration.
  const Particle cube = load_particle("box:x=1,y=1,z=1", 2.0);
  SettleParams p = paper_params();
  const Quat tilt = parse_orientation("axis-angle:1,0,0,0.3");
  const SettleResult converged = settle(cube, p, tilt);
  ASSERT_EQ(converged.status, Status::rest);
  EXPECT_EQ(converged.unconverged_steps, 0);
  p.max_iterations = 1;
  const SettleResult bounded = settle(cube, p, tilt);
  EXPECT_GT(bounded.steps, 10);
  EXPECT_EQ(bounded.unconverged_steps, bounded.steps);
  // One pass is still taken (the bound counts passes from one): the cube falls back onto the same face.
  ASSERT_EQ(bounded.status, Status::rest);
  EXPECT_EQ(bounded.rest_face, converged.rest_face);
  // A single pass makes the step explicit in ω (first order): measured 6.9e-4 relative; bound 10×.
  EXPECT_NEAR(bounded.time, converged.time, 7e-3 * converged.time);
}

}  // namespace
}  // namespace repose
