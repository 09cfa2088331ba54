// The adaptive integrator against the paper's fixed step at a small step (issue 12, "Convergence"): the two
// integrate the same equations with the same contact decisions, so at dt → 0 the paper's scheme must land on
// the same rest face as the adaptive one, after the same time. This is what found an adaptive-only bug (a
// point leaving the ε band counted as one entering it, which changed the choice of support on grains).
// bench/convergence.cpp runs the same comparison on 100s of drops (docs/performance.md).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <repose/model/orientation.hpp>
#include <repose/model/particle.hpp>
#include <repose/poses/sampling.hpp>
#include <repose/sim/settle.hpp>
#include <string>
#include <vector>

namespace repose {
namespace {

// Whether drop `q` is ill-conditioned at `angle` (rad): a start turned by `angle` about ±x, ±y or ±z rests on
// another face than `face`, or after a time more than 1e-3 (relative) away from `time`. Two faithful
// integrations of such a drop may legitimately disagree by that much: on grains the time to rest jumps where
// a contact decision flips (a point a hair inside or outside the touching tolerance when another point
// reaches the band), as the rest face does at a balance.
bool ill_conditioned(const Particle& particle, const SettleParams& params, const Quat& q, int face,
                     double time, double angle) {
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0}) {
      const Quat turn(Eigen::AngleAxisd(sign * angle, Vec3::Unit(axis)));
      const SettleResult r = settle(particle, params, (turn * q).normalized());
      if (r.rest_face != face || std::abs(r.time - time) > 1e-3 * time) return true;
    }
  return false;
}

// Settles drops 0 .. n-1 of `seed` with both parameter sets (damping ratio 0.05 as `repose poses`; `vary`
// turns the first set into the second) and checks that every drop rests on the same face after times within
// `tolerance` of each other (relative), unless the drop is ill-conditioned at 1e-6 rad (above: issue 12's
// "within 1e-6 rad of a balance", for the time as for the face). Prints the largest difference and the drops
// excused.
void expect_same_runs(const char* spec, std::uint64_t seed, int n, double tolerance,
                      const std::function<void(SettleParams&, double tau)>& vary) {
  const Particle particle = load_particle(spec, 1000.0);
  SettleParams a_params;
  a_params.damping = 0.05 * particle.mass.mass * std::sqrt(a_params.gravity * std::pow(particle.length, 3));
  SettleParams b_params = a_params;
  vary(b_params, std::sqrt(particle.length / b_params.gravity));
  double worst = 0, worst_stable = 0;
  int excused = 0;
  for (int i = 0; i < n; ++i) {
    const Quat q = drop_orientation(seed, static_cast<std::uint64_t>(i));
    const SettleResult a = settle(particle, a_params, q);
    const SettleResult b = settle(particle, b_params, q);
    ASSERT_EQ(a.status, Status::rest) << spec << " drop " << i;
    ASSERT_EQ(b.status, Status::rest) << spec << " drop " << i;
    // The time to rest, and where the paper's own run ends (its stability test passing, a located decision).
    const double rel = std::abs(a.time - b.time) / b.time;
    const double rel_stable = std::abs(a.stable_time - b.stable_time) / b.time;
    if (a.rest_face == b.rest_face && rel < tolerance && rel_stable < tolerance) {
      worst = std::max(worst, rel);
      worst_stable = std::max(worst_stable, rel_stable);
      continue;
    }
    const bool excuse = ill_conditioned(particle, a_params, q, a.rest_face, a.time, 1e-6);
    excused += excuse;
    EXPECT_TRUE(excuse) << spec << " drop " << i << " (" << format_orientation(q) << "): faces "
                        << a.rest_face << ", " << b.rest_face << ", times " << a.time << ", " << b.time
                        << ", stable at " << a.stable_time << ", " << b.stable_time
                        << ", well-conditioned at 1e-6 rad";
  }
  std::printf(
      "%s: largest relative difference of the time to rest %.3g, of the paper's end (× the time to rest) "
      "%.3g; "
      "%d ill-conditioned drops excused\n",
      spec, worst, worst_stable, excused);
}

// 20 drops of seed 1 per shape (uniform random orientations, from rest), damping ratio 0.05 as `repose
// poses`; the paper's scheme at dt = 2e-4·sqrt(L/g). Every drop must land on the same face. The time to rest
// differs by the paper's step error: its integration is second order (measured ≤ 1.3e-8 of the time on the
// box, tetrahedron and cylinder), but its contact decisions (the contact type, the stability test, a line's
// support, the axis a surface contact turns about) are taken at step ends, up to one step late, so on grains
// that make many such decisions it converges at first order: measured ≤ 3.1e-4 at this step, and on a grain
// drop 0.7731490, 0.7732096, 0.7732499, 0.7732580 s at dt = 1e-4, 3e-5, 1e-5, 3e-6 s against the adaptive
// 0.7732638 s. Tolerance 1e-3 (issue 12's bound). A start within ~1e-6 rad of a balance could legitimately go
// either way; none of these drops does.
TEST(Convergence, AdaptiveAndSmallStepPaperSchemeAgreeDropByDrop) {
  for (const char* spec : {"box:x=1,y=2,z=3", "tetrahedron:edge=1", "cylinder:r=0.5,h=1,n=16",
                           "irregular:seed=1,n=4", "irregular:seed=7,n=4"})
    expect_same_runs(spec, 1, 20, 1e-3, [](SettleParams& p, double tau) {
      p.integrator = Integrator::paper;
      p.dt = 2e-4 * tau;
    });
}

// Drops of seed 1 of `spec` (damping ratio 0.05, as `repose poses`) settled by the adaptive integrator and by
// the paper's fixed step at dt = dt_factor·τ: the same face and the time to rest within 1e-3 (issue 12's
// bound: the paper's decisions lag by up to a step).
void expect_paper_step_agrees(const char* spec, double dt_factor, const std::vector<std::uint64_t>& drops) {
  const Particle grain = load_particle(spec, 1000.0);
  SettleParams adaptive;
  adaptive.damping = 0.05 * grain.mass.mass * std::sqrt(adaptive.gravity * std::pow(grain.length, 3));
  SettleParams paper = adaptive;
  paper.integrator = Integrator::paper;
  paper.dt = dt_factor * std::sqrt(grain.length / paper.gravity);
  for (std::uint64_t drop : drops) {
    const Quat q = drop_orientation(1, drop);
    const SettleResult a = settle(grain, adaptive, q), b = settle(grain, paper, q);
    ASSERT_EQ(b.status, Status::rest) << spec << " drop " << drop;
    EXPECT_EQ(a.rest_face, b.rest_face) << spec << " drop " << drop;
    EXPECT_NEAR(a.time, b.time, 1e-3 * b.time) << spec << " drop " << drop;
    std::printf("%s drop %d: faces %d, %d; times %.9g (adaptive), %.9g (paper)\n", spec,
                static_cast<int>(drop), a.rest_face, b.rest_face, a.time, b.time);
  }
}

// After the stability test has passed, the adaptive run's decisions read the contact set at each instant
// (band crossings are not events then), and its membership must be the contact update's: within ε + the
// touching tolerance (1e-9·L) of the wall, not ε alone. Drops 6 and 73 of seed 1 of this grain have a vertex
// that stays in that 1e-9·L sliver while the particle turns onto its face; with membership at ε alone they
// rest on faces 99 and 79 instead of 131 and 84. The paper's scheme at dt = 1e-5·τ is the reference: faces
// 131 and 84; its times 1.52136564 and 1.90976376 s (1.90294, 1.90861 at 1e-4, 2.5e-5·τ: first order,
// towards the adaptive run's 1.52136169 and 1.91053). Measured: 2.6e-6 and 4.0e-4 relative; bound 1e-3 as
// above (the paper's decisions lag by up to a step).
TEST(Convergence, TheDecisionsCountTheContactSetAsTheUpdateDoes) {
#ifdef NDEBUG
  expect_paper_step_agrees("irregular:seed=3,n=5", 1e-5, {6, 73});
#else
  // The sanitizer build (~200x slower): drop 6 alone, at dt = 1e-4·τ, where its paper run already agrees
  // (1.52138176 s, 1.3e-5 relative); drop 73's paper run lags by 4e-3 there.
  expect_paper_step_agrees("irregular:seed=3,n=5", 1e-4, {6});
#endif
}

// Every contact decision of the adaptive integrator is an event located on its dense output, so its result
// cannot depend on how long its steps are allowed to be: the default longest step 0.2·τ and one 200× shorter
// must give the same run. A decision taken only at step ends (not located) would make the time to rest move
// by up to a step: this test found three (a touching point lifting off, the contact set changing after the
// stability test has passed, a support chosen from several touching points whose motion then lifts one of
// them). 15 drops of seed 2 per shape, damping ratio 0.05. Measured: the same face everywhere, the largest
// relative difference of the time to rest 8.9e-9 (the integrator's tolerance is 1e-9 per step, over ~50 steps
// of the longer cap); bound 1e-7.
// One drop of the last grain is excused: it chatters between a point and a line support (a point entering
// the band and leaving it again 0.3 µs later, every 2.5 ms) with the centre of mass nearly over the line,
// until one run takes the line and the other does not; turned by 1e-6 rad it rests elsewhere.
TEST(Convergence, TheAdaptiveRunDoesNotDependOnItsLongestStep) {
  for (const char* spec : {"box:x=1,y=2,z=3", "tetrahedron:edge=1", "irregular:seed=1,n=4",
                           "irregular:seed=7,n=4", "irregular:seed=3,n=3"})
    expect_same_runs(spec, 2, 15, 1e-7, [](SettleParams& p, double tau) { p.dt = 1e-3 * tau; });
}

// The stability test can pass for less than the spacing of the decision checks inside a step (a few ms on a
// grain turning fast): found by the margin's Lipschitz bound (brief_stability_pass), where the paper's run
// ends must not depend on the longest step either. Drops 73, 77, 78 of seed 2 of this grain passed it for a
// moment that the checks at the default step missed: the paper's end came 0.06, 0.41 and 0.16 s later than
// at a 200× shorter step. Measured now: relative differences ≤ 3.5e-9; bound 1e-7 as above.
TEST(Convergence, ABriefPassOfTheStabilityTestIsFound) {
  const Particle grain = load_particle("irregular:seed=7,n=4", 1000.0);
  SettleParams coarse;
  coarse.damping = 0.05 * grain.mass.mass * std::sqrt(coarse.gravity * std::pow(grain.length, 3));
  SettleParams fine = coarse;
  fine.dt = 1e-3 * std::sqrt(grain.length / fine.gravity);
  for (std::uint64_t drop : {73, 77, 78}) {
    const Quat q = drop_orientation(2, drop);
    const SettleResult a = settle(grain, coarse, q), b = settle(grain, fine, q);
    ASSERT_GT(b.stable_time, 0) << "drop " << drop;
    std::printf("drop %d: the paper's end %.12g, %.12g\n", static_cast<int>(drop), a.stable_time,
                b.stable_time);
    EXPECT_NEAR(a.stable_time, b.stable_time, 1e-7 * b.stable_time) << "drop " << drop;
    EXPECT_NEAR(a.time, b.time, 1e-7 * b.time) << "drop " << drop;
  }
}

// A vertex that comes within the contact set's margin above the band (ε < z ≤ ε + 1e-9·L) without entering it
// joins the set only at an entry event: the paper's step used to take it in whenever one of its step ends
// fell while it hovered there, so its run depended on where its steps ended, and at dt = 1e-5·τ drops 97 and
// 161 of seed 1 of this grain came to rest 12 % and 103 % later than the adaptive run (0.827 and 2.460 s
// against 0.734 and 1.213; docs/performance.md, "Convergence"). Measured now: 2.2e-9 and 2.0e-5 relative;
// bound 1e-3, issue 12's. The sanitizer build (~200× slower) runs drop 97 at dt = 2e-4·τ, where both rules
// agree (to 1.0e-8): a check of the same comparison, not of the rule.
TEST(Convergence, AVertexHoveringAboveTheBandJoinsOnlyByEnteringIt) {
#ifdef NDEBUG
  expect_paper_step_agrees("irregular:seed=1,n=4", 1e-5, {97, 161});
#else
  expect_paper_step_agrees("irregular:seed=1,n=4", 2e-4, {97});
#endif
}

// Nor on its tolerance, down to 1e-13: at the default 1e-9 the steps are placed elsewhere, so a contact
// decision that is not located (the contact set changing once the stability test has passed, say) shows up
// as a different time to rest. 20 drops of seed 1 of a grain whose drop 17 did so; damping ratio 0.05.
// Measured: the largest relative difference of the time to rest 4.5e-8 (over 200 drops of this grain 1.2e-5:
// the integration error grows near balances); bound 1e-3, issue 12's. Without the decision this drop's time
// moves by 1.1e-2.
TEST(Convergence, TheAdaptiveRunDoesNotDependOnItsTolerance) {
  expect_same_runs("irregular:seed=7,n=6", 1, 20, 1e-3, [](SettleParams& p, double) { p.tolerance = 1e-13; });
}

}  // namespace
}  // namespace repose
