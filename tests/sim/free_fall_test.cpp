// Free fall with an initial downward speed against closed forms computed in the test. Units are CGS (cm, g,
// s; g = 981 cm/s²).
#include <gtest/gtest.h>

#include <cmath>
#include <repose/model/particle.hpp>
#include <repose/sim/settle.hpp>
#include <vector>

#include "gravity.hpp"

namespace repose {
namespace {

TEST(FreeFall, ThrownDownItFollowsTheBallisticArcAndStartsWithHalfMVSquared) {
  // Box 1 × 2 × 3 of density 2 (m = 12 g), flat, lowest point h above the wall, thrown down at v. Closed
  // forms: E(0) = ½·m·v² + m·g·(h + 1.5); while falling z(t) = h + 1.5 − v·t − ½·g·t², kinetic energy ½·m·(v
  // + g·t)²; touchdown at t = (sqrt(v² + 2·g·h) − v)/g. The engine's fall is exact (closed form), so 1e-12
  // relative.
  const Particle box = load_particle("box:x=1,y=2,z=3", 2.0);
  const double m = 12.0, h = 4.0, v = 150.0;
  SettleParams p;
  p.gravity = test::kGravityCGS;
  p.drop_height = h;
  p.drop_speed = v;
  std::vector<Sample> samples;
  const SettleResult r = settle(
      box, p, Quat::Identity(), [&](const Sample& s) { samples.push_back(s); }, 1e-3);  // every ms
  const double e0 = 0.5 * m * v * v + m * test::kGravityCGS * (h + 1.5);
  EXPECT_NEAR(r.energy_start, e0, 1e-12 * e0);
  ASSERT_FALSE(samples.empty());
  EXPECT_NEAR(samples.front().kinetic_energy, 0.5 * m * v * v, 1e-12 * e0);
  const double touch = (std::sqrt(v * v + 2 * test::kGravityCGS * h) - v) / test::kGravityCGS;
  ASSERT_FALSE(r.phases.empty());
  EXPECT_EQ(r.phases.front().contact, ContactType::free_fall);
  EXPECT_NEAR(r.phases.front().t1, touch, 1e-12 * touch);
  int falling = 0;
  for (const Sample& s : samples) {
    if (s.contact != ContactType::free_fall || s.t >= touch) continue;
    ++falling;
    EXPECT_NEAR(s.com.z(), h + 1.5 - v * s.t - 0.5 * test::kGravityCGS * s.t * s.t, 1e-12 * (h + 1.5))
        << "t = " << s.t;
    EXPECT_NEAR(s.kinetic_energy, 0.5 * m * (v + test::kGravityCGS * s.t) * (v + test::kGravityCGS * s.t),
                1e-12 * e0)
        << "t = " << s.t;
    EXPECT_NEAR(s.kinetic_energy + s.potential_energy, e0, 1e-12 * e0) << "t = " << s.t;
  }
  EXPECT_GT(falling, 10);
  // Flat on its 1 × 2 face it stays there: the plastic impact leaves nothing.
  ASSERT_EQ(r.status, Status::rest);
  EXPECT_NEAR(r.time, touch, 1e-12 * touch);
  EXPECT_NEAR(r.com.z(), 1.5, 1e-12);
}

TEST(FreeFall, ThrownDownFromTheWallItSettlesAsThrownFromJustAbove) {
  // The paper's model (E = 0, μ infinite): a body started on the wall and thrown down at v takes the paper's
  // touch at t = 0 with that velocity, as one thrown from a height h → 0 does when it reaches the wall after
  // h/v. So the two settle alike: at h = 1e-9 cm the fall takes 7e-12 s and changes the touch velocity by
  // g·h/v = 7e-9 cm/s, of 150 — the time to rest within 1e-9 relative and the final pose within 1e-9 rad (the
  // adaptive integrator's tolerance; the start differs by 5e-11 relative, the same steps follow). A box 1 × 2
  // × 3 on one corner (turned 1.1 rad about a skew axis): carrying the throw's angular momentum about the
  // corner into the rotation, as after an impact, would rest it 4 times sooner.
  const Particle box = load_particle("box:x=1,y=2,z=3", 2.0);
  const Quat tilted(Eigen::AngleAxisd(1.1, Vec3(0.3, 1, 0.2).normalized()));
  SettleParams on_wall;
  on_wall.gravity = test::kGravityCGS;
  on_wall.drop_speed = 150.0;
  SettleParams just_above = on_wall;
  just_above.drop_height = 1e-9;
  const SettleResult a = settle(box, on_wall, tilted), b = settle(box, just_above, tilted);
  ASSERT_EQ(a.status, Status::rest);
  ASSERT_EQ(b.status, Status::rest);
  EXPECT_NEAR(a.time, b.time, 1e-9 * b.time);
  EXPECT_LT(a.orientation.angularDistance(b.orientation), 1e-9);
}

TEST(FreeFall, TossedWithoutSpinItFollowsTheParabolaInAllThreeAxes) {
  // The same box, flat, h above the wall, tossed with velocity (vx, vy, vz) and no spin: the centre of mass
  // moves by (vx·t, vy·t, vz·t − ½·g·t²) until the touch at t = (vz + sqrt(vz² + 2·g·h))/g, where it stays
  // (flat, the plastic touch). Exact in the engine (closed form), so 1e-12 relative.
  const Particle box = load_particle("box:x=1,y=2,z=3", 2.0);
  const double h = 4.0, vx = 30.0, vy = -70.0, vz = 50.0;
  SettleParams p;
  p.gravity = test::kGravityCGS;
  p.drop_height = h;
  p.velocity = Vec3(vx, vy, vz);
  std::vector<Sample> samples;
  const SettleResult r = settle(
      box, p, Quat::Identity(), [&](const Sample& s) { samples.push_back(s); }, 1e-3);
  ASSERT_FALSE(samples.empty());
  const Vec3 start = samples.front().com;
  const double touch = (vz + std::sqrt(vz * vz + 2 * test::kGravityCGS * h)) / test::kGravityCGS;
  int flying = 0;
  for (const Sample& s : samples) {
    if (s.t >= touch) continue;
    ++flying;
    const Vec3 expected = start + Vec3(vx * s.t, vy * s.t, vz * s.t - 0.5 * test::kGravityCGS * s.t * s.t);
    EXPECT_NEAR((s.com - expected).norm(), 0.0, 1e-12 * (h + 1.5 + std::abs(vy) * touch)) << "t = " << s.t;
  }
  EXPECT_GT(flying, 10);
  ASSERT_EQ(r.status, Status::rest);
  EXPECT_NEAR(r.time, touch, 1e-12 * touch);
  const Vec3 landed = start + Vec3(vx * touch, vy * touch, 0.0);
  EXPECT_NEAR(r.com.x(), landed.x(), 1e-12 * std::abs(vx) * touch);
  EXPECT_NEAR(r.com.y(), landed.y(), 1e-12 * std::abs(vy) * touch);
  EXPECT_NEAR(r.com.z(), 1.5, 1e-12);
}

TEST(FreeFall, TheAutomaticTimeLimitCountsTheFall) {
  // The default limit is 2000·sqrt(L/g) plus the fall time (SettleParams::max_time). Dropped flat from
  // 8·10⁶·L the fall alone takes sqrt(2·8e6)·sqrt(L/g) = 4000·sqrt(L/g), twice the settling allowance, and
  // the cube must still land (at the ballistic time, to 1e-9 relative) and rest.
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1.0);
  SettleParams p;
  p.gravity = test::kGravityCGS;
  p.drop_height = 8e6 * cube.length;
  const SettleResult r = settle(cube, p, Quat::Identity());
  ASSERT_EQ(r.status, Status::rest);
  const double touch = std::sqrt(2 * p.drop_height / test::kGravityCGS);
  EXPECT_NEAR(r.time, touch, 1e-9 * touch);
}

TEST(FreeFall, AStepLimitOfOneStopsAfterExactlyOneStepOfTheFall) {
  // --max-steps 1 is a legal limit (any positive count): the run takes one step of the fall, dt, and stops
  // with status max_steps, the centre of mass at h + ½ − ½·g·dt² (the fall is a closed form: 1e-12).
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1.0);
  SettleParams p;
  p.gravity = test::kGravityCGS;
  p.drop_height = 2.0;
  p.dt = 1e-3;
  p.max_steps = 1;
  std::vector<Sample> samples;
  const SettleResult r = settle(cube, p, Quat::Identity(), [&](const Sample& s) { samples.push_back(s); });
  EXPECT_EQ(r.status, Status::max_steps);
  EXPECT_EQ(r.steps, 1);
  EXPECT_NEAR(r.time, 1e-3, 1e-15);
  ASSERT_FALSE(samples.empty());
  EXPECT_NEAR(samples.back().com.z(), 2.5 - 0.5 * test::kGravityCGS * 1e-6, 1e-12);
}

TEST(FreeFall, ATimeLimitInsideTheFallStopsItExactlyThere) {
  // --max-time 0.0105 s with dt = 1 ms, dropped from 2 cm: ten whole steps, then the closed form evaluated at
  // the limit (not a step: the fall is exact, only its samples are on the grid of dt), so the run stops at
  // exactly the limit (status max_time) with the centre of mass on the ballistic arc, h + ½ − ½·g·t² (closed
  // form, 1e-12), and the observer sees that last state.
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1.0);
  SettleParams p;
  p.gravity = test::kGravityCGS;
  p.drop_height = 2.0;
  p.dt = 1e-3;
  p.max_time = 0.0105;
  std::vector<Sample> samples;
  const SettleResult r = settle(cube, p, Quat::Identity(), [&](const Sample& s) { samples.push_back(s); });
  EXPECT_EQ(r.status, Status::max_time);
  EXPECT_NEAR(r.time, 0.0105, 1e-15);
  EXPECT_EQ(r.steps, 10);
  ASSERT_FALSE(samples.empty());
  EXPECT_EQ(samples.back().t, r.time);
  EXPECT_NEAR(samples.back().com.z(), 2.5 - 0.5 * test::kGravityCGS * 0.0105 * 0.0105, 1e-12);
}

}  // namespace
}  // namespace repose
