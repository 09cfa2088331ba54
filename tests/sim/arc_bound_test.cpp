// The adaptive contact steps' arc bound (src/sim/phases/contact_adaptive_step.cpp, Contact::arc_bound) is a
// claim from energy: in time h the particle turns about its support by at most sqrt(a)·h + b·h²/4 rad
// (a = 2·K₀/I_min, b = 2·m·g·r_c/I_min). Which vertices are checked for events inside a step, and whether a
// step is checked for a change of the contact decisions, rest on it. The oracle is the motion itself: the
// angle between the orientations at a step's two ends, which the path's angle (the bound's subject) is at
// least. White box: sim::Engine is driven step by step through real drops. The bound is dimensionless in
// its units (h in units of sqrt(L/g)), so it is checked at sizes where a step lasts well under and well
// over one second (a wrong power of h shows only on one side of h = 1 s).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <repose/model/particle.hpp>
#include <repose/poses/sampling.hpp>
#include <string>
#include <vector>

#include "../../src/sim/engine.hpp"

namespace repose {
namespace {

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

struct Count {
  long steps = 0;
  double longest = 0;   // the longest step checked (s)
  double tightest = 0;  // the largest angle / bound seen
};

// Every adaptive contact step that starts and ends about the support of the step before it (a changed
// support restarts the integrator with that support's moments, so the bound is checked from the second
// step about a support on): the angle turned is within the bound evaluated at the step's start.
void check_drops(const std::string& spec, int drops, Count& count) {
  const Particle particle = load_particle(spec, 1000.0);
  SettleParams params;
  params.integrator = Integrator::adaptive;
  params.damping = 0.05 * particle.mass.mass * std::sqrt(params.gravity * std::pow(particle.length, 3));
  params.drop_height = 0.3 * particle.length;
  for (int drop = 0; drop < drops; ++drop) {
    sim::Engine engine(particle, params, drop_orientation(3, static_cast<std::uint64_t>(drop)));
    const sim::Run& run = engine.run();
    const double longest = 2 * run.tol.dt;
    bool settled_support = false;  // the step before ran about the current support
    for (int step = 0; step < 20000 && engine.status() == Status::running; ++step) {
      auto* before = std::get_if<sim::Contact>(&engine.phase());
      if (before == nullptr || before->inside_step()) {
        engine.step();
        settled_support = false;
        continue;
      }
      // The bound at the step's start, at lengths h_i = longest·2^(-i/64): the step's own length is not
      // known before it is taken, and the bound grows with h, so h_i just above it is used.
      std::vector<double> bound;
      for (int i = 0; i < 64 * 40; ++i) bound.push_back(before->arc_bound(longest * std::exp2(-i / 64.0)));
      const sim::Support support = before->support();
      const Quat q0 = run.q;
      const double t0 = run.t;
      const bool checked = settled_support;
      engine.step();
      auto* after = std::get_if<sim::Contact>(&engine.phase());
      const bool same = after != nullptr && after->support().body == support.body &&
                        after->support().line == support.line &&
                        (!support.line || after->support().axis == support.axis);
      settled_support = same;
      if (!checked || after == nullptr) continue;
      const double h = run.t - t0;
      if (!(h > 0)) continue;
      const int i = static_cast<int>(std::floor(-64 * std::log2(h / longest)));
      ASSERT_GE(i, 0) << spec << " drop " << drop << ": a step of " << h << " s";
      if (i >= static_cast<int>(bound.size())) continue;
      const double angle = q0.angularDistance(run.q);
      ++count.steps;
      count.longest = std::max(count.longest, h);
      count.tightest = std::max(count.tightest, angle / bound[static_cast<std::size_t>(i)]);
      EXPECT_LE(angle, bound[static_cast<std::size_t>(i)] * (1 + 1e-9))
          << spec << " drop " << drop << " t " << t0 << ": turned " << angle << " rad in " << h
          << " s, bound " << bound[static_cast<std::size_t>(i)];
      if (::testing::Test::HasFailure()) return;
    }
  }
}

TEST(ArcBound, NoAdaptiveStepTurnsTheParticleFartherThanItsEnergyBound) {
  for (double s : {1.0, 1e4}) {
    Count count;
    for (const std::string& spec :
         {"box:x=" + num(s) + ",y=" + num(2 * s) + ",z=" + num(3 * s), "tetrahedron:edge=" + num(s),
          "cylinder:r=" + num(0.5 * s) + ",h=" + num(0.8 * s) + ",n=16"})
      check_drops(spec, 4, count);
    std::printf("size %g: %ld steps checked, the longest %.3g s, largest angle / bound %.3f\n", s,
                count.steps, count.longest, count.tightest);
    EXPECT_GT(count.steps, 100);
    if (s > 1) {
      EXPECT_GT(count.longest, 1.0);  // steps over a second: the bound's h² term is exercised
    }
  }
}

}  // namespace
}  // namespace repose
