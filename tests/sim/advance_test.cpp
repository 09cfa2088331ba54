// Settler::advance_to (a DEM code's own step) and sampled runs: where a run is stopped must not change it.
#include <gtest/gtest.h>

#include <cmath>
#include <repose/error.hpp>
#include <repose/model/orientation.hpp>
#include <repose/model/particle.hpp>
#include <repose/poses/sampling.hpp>
#include <repose/sim/settle.hpp>
#include <vector>

namespace repose {
namespace {

void expect_same_result(const SettleResult& a, const SettleResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.rest_face, b.rest_face);
  EXPECT_EQ(a.orientation.coeffs(), b.orientation.coeffs());
  EXPECT_EQ(a.com, b.com);
  EXPECT_EQ(a.energy_end, b.energy_end);
}

// A DEM code advancing by its own step (here 1e-4 s, ~0.3 % of τ = sqrt(L/g)) sees the particle exactly at
// each requested time, and the adaptive run it drives is the uninterrupted run, bit for bit: the integrator's
// steps and events do not depend on where it is stopped (the state there is interpolated).
TEST(AdvanceTo, StopsExactlyThereAndLeavesTheAdaptiveRunUnchanged) {
  for (const char* spec : {"box:x=1,y=2,z=3", "tetrahedron:edge=1", "irregular:seed=2,n=4"}) {
    const Particle particle = load_particle(spec, 1000.0);
    SettleParams params;
    params.drop_height = 0.2 * particle.length;
    for (std::uint64_t i = 0; i < 5; ++i) {
      const Quat q = drop_orientation(7, i);
      const SettleResult whole = settle(particle, params, q);
      Settler settler(particle, params, q);
      const double dem_dt = 1e-4;
      for (long k = 1; k < 1'000'000 && settler.status() == Status::running; ++k) {
        const bool running = settler.advance_to(static_cast<double>(k) * dem_dt);
        if (running) {
          ASSERT_EQ(settler.sample().t, static_cast<double>(k) * dem_dt) << spec << " drop " << i;
        }
      }
      SCOPED_TRACE(std::string(spec) + " drop " + std::to_string(i));
      expect_same_result(settler.result(), whole);
    }
  }
}

// The paper's fixed step is shortened to land on the requested time, so there the trajectory does change:
// only the end state is checked, against the uninterrupted run (the same rest face; the time within the
// trapezoidal rule's error, measured 3e-9 relative; tolerance 1e-7).
TEST(AdvanceTo, ThePaperIntegratorLandsOnTheRequestedTimesToo) {
  const Particle particle = load_particle("box:x=1,y=2,z=3", 1000.0);
  SettleParams params;
  params.integrator = Integrator::paper;
  const Quat q = parse_orientation("axis-angle:1,0.2,0,0.7");
  const SettleResult whole = settle(particle, params, q);
  Settler settler(particle, params, q);
  const double dem_dt = 0.37e-3;  // not a multiple of the engine's step
  for (long k = 1; k < 1'000'000 && settler.advance_to(static_cast<double>(k) * dem_dt); ++k)
    ASSERT_EQ(settler.sample().t, static_cast<double>(k) * dem_dt);
  const SettleResult r = settler.result();
  ASSERT_EQ(r.status, Status::rest);
  EXPECT_EQ(r.rest_face, whole.rest_face);
  EXPECT_NEAR(r.time, whole.time, 1e-7 * whole.time);
}

// A time limit inside a rotation stops the run exactly there, with either integrator (status max_time): the
// paper's step before the limit is shortened to end on it (10 whole steps of 1 ms, then 0.5 ms), the
// adaptive one stops inside its step (the state there interpolated). A cube tilted 0.3 rad on an edge.
TEST(AdvanceTo, ATimeLimitInsideARotationStopsItExactlyThere) {
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1.0);
  for (Integrator integrator : {Integrator::paper, Integrator::adaptive}) {
    SettleParams p;
    p.integrator = integrator;
    p.dt = 1e-3;
    p.max_time = 0.0105;
    const SettleResult r = settle(cube, p, Quat(Eigen::AngleAxisd(0.3, Vec3::UnitX())));
    EXPECT_EQ(r.status, Status::max_time) << to_string(integrator);
    EXPECT_EQ(r.time, 0.0105) << to_string(integrator);
    if (integrator == Integrator::paper) {
      EXPECT_EQ(r.steps, 11);
    }
  }
}

// run(observer, sample_dt) reports the initial state, every multiple of sample_dt before the end, and the
// end.
TEST(SampledRun, ReportsEveryMultipleOfTheIntervalAndTheEnd) {
  const Particle particle = load_particle("tetrahedron:edge=1", 1000.0);
  const SettleParams params;
  const Quat q = parse_orientation("axis-angle:1,0.3,0,2.5");
  std::vector<double> times;
  const double interval = 2.5e-4;
  const SettleResult r = settle(
      particle, params, q, [&](const Sample& s) { times.push_back(s.t); }, interval);
  ASSERT_EQ(r.status, Status::rest);
  ASSERT_EQ(times.size(), static_cast<std::size_t>(std::ceil(r.time / interval)) + 1);
  for (std::size_t k = 0; k + 1 < times.size(); ++k) EXPECT_EQ(times[k], static_cast<double>(k) * interval);
  EXPECT_EQ(times.back(), r.time);
  expect_same_result(r, settle(particle, params, q));
  EXPECT_THROW(settle(particle, params, q, {}, -1.0), Error);
}

// The starting orientation is any quaternion of norm ≥ 1e-12 (Settler's documented floor), normalised: 2·q
// runs exactly as q (scaling by 2 is exact), and the identity at norm 1e-12 exactly as the identity. Below
// the floor, zero and non-finite quaternions are refused.
TEST(StartingOrientation, IsNormalisedDownToItsFloorAndRefusedBelowIt) {
  const Particle particle = load_particle("tetrahedron:edge=1", 1000.0);
  const SettleParams params;
  const Quat q = parse_orientation("axis-angle:1,0.3,0,2.5");
  expect_same_result(settle(particle, params, q), settle(particle, params, Quat(q.coeffs() * 2)));
  const SettleResult identity = settle(particle, params, Quat::Identity());
  expect_same_result(identity, settle(particle, params, Quat(1e-12, 0, 0, 0)));
  EXPECT_THROW(settle(particle, params, Quat(0.999e-12, 0, 0, 0)), Error);
  EXPECT_THROW(settle(particle, params, Quat(0, 0, 0, 0)), Error);
  EXPECT_THROW(settle(particle, params, Quat(NAN, 0, 0, 1)), Error);
  EXPECT_THROW(settle(particle, params, Quat(INFINITY, 0, 0, 1)), Error);
}

}  // namespace
}  // namespace repose
