// Issue 48's property sweep: random tosses of random convex polyhedra (4–60 vertices) with E in [0, 0.95],
// μ = 0 for a tenth and uniform in [0.05, 2] otherwise, up to sqrt(g·L) of velocity and 10·sqrt(g/L) of spin.
// Checked after every step of the engine, white-box:
//   - the mechanical energy never rises, beyond what the ledger's non-dissipative terms (the normal forces'
//     work on drifting points, the repositioning of drift undone) account for, by more than kRise;
//   - no point pressed on the wall pulls (N ≥ −kForce), none above the band carries a force, and friction's
//     power at each point is ≤ 0 beyond μ·N·2·slip_speed (a point at rest slips below 2·slip_speed by
//     definition);
//   - at the end: a status (every loop bounded), no vertex deeper than 1e-9·L, every impulse of the wall
//     pushing and in the friction cone, the ledger closed to 1e-6·m·g·L (issue 48's bound), and every
//     fallback counted, printed by kind.
// REPOSE_FRICTION_TOSSES sets the number (default 60 in optimised builds, 6 in debug and sanitizer builds),
// REPOSE_FRICTION_FIRST the first index, REPOSE_FRICTION_LIST=1 lists the tosses with a hand-over or a
// bounded round. Measured on dac2218: REPOSE_FRICTION_TOSSES=2000 (34 s): every property holds on 2,000 of
// 2,000; largest rise 1.2e-8·m·g·L, largest ledger residual 3.8e-7·m·g·L; fallbacks: 0 hand-overs stalled
// (3 on 514b6f0: Painlevé's dynamic jam), 16 timed out (16; every one μ = 0 without damping, a spinning
// top on a frictionless floor, docs/method.md), 1 bounded round (6: two corners trading impacts; toss
// 1237: a hold, a two-point impact without collision and an impact cycling), 94 pyramid forces (87),
// 0 unsolved, 0 unresolved. REPOSE_FRICTION_TOSSES=20000 on 41d5a2d: 19,999 of 20,000 held every property
// (toss 2914, μ = 0, closed its ledger to 1.0019e-6·m·g·L; 9.98e-7 on dac2218, the integrator's error over
// 200·τ), fallbacks 22 stalled, 149 timed out, 71 bounded rounds, 481 pyramid, 25 unsolved, 79 unresolved;
// on 0905eab (two halves of 10,000, 21 and 29 min): every property holds on all 20,000; largest rise
// 1.2e-8·m·g·L, residual ≤ 9.98e-7·m·g·L; 6 stalled (all μ > 1.68, each after 8–10 bounded rounds: a hold /
// impact without collision / impact cycle, the next cause to remove), 145 timed out (every one μ = 0),
// 61 bounded rounds, 487 pyramid, 24 unsolved, 80 unresolved; captures 825,902 Zeno, 3,070 Painlevé.
// Session 56, with Painlevé's jam leaving a pulled point free (the cause of that cycle): 2,000 tosses, every
// property holds, bounded rounds 0 (1), the rest unchanged; tosses 10,000–19,999 (REPOSE_FRICTION_FIRST=10000
// REPOSE_FRICTION_TOSSES=10000, 65 min under load): every property holds, largest rise 6.5e-9·m·g·L,
// residual ≤ 8.9e-7·m·g·L; stalled 0 (6 on 0905eab, all in this half), bounded rounds 1 (58; toss 13154,
// μ = 1.98), timed out 53 (53, every one μ = 0), pyramid 320 (320), unsolved 3 (3), unresolved 40 (40);
// tosses 0–9,999 on 63e18a4 (19 min): every property holds, residual ≤ 9.98e-7·m·g·L (toss 2914, μ = 0);
// stalled 0 (0), bounded rounds 0 (3), timed out 92 (92, every one μ = 0), pyramid 167 (167), unsolved 21
// (21), unresolved 41 (40). All 20,000: stalled 0 (6), bounded rounds 1 (61), timed out 145 (145), pyramid
// 487, unsolved 24, unresolved 81; captures 826,595 Zeno, 2,340 Painlevé.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <numbers>
#include <random>
#include <repose/model/particle.hpp>
#include <sstream>

#include "../../../src/sim/engine.hpp"

namespace repose::sim {
namespace {

#ifdef NDEBUG
constexpr long kDefaultTosses = 60;
#else
constexpr long kDefaultTosses = 6;
#endif
// The adaptive integrator's energy error per step is below 5.2 × its tolerance (1e-9) × m·g·L
// (tolerances.hpp, kEnergyErrorMargin): ten times that.
constexpr double kRise = 5e-8;
// Forces: round-off of the solvers, 1e-9 of m·g·(1 + μ).
constexpr double kForce = 1e-9;

struct Toss {
  Particle particle;
  SettleParams params;
  Quat orientation;
  std::string describe;
};

Toss make_toss(std::uint64_t index) {
  std::mt19937_64 rng(0x48'0000 + index);
  std::uniform_real_distribution<double> u(0, 1);
  const int count = 4 + static_cast<int>(57 * u(rng));
  const Vec3 axes(0.3 + u(rng), 0.3 + u(rng), 0.3 + u(rng));
  std::vector<Vec3> points;
  for (int k = 0; k < count; ++k)
    points.push_back(Vec3(2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1).cwiseProduct(axes));
  MeshOptions options;
  options.inertia = InertiaModel::convex;
  Toss t{make_particle(TriangleMesh{points, {}}, "random convex", 1000.0, options), {}, Quat::Identity(), ""};
  const double L = t.particle.length, g = t.params.gravity;
  const auto direction = [&] {
    Vec3 v;
    do v = Vec3(2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1);
    while (v.norm() > 1 || v.norm() < 1e-3);
    return Vec3(v.normalized());
  };
  t.orientation = Quat(Eigen::AngleAxisd(2 * std::numbers::pi * u(rng), direction()));
  t.params.drop_height = L * u(rng);
  t.params.velocity = std::sqrt(g * L) * u(rng) * direction();
  t.params.spin = 10 * std::sqrt(g / L) * u(rng) * direction();
  t.params.restitution = 0.95 * u(rng);
  t.params.friction = u(rng) < 0.1 ? 0.0 : 0.05 + 1.95 * u(rng);
  std::ostringstream d;
  d << "toss " << index << ": " << count << " points, E = " << t.params.restitution
    << ", μ = " << t.params.friction;
  t.describe = d.str();
  return t;
}

struct Totals {
  long stalled = 0, handovers = 0, bounded = 0, pyramids = 0, unsolved = 0, unresolved = 0, zeno = 0,
       painleve = 0;
  double worst_residual = 0, worst_rise = 0;
};

// The violations of one toss ("" if none).
std::string check_toss(const Toss& t, Totals& totals) {
  const double L = t.particle.length, m = t.particle.mass.mass, g = t.params.gravity;
  const double mgL = m * g * L, mu = t.params.friction;
  Engine engine(t.particle, t.params, t.orientation);
  const auto noncons = [&] {  // the ledger's terms that may add energy without being a rise
    const FrictionalAccount& a = engine.run().record.account;
    return a.normal_work + a.repositioning;
  };
  Sample before = engine.sample();
  double before_extra = noncons();
  std::ostringstream why;
  while (engine.step()) {
    const Sample now = engine.sample();
    const double extra = noncons();
    const double rise = (now.kinetic_energy + now.potential_energy) -
                        (before.kinetic_energy + before.potential_energy) - (extra - before_extra);
    totals.worst_rise = std::max(totals.worst_rise, rise / mgL);
    if (rise > kRise * mgL) why << " energy rose by " << rise / mgL << " m·g·L at t = " << now.t << ";";
    if (auto* c = std::get_if<FrictionalContact>(&engine.phase())) {
      for (const auto& p : c->point_forces()) {
        const double N = p.force.z(), scale = m * g * (1 + mu);
        if (N < -kForce * scale)
          why << " a point pulls (N = " << N / (m * g) << " m·g) at t = " << now.t << ";";
        // (at a lift-off the step ends where the point is at the band's edge, to the locator's resolution)
        if (N > kForce * scale && p.point.z() > (1 + 1e-6) * engine.run().tol.frictional_band)
          why << " a force on a point " << p.point.z() / L << "·L above the wall at t = " << now.t << ";";
        const double power = p.force.head<2>().dot(p.velocity.head<2>());
        if (power > mu * std::max(N, 0.0) * tol::kSlipHysteresis * engine.run().tol.slip_speed +
                        kForce * scale * engine.run().tol.speed)
          why << " friction's power " << power << " > 0 at t = " << now.t << " (N = " << N
              << ", |F_t| = " << p.force.head<2>().norm() << ", slip "
              << p.velocity.head<2>().norm() / engine.run().tol.slip_speed << " slip_speed, height "
              << p.point.z() / L << " L);";
      }
    }
    if (!why.str().empty()) break;
    before = now;
    before_extra = extra;
  }
  const SettleResult r = engine.result();
  if (r.status == Status::running) why << " still running;";
  if (r.max_penetration > 1e-9 * L) why << " depth " << r.max_penetration / L << "·L;";
  // Every impulse of the wall (impacts, Zeno's captures, Painlevé's impacts without collision) pushes and
  // stays in the cone: each point's does, so their sum does (the normal is the same at every point). The
  // tolerance is the solvers' round-off on impulses up to m·(1 + 10)·sqrt(g·L) (the toss's speed and spin).
  const double impulse_tol = kForce * (1 + mu) * 11 * m * std::sqrt(g * L);
  for (const ImpactRecord& i : r.impacts) {
    if (i.impulse.z() < -impulse_tol)
      why << " an impulse pulls (" << i.impulse.z() << ") at t = " << i.t << ";";
    if (std::isfinite(mu) && i.impulse.head<2>().norm() > mu * std::max(i.impulse.z(), 0.0) + impulse_tol)
      why << " an impulse outside the cone (|P_t| = " << i.impulse.head<2>().norm()
          << ", μ·P_n = " << mu * i.impulse.z() << ") at t = " << i.t << ";";
    // No impulse of the wall creates energy (Stronge's law dissipates; Painlevé's impacts without collision
    // are scaled back to their energy minimum): round-off of kinetic energies up to m·g·L·(1 + 10²).
    if (i.energy_after > i.energy_before + kForce * 101 * mgL)
      why << " an impulse added " << (i.energy_after - i.energy_before) / mgL << " m·g·L at t = " << i.t
          << ";";
  }
  if (r.frictional) {
    const FrictionalAccount& f = *r.frictional;
    double impacts = 0;
    for (const ImpactRecord& i : r.impacts) impacts += i.energy_before - i.energy_after;
    const double residual = r.energy_end - r.energy_start + impacts + r.friction_work + r.damping_work -
                            f.normal_work + f.stopping_losses + f.drift_corrections - f.repositioning +
                            f.rest_losses + f.paper_phase_losses + f.frictionless_motion;
    totals.worst_residual = std::max(totals.worst_residual, std::abs(residual) / mgL);
    if (std::abs(residual) > 1e-6 * mgL) why << " the ledger is off by " << residual / mgL << " m·g·L;";
    totals.stalled += f.handovers_stalled;
    totals.handovers += f.handovers_timed_out;
    if (std::getenv("REPOSE_FRICTION_LIST") &&
        f.handovers_stalled + f.handovers_timed_out + f.bounded_rounds > 0)
      std::cout << t.describe << ": hand-overs " << f.handovers_stalled << " stalled, "
                << f.handovers_timed_out << " timed out; bounded rounds " << f.bounded_rounds << "\n";
    totals.bounded += f.bounded_rounds;
    totals.pyramids += f.pyramid_forces;
    totals.unsolved += f.unsolved_forces;
    totals.unresolved += f.unresolved_forces;
    totals.zeno += f.zeno_captures;
    totals.painleve += r.painleve;
  }
  return why.str();
}

TEST(FrictionalProperty, RandomTossesOfRandomConvexPolyhedraKeepEveryInvariant) {
  const char* count_text = std::getenv("REPOSE_FRICTION_TOSSES");
  const char* first_text = std::getenv("REPOSE_FRICTION_FIRST");
  const long count = count_text && *count_text ? std::atol(count_text) : kDefaultTosses;
  const long first = first_text && *first_text ? std::atol(first_text) : 0;
  Totals totals;
  int failures = 0;
  for (long i = first; i < first + count; ++i) {
    const Toss t = make_toss(static_cast<std::uint64_t>(i));
    const std::string why = check_toss(t, totals);
    if (!why.empty() && ++failures <= 10) ADD_FAILURE() << t.describe << ":" << why;
  }
  std::cout << count << " tosses: largest rise " << totals.worst_rise << " m·g·L, largest ledger residual "
            << totals.worst_residual << " m·g·L; fallbacks: hand-overs stalled " << totals.stalled
            << ", timed out " << totals.handovers << ", bounded rounds " << totals.bounded
            << ", pyramid forces " << totals.pyramids << ", unsolved forces " << totals.unsolved
            << ", unresolved forces " << totals.unresolved << "; captures: Zeno " << totals.zeno
            << ", Painlevé " << totals.painleve << "\n";
  EXPECT_EQ(failures, 0) << " of " << count << " tosses broke a property";
}

// Painlevé's impacts without collision keep their impulses in the cone (issue 48: the cone taken as μ instead
// of μ times the normal impulse passed every other test). Two tosses of the sweep above whose impacts
// without collision project an impulse onto the cone with a normal impulse below 1 (found by planting that
// bug: these two failed among 2,000; re-found so for the error-controlled impact law, whose trajectories
// differ at round-off: 15 of 2,000 failed, these two among them), checked by the definition; each must meet
// Painlevé's case, so the test cannot pass by not reaching it.
TEST(FrictionalProperty, PainleveImpulsesOfTwoSweepTossesStayInTheCone) {
  for (const std::uint64_t index : {308u, 1517u}) {
    const Toss t = make_toss(index);
    Totals totals;
    EXPECT_EQ(check_toss(t, totals), "") << t.describe;
    EXPECT_GT(totals.painleve, 0) << t.describe;
  }
}

// Tosses of the sweep that needed a fallback on 514b6f0: three stalled at Painlevé's dynamic jam (μ > 1.5,
// a sliding point's normal force diverging as its compliance under its own friction went to zero, the
// integrator's steps shrinking until the phase handed over) and six hit the rounds' bound at a landing on
// two corners (each one-point impact driving the other corner in: an endless trade of ever smaller
// impacts). The jam is an impact without collision now (counted as Painlevé's) and the corners strike
// together: every property holds and neither needs a fallback.
TEST(FrictionalProperty, DynamicJamsAndTwoCornerLandingsNeedNoFallback) {
  for (const std::uint64_t index : {106u, 939u, 1624u}) {
    const Toss t = make_toss(index);
    Totals totals;
    EXPECT_EQ(check_toss(t, totals), "") << t.describe;
    EXPECT_EQ(totals.stalled + totals.handovers + totals.bounded, 0) << t.describe;
    EXPECT_GT(totals.painleve, 0) << t.describe;
  }
  for (const std::uint64_t index : {855u, 862u, 1009u, 1364u, 1474u, 1573u}) {
    const Toss t = make_toss(index);
    Totals totals;
    EXPECT_EQ(check_toss(t, totals), "") << t.describe;
    EXPECT_EQ(totals.stalled + totals.handovers + totals.bounded, 0) << t.describe;
  }
}

// Toss 1237 (μ = 1.88) hit the rounds' bound on 197e4a6 at t = 2.2412: a jam at two sliding points whose
// joint least-norm stop pulled one of them; that impulse was dropped and the other kept its share of the
// joint stop, a kick (0.28 of tangential impulse against a slip of 8e-6·sqrt(g·L)) projected onto its cone,
// which started a hold / jam / impact cycle until the bound. The pulled point is now left free and the other
// stopped alone: no bounded round, and fewer jams.
TEST(FrictionalProperty, AJamThatWouldPullOneOfItsPointsStopsTheOthersWithoutIt) {
  const Toss t = make_toss(1237);
  Totals totals;
  EXPECT_EQ(check_toss(t, totals), "") << t.describe;
  EXPECT_EQ(totals.stalled + totals.handovers + totals.bounded, 0) << t.describe;
  EXPECT_GT(totals.painleve, 0) << t.describe;
}

}  // namespace
}  // namespace repose::sim
