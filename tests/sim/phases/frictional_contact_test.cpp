// The contact phase with finite friction (issue 34; src/sim/phases/frictional_contact.hpp), run through the
// public engine, against closed forms worked out here: a box sliding flat, the tall box's tipping threshold,
// a cylinder that slides into rolling, a rod's foot slipping at its closed-form angle, the frictionless rod
// whose centre of mass falls straight down; and the energy ledger. SI units, g = 9.81.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <repose/model/particle.hpp>
#include <repose/poses/sampling.hpp>
#include <repose/sim/settle.hpp>
#include <string>
#include <tuple>
#include <vector>

#include "gravity.hpp"

namespace repose {
namespace {

SettleParams sliding_start(const Vec3& velocity, double mu) {
  SettleParams p;
  p.velocity = velocity;
  p.friction = mu;
  return p;
}

bool has_line_phase(const SettleResult& r) {
  for (const Phase& ph : r.phases)
    if (ph.contact == ContactType::line || ph.contact == ContactType::point) return true;
  return false;
}

// The time series' first sample of a run started on the wall: the cube's four bottom corners on it, all
// sliding when it is started sliding, all at rest when it is started still, the contact a surface (it used to
// say free fall with no point, the frictional phase's first segment not having begun).
TEST(FrictionalContact, FirstSampleOfAWallStartShowsItsPointsAndTheirModes) {
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1000.0);
  for (const double v : {0.0, 1.5}) {
    Settler settler(cube, sliding_start(Vec3(v, 0, 0), 0.5), Quat::Identity());
    const Sample s = settler.sample();
    EXPECT_EQ(s.contact, ContactType::surface) << v;
    EXPECT_EQ(s.contact_count, 4) << v;
    EXPECT_EQ(s.sliding, v > 0 ? 4 : 0) << v;
    EXPECT_EQ(s.sticking, v > 0 ? 0 : 4) << v;
  }
  // On an edge (turned 45° about x): its two corners, a line; on a corner (its diagonal vertical): a point.
  const Quat edge(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitX()));
  const Quat corner = Quat::FromTwoVectors(Vec3(-1, -1, -1).normalized(), -Vec3::UnitZ());
  for (const auto& [q, type, count] :
       {std::tuple{edge, ContactType::line, 2}, {corner, ContactType::point, 1}}) {
    Settler settler(cube, sliding_start(Vec3::Zero(), 0.5), q);
    const Sample s = settler.sample();
    EXPECT_EQ(s.contact, type) << count;
    EXPECT_EQ(s.contact_count, count);
    EXPECT_EQ(s.sticking, count);
  }
}

// A unit cube on its face, started on the wall sliding at v0 (the defect: it used to stop where it
// started): it decelerates at μ·g and stops after v0²/(2μg) at t = v0/(μg), without turning. The
// deceleration is constant, which Dormand–Prince integrates exactly; the stop is located where the slip
// falls below kSpeed = 1e-9·sqrt(g·L), so t is late by at most 1e-9·sqrt(g·L)/(μ·g) and the distance
// short by its square: tolerances 2e-9·sqrt(L/g)/μ and 1e-12·L. Friction takes the whole kinetic energy
// (1e-9 relative: the ledger's integration).
TEST(FrictionalContact, BoxSlidingFlatStopsAtTheClosedForm) {
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1000.0);
  const double L = cube.length, tau = std::sqrt(L / test::kGravitySI), m = cube.mass.mass;
  for (const double mu : {0.2, 0.5, 1.0}) {
    for (const Vec3& dir : {Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0.6, 0.8, 0)}) {
      const double v0 = 1.5;
      const SettleResult r = settle(cube, sliding_start(v0 * dir, mu), Quat::Identity());
      ASSERT_EQ(r.status, Status::rest) << mu;
      const double d = v0 * v0 / (2 * mu * test::kGravitySI);
      EXPECT_NEAR(r.com.x(), d * dir.x(), 1e-12 * L) << "mu " << mu;
      EXPECT_NEAR(r.com.y(), d * dir.y(), 1e-12 * L) << "mu " << mu;
      EXPECT_NEAR(r.com.z(), 0.5, 1e-12 * L);
      EXPECT_NEAR(r.time, v0 / (mu * test::kGravitySI), 2e-9 * tau / mu) << "mu " << mu;
      EXPECT_NEAR(r.orientation.angularDistance(Quat::Identity()), 0, 1e-12) << "no pitch, no yaw";
      EXPECT_TRUE(r.impacts.empty());
      EXPECT_FALSE(has_line_phase(r)) << "the back edge never lifts at mu = " << mu;
      EXPECT_NEAR(r.friction_work, 0.5 * m * v0 * v0, 1e-9 * m * test::kGravitySI * L);
      EXPECT_NEAR(r.sliding_distance, d, 1e-9 * L);
      EXPECT_NEAR(r.energy_start - r.energy_end, r.friction_work, 1e-9 * m * test::kGravitySI * L);
    }
  }
}

// A 1 × 1 × 3 box standing on its end, started sliding: the friction μ·m·g at the base, 1.5 below the
// centre of mass, takes the back edge's normal force m·g·(1/2 − μ·h/(2a)) to zero at μ = a/h = 1/3 (half the
// base over the centre of mass's height). Below it the box slides flat to the closed-form stop, its back
// edge on the wall; above it the back edge lifts at once: 0.02 s later it is above the wall (by more than the
// integrator's drift, 1e-9·L) and pitching.
TEST(FrictionalContact, TallBoxTipsIfAndOnlyIfMuExceedsOneThird) {
  const Particle tall = load_particle("box:x=1,y=1,z=3", 1000.0);
  const double L = tall.length;
  const Vec3 back_corner(-0.5, 0.5, -1.5);
  for (const double mu : {0.25, 0.32, 0.333, 0.334, 0.4, 1.0}) {
    Settler settler(tall, sliding_start(Vec3(1, 0, 0), mu), Quat::Identity());
    settler.advance_to(0.02);
    const Sample s = settler.sample();
    const double back = (s.com + s.orientation * back_corner).z();
    if (mu < 1.0 / 3) {
      EXPECT_LE(back, 1e-9 * L) << "mu " << mu << " below 1/3: the back edge stays on the wall";
      const SettleResult r = settle(tall, sliding_start(Vec3(1, 0, 0), mu), Quat::Identity());
      ASSERT_EQ(r.status, Status::rest);
      EXPECT_FALSE(has_line_phase(r)) << "mu " << mu << ": slides flat";
      EXPECT_NEAR(r.com.x(), 1 / (2 * mu * test::kGravitySI), 1e-12 * L) << mu;
    } else {
      EXPECT_GT(back, 1e-9 * L) << "mu " << mu << " above 1/3: the back edge lifts";
      EXPECT_EQ(s.sliding + s.sticking, 2) << "mu " << mu << ": the front edge alone is pressed";
    }
  }
}

// A 32-gon disk (circumradius R = 0.5, thickness 0.1) lying on its face, spun at ω0 = 5 about its axis with μ
// = 0.3: its 32 corners, all on the rim, slide along it, each pressed by m·g/32 (the linear pressure of the
// planar sliding face is uniform by symmetry), so friction's torque is μ·m·g·R and the spin stops at
// T = J·ω0/(μ·m·g·R), J = m·R²·(1 + 2·cos²(π/32))/6 the regular polygon's polar moment, after turning ω0·T/2,
// the centre never moving. The deceleration is constant (integrated exactly); the stop is located where the
// rim's slip falls below 1e-9·sqrt(g·L), 4e-10 s early at most: tolerance 1e-8·τ, and on the angle ω0 times
// it.
TEST(FrictionalContact, SpinningDiskStopsWhereFrictionsTorqueSays) {
  const Particle disk = load_particle("cylinder:r=0.5,h=0.1,n=32", 1000.0);
  const double m = disk.mass.mass, R = 0.5, mu = 0.3, w0 = 5, tau = std::sqrt(disk.length / test::kGravitySI);
  const double J = m * R * R * (1 + 2 * std::pow(std::cos(std::numbers::pi / 32), 2)) / 6;
  SettleParams p;
  p.friction = mu;
  p.spin = Vec3(0, 0, w0);
  const SettleResult r = settle(disk, p, Quat::Identity());
  ASSERT_EQ(r.status, Status::rest);
  const double T = J * w0 / (mu * m * test::kGravitySI * R);
  EXPECT_NEAR(r.time, T, 1e-8 * tau);
  EXPECT_NEAR(r.orientation.angularDistance(Quat::Identity()), w0 * T / 2, w0 * 1e-8 * tau);
  EXPECT_NEAR(r.com.head<2>().norm(), 0, 1e-12);
  EXPECT_TRUE(r.impacts.empty());
  EXPECT_NEAR(r.friction_work, 0.5 * J * w0 * w0, 1e-9 * m * test::kGravitySI * disk.length);
}

// A 32-gon cylinder (R = 0.5, h = 1) standing on its end, launched sliding along x: friction's moment
// μ·m·g·h/2 moves the centre of pressure forward by e = μ·h/2. Linear pressure over the rim's corners would
// turn negative at the back for e > R/2 (μ > 0.5), so the back corners carry nothing; the base tips only when
// the centre of pressure leaves it, at the front corner (x = R): μ > 2R/h = 1. Below that it slides flat to
// the closed form (tolerances as the sliding box's); above it the back rim lifts (0.02 s later above 1e-9·L).
TEST(FrictionalContact, StandingCylinderSlidesOnAPartlyLoadedBaseUntilItTips) {
  const Particle cyl = load_particle("cylinder:r=0.5,h=1,n=32", 1000.0);
  const double L = cyl.length, tau = std::sqrt(L / test::kGravitySI), v0 = 1.5;
  for (const double mu : {0.3, 0.6, 0.8, 0.98}) {
    const SettleResult r = settle(cyl, sliding_start(Vec3(v0, 0, 0), mu), Quat::Identity());
    ASSERT_EQ(r.status, Status::rest) << mu;
    EXPECT_NEAR(r.com.x(), v0 * v0 / (2 * mu * test::kGravitySI), 1e-12 * L) << "mu " << mu;
    EXPECT_NEAR(r.time, v0 / (mu * test::kGravitySI), 2e-9 * tau / mu) << "mu " << mu;
    EXPECT_NEAR(r.orientation.angularDistance(Quat::Identity()), 0, 1e-12) << "mu " << mu << ": no pitch";
    EXPECT_TRUE(r.impacts.empty()) << "mu " << mu;
  }
  Settler settler(cyl, sliding_start(Vec3(v0, 0, 0), 1.02), Quat::Identity());
  settler.advance_to(0.02);
  const Sample s = settler.sample();
  EXPECT_GT((s.com + s.orientation * Vec3(-0.5, 0, -0.5)).z(), 1e-9 * L) << "mu 1.02: the back rim lifts";
}

// A solid cylinder lying on its side (a 256-gon prism), launched sliding at v0 without spin: friction
// decelerates it at μ·g and spins it up at 2μg/R until the contact stops slipping at t = v0/(3μg), from
// when it rolls at 2v0/3. The polygon rolls over an edge every 2π/256 of a turn, each a small plastic
// impact (the rolling polygon's loss, (1 − (1 − cos θ)·m·R²/I_O)² per edge, 1.3e-4 of the speed here):
// measured against the smooth cylinder, the stop comes 4e-4·t late and the speed is 6e-4·v0 off; the
// tolerances 2e-3·t and 2e-3·v0 hold that with margin. The time series' step is 1e-4 s.
TEST(FrictionalContact, CylinderSlidingOnItsSideRollsAtTwoThirdsFromTheClosedFormTime) {
  const Particle cyl = load_particle("cylinder:r=0.5,h=1,n=256", 1000.0);
  const double mu = 0.3, v0 = 1.0;
  SettleParams p = sliding_start(Vec3(v0, 0, 0), mu);
  p.max_time = 0.3;
  Settler settler(cyl, p, Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitX())));
  double prev_x = 0, prev_t = 0, stop = -1, speed = 0;
  for (double t = 1e-4; t <= 0.25 && settler.status() == Status::running; t += 1e-4) {
    settler.advance_to(t);
    const Sample s = settler.sample();
    const double vx = (s.com.x() - prev_x) / (s.t - prev_t);
    // Rolling: every point on the wall sticks.
    if (stop < 0 && s.sliding == 0 && s.sticking > 0 && t > 0.01) {
      stop = s.t;
      speed = vx;
    }
    prev_x = s.com.x();
    prev_t = s.t;
  }
  const double t_roll = v0 / (3 * mu * test::kGravitySI);
  EXPECT_NEAR(stop, t_roll, 2e-3 * t_roll + 2e-4);
  EXPECT_NEAR(speed, 2 * v0 / 3, 2e-3 * v0);
}

// A frictionless rod (0.1 × 0.1 × 1) released from rest tilted on one edge of its foot: no horizontal force
// acts, so its centre of mass falls straight down (its x and y stay where they were to round-off), and the
// foot slides but stays on the wall until the rod lands.
TEST(FrictionalContact, FrictionlessRodsCentreFallsStraightDown) {
  const Particle rod = load_particle("box:x=0.1,y=0.1,z=1", 1000.0);
  const double L = rod.length;
  SettleParams p;
  p.friction = 0;
  const double beta = std::atan(0.1) + 0.05;
  Settler settler(rod, p, Quat(Eigen::AngleAxisd(beta, Vec3::UnitY())));
  const Vec3 start = settler.sample().com;
  int samples_on_foot = 0;
  for (double t = 1e-3; settler.status() == Status::running && t < 5; t += 1e-3) {
    settler.advance_to(t);
    const Sample s = settler.sample();
    if (s.contact_count != 2) break;  // the rod lands
    ++samples_on_foot;
    EXPECT_NEAR(s.com.x(), start.x(), 1e-12 * L) << "t " << t;
    EXPECT_NEAR(s.com.y(), start.y(), 1e-12 * L) << "t " << t;
  }
  EXPECT_GT(samples_on_foot, 100) << "the foot stays on the wall (two corners) until the rod lands";
  EXPECT_EQ(settle(rod, p, Quat(Eigen::AngleAxisd(beta, Vec3::UnitY()))).status, Status::rest);
}

// A rod (0.1 × 0.1 × 1) released from rest a little past balance on one edge of its foot pivots about it
// while friction holds: about the edge (arm r from it to the centre of mass, I_O = I_c + m·r²) at tilt φ
// from the vertical, ω² = 2·m·g·r·(cos φ0 − cos φ)/I_O and α = m·g·r·sin φ/I_O, so the foot needs
// F/N = r·(α·cos φ − ω²·sin φ)/(g − r·(α·sin φ + ω²·cos φ)); it slips where that first reaches μ. The
// onset is read from the foot's displacement, which grows as (t − t_s)³ after it (the slip's acceleration
// starts from zero): t_s from two displacements (1e-6 and 1e-5 of L) by the cube law, and φ at t_s from a
// second run stopped there. The cube law's next term and the sampling leave 2e-3 rad.
TEST(FrictionalContact, RodFootSlipsAtTheClosedFormAngle) {
  const Particle rod = load_particle("box:x=0.1,y=0.1,z=1", 1000.0);
  const double L = rod.length, m = rod.mass.mass;
  const double w = 0.1, h = 1.0;
  const double r = std::hypot(w / 2, h / 2), ic = m * (w * w + h * h) / 12, io = ic + m * r * r;
  const double phi0 = 0.1, beta = std::atan(w / h) + phi0;
  const Quat q0(Eigen::AngleAxisd(beta, Vec3::UnitY()));
#ifdef NDEBUG
  const std::vector<double> frictions = {0.2, 0.3};
#else
  const std::vector<double> frictions = {0.3};  // the sanitizer build: one (each takes ~10^4 advance_to)
#endif
  for (const double mu : frictions) {
    const auto ratio = [&](double phi) {
      const double w2 = 2 * m * test::kGravitySI * r * (std::cos(phi0) - std::cos(phi)) / io;
      const double al = m * test::kGravitySI * r * std::sin(phi) / io;
      return r * (al * std::cos(phi) - w2 * std::sin(phi)) /
             (test::kGravitySI - r * (al * std::sin(phi) + w2 * std::cos(phi)));
    };
    double lo = phi0, hi = phi0;
    while (ratio(hi) < mu) {
      lo = hi;
      hi += 1e-3;
    }
    for (int i = 0; i < 60; ++i) (ratio(0.5 * (lo + hi)) < mu ? lo : hi) = 0.5 * (lo + hi);
    const double phi_slip = 0.5 * (lo + hi);

    SettleParams p;
    p.friction = mu;
    Settler run(rod, p, q0);
    const Vec3 foot_body(w / 2, 0, -h / 2);  // the middle of the foot's edge on the wall
    const Vec3 foot0 = run.sample().com + q0 * foot_body;
    double t1 = -1, d1 = 0, t2 = -1, d2 = 0;
    for (double t = 1e-4; t < 3 && t2 < 0 && run.status() == Status::running; t += 1e-4) {
      run.advance_to(t);
      const Sample s = run.sample();
      const double d = ((s.com + s.orientation * foot_body) - foot0).head<2>().norm();
      if (t1 < 0 && d > 1e-6 * L) {
        t1 = s.t;
        d1 = d;
      } else if (t1 > 0 && d > 1e-5 * L) {
        t2 = s.t;
        d2 = d;
      }
    }
    ASSERT_GT(t2, 0) << "the foot slips at mu " << mu;
    const double c1 = std::cbrt(d1), c2 = std::cbrt(d2);
    const double ts = t1 - c1 * (t2 - t1) / (c2 - c1);
    Settler again(rod, p, q0);
    again.advance_to(ts);
    const Sample s = again.sample();
    const Vec3 foot = s.com + s.orientation * foot_body;
    const double phi = std::atan2(std::abs(s.com.x() - foot.x()), s.com.z() - foot.z());
    EXPECT_NEAR(phi, phi_slip, 2e-3) << "mu " << mu;
  }
}

// Impacts, friction and the damping moment account for every change of the mechanical energy, which never
// rises: a tossed box landing with spin, with restitution, across μ. The balance closes to the
// integrator's tolerance times the steps (1e-6·m·g·L) and what the rest test drops (≤ m·g·1e-7·L).
TEST(FrictionalContact, EnergyLedgerClosesForTossedLandings) {
  const Particle box = load_particle("box:x=1,y=2,z=3", 1000.0);
  const double L = box.length, m = box.mass.mass;
  for (const double mu : {0.1, 0.5, 2.0}) {
    SettleParams p;
    p.drop_height = 0.5;
    p.velocity = Vec3(1.0, 0.5, 0);
    p.spin = Vec3(2, -3, 1);
    p.restitution = 0.3;
    p.friction = mu;
    p.damping = 0.05;
    const SettleResult r = settle(box, p, Quat(Eigen::AngleAxisd(0.3, Vec3(1, 1, 0).normalized())));
    ASSERT_EQ(r.status, Status::rest) << mu;
    double impacts = 0;
    for (const ImpactRecord& i : r.impacts) {
      EXPECT_LE(i.energy_after, i.energy_before + 1e-12 * m * test::kGravitySI * L);
      impacts += i.energy_before - i.energy_after;
    }
    EXPECT_GE(r.friction_work, 0);
    EXPECT_GE(r.damping_work, 0);
    const double lost = r.energy_start - r.energy_end;
    EXPECT_NEAR(lost, r.friction_work + r.damping_work + impacts, 1e-6 * m * test::kGravitySI * L)
        << "mu " << mu;
    EXPECT_LE(r.max_penetration, 1e-9 * L);
  }
}

// Friction infinite keeps the paper's phase; a large finite μ converges to it: the same rest face for
// tosses that never slide far (μ = 100).
TEST(FrictionalContact, LargeFrictionRestsOnThePapersFace) {
  const Particle box = load_particle("box:x=1,y=2,z=3", 1000.0);
  int same = 0, total = 0;
  for (int k = 0; k < 6; ++k) {
    const Quat q(Eigen::AngleAxisd(0.4 + 0.37 * k, Vec3(std::sin(k), std::cos(k), 0.5).normalized()));
    SettleParams p;
    p.drop_height = 0.2;
    SettleParams finite = p;
    finite.friction = 100;
    const SettleResult a = settle(box, p, q), b = settle(box, finite, q);
    ASSERT_EQ(b.status, Status::rest);
    same += a.rest_face == b.rest_face;
    ++total;
  }
  EXPECT_GE(same, total - 1);
}

}  // namespace
}  // namespace repose

namespace repose {
namespace {

// Issue 34's defects of the hand-over and the start, each failing on main 1005e77:
// - a rod at 45° (m 1, I 1/12 about its middle) landing on its end with v (2, 0, −1), μ = 0, E = 0: the old
//   hand-over turned the momentum about the foot into rotation about it, a pulling impulse with unlimited
//   friction; frictionless, no horizontal force acts at any time, so the centre of mass's horizontal
//   velocity stays 2 (its x grows by 2·t to round-off) until the rod lands flat;
// - a cube face down on the wall at 1 m/s used to end at rest at t = 0 where it started (covered by
//   BoxSlidingFlatStopsAtTheClosedForm);
// - thrown down from height 0 with E > 0 the old start bypassed the impact law: it must match a start from
//   1e-12 above the wall (the same impact, 1e-9 relative in the first impact's speeds).
TEST(FrictionalContact, FrictionlessLandingKeepsTheHorizontalVelocity) {
  const Particle rod = load_particle("box:x=0.05,y=0.05,z=1", 1000.0);
  SettleParams p;
  p.drop_height = 1e-3;
  p.velocity = Vec3(2, 0, -1);
  p.friction = 0;
  Settler settler(rod, p, Quat(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitY())));
  const Vec3 c0 = settler.sample().com;
  for (double t = 1e-3; t < 0.3 && settler.status() == Status::running; t += 1e-3) {
    settler.advance_to(t);
    const Sample s = settler.sample();
    if (s.contact_count > 2) break;  // landed flat
    EXPECT_NEAR(s.com.x(), c0.x() + 2 * s.t, 1e-9) << "t " << s.t;
  }
}

TEST(FrictionalContact, ThrownDownFromTheWallStrikesByTheImpactLaw) {
  const Particle cube = load_particle("box:x=1,y=1,z=1", 1000.0);
  for (const double mu : {0.5, static_cast<double>(INFINITY)}) {
    SettleParams a;
    a.drop_speed = 2;
    a.restitution = 0.5;
    a.friction = mu;
    SettleParams b = a;
    b.drop_height = 1e-12;
    const Quat q(Eigen::AngleAxisd(0.3, Vec3(1, 2, 0).normalized()));
    const SettleResult ra = settle(cube, a, q), rb = settle(cube, b, q);
    ASSERT_FALSE(ra.impacts.empty()) << "mu " << mu;
    ASSERT_FALSE(rb.impacts.empty());
    EXPECT_NEAR(ra.impacts[0].normal_speed_before, rb.impacts[0].normal_speed_before, 1e-9 * 2);
    EXPECT_NEAR(ra.impacts[0].normal_speed_after, rb.impacts[0].normal_speed_after, 1e-9 * 2);
    EXPECT_GT(ra.impacts[0].normal_speed_after, 0) << "it rebounds";
  }
}

// Painlevé's rod: a 1 × 0.05 × 0.05 rod (density 1, m = 2.5 g: its impulses are far below 1 in SI) standing
// at 45° on its foot edge, started on the wall sliding foot first at v0 = 1 m/s. The foot edge's midpoint is
// r = R·(−0.5, 0, −0.025) from the centre of mass; a single point there has no consistent normal force once
// μ > W_nn/W_nt = (1/m + r_x²/I)/(r_x·r_z/I) = 1.575 (I = m·(1 + 0.05²)/12 about y). At μ = 2 the slide ends
// at once in an impact without collision that stops the foot (Génot & Brogliato's dynamic jam); the impulse
// at the foot keeps the angular momentum about it, L = m·|r_z|·v0, so the kinetic energy left is
// L²/(2·I_foot), I_foot = I + m·|r|², the rest lost (1e-9 relative: round-off of a least-norm solve). The
// foot edge's two corners jam together, with equal impulses by the rod's mirror symmetry in y, so the
// record's point (the impulses' centre) is the edge's midpoint, com + r (1e-12·L: round-off of a rotation).
// At μ = 1 the foot slides on, with no such impact.
TEST(FrictionalContact, PainleveRodJamsByAnImpactWithoutCollision) {
  const Particle rod = load_particle("box:x=1,y=0.05,z=0.05", 1.0);
  const double m = rod.mass.mass;
  const Quat q(Eigen::AngleAxisd(-std::numbers::pi / 4, Vec3::UnitY()));
  const Vec3 r = q * Vec3(-0.5, 0, -0.025);
  const double inertia = m * (1 + 0.05 * 0.05) / 12;
  const double i_foot = inertia + m * (r.x() * r.x() + r.z() * r.z());
  const double angular_momentum = m * std::abs(r.z()) * 1.0;
  const double lost = 0.5 * m - angular_momentum * angular_momentum / (2 * i_foot);
  SettleParams p = sliding_start(Vec3(-1, 0, 0), 2.0);
  p.max_time = 0.05;  // the start is what matters: the first 0.05 s
  Settler settler(rod, p, q);
  const Vec3 com = settler.sample().com;
  const SettleResult jam = settler.run();
  ASSERT_GE(jam.painleve, 1);
  ASSERT_FALSE(jam.impacts.empty());
  const ImpactRecord& first = jam.impacts.front();
  EXPECT_EQ(first.t, 0.0);
  EXPECT_EQ(first.points, 2) << "the foot edge's two corners";
  EXPECT_LT((first.point - (com + r)).norm(), 1e-12) << "the foot edge's midpoint";
  EXPECT_TRUE(first.stick);
  EXPECT_LE(first.tangential_speed_after, 1e-9);
  EXPECT_NEAR(first.energy_before - first.energy_after, lost, 1e-9 * lost);
  p.friction = 1.0;
  const SettleResult slide = settle(rod, p, q);
  for (const ImpactRecord& i : slide.impacts) EXPECT_GT(i.t, 0.0);
  EXPECT_EQ(slide.painleve, 0);
}

}  // namespace
}  // namespace repose
