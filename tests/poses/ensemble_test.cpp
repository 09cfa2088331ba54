// Batches of drops: determinism across threads and splits, merging, early decision, Wilson intervals.
#include "repose/poses/ensemble.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "repose/error.hpp"
#include "repose/poses/landscape.hpp"
#include "repose/poses/rest_poses.hpp"
#include "repose/poses/sampling.hpp"

namespace {

using namespace repose;

// The sanitizer build runs the engine ~200x slower: it checks the same properties on fewer drops.
#ifdef NDEBUG
constexpr bool kOptimised = true;
#else
constexpr bool kOptimised = false;
#endif
// n drops in the optimised build, max(2, n / 20) in debug and sanitizer builds.
constexpr std::uint64_t drops(std::uint64_t n) { return kOptimised ? n : std::max<std::uint64_t>(2, n / 20); }

struct Study {
  Particle particle;
  RestLandscape landscape;
  RestPoseCatalog catalog;
  explicit Study(const std::string& spec, double persistence = 0)
      : particle(load_particle(spec, 1.0)),
        landscape(compute_rest_landscape(particle)),
        catalog(catalog_rest_poses(particle, landscape, persistence * particle.length)) {}
  EnsembleTally run(DropRange drops, int threads, PoseMethod method = PoseMethod::dynamic,
                    bool decide_early = true) const {
    EnsembleOptions o;
    o.seed = 42;
    o.drops = drops;
    o.threads = threads;
    o.method = method;
    o.decide_early = decide_early;
    o.params.damping = 0.05 * particle.mass.mass * std::sqrt(o.params.gravity * std::pow(particle.length, 3));
    return run_ensemble(particle, landscape, catalog, o);
  }
};

// Everything but the wall-clock time, bit for bit.
void expect_same_tally(const EnsembleTally& a, const EnsembleTally& b) {
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.method, b.method);
  ASSERT_EQ(a.ranges.size(), b.ranges.size());
  for (std::size_t r = 0; r < a.ranges.size(); ++r) {
    EXPECT_EQ(a.ranges[r].begin, b.ranges[r].begin);
    EXPECT_EQ(a.ranges[r].end, b.ranges[r].end);
  }
  EXPECT_EQ(a.status_counts, b.status_counts);
  EXPECT_EQ(a.decided_early, b.decided_early);
  EXPECT_EQ(a.steps, b.steps);
  ASSERT_EQ(a.poses.size(), b.poses.size());
  for (std::size_t p = 0; p < a.poses.size(); ++p) {
    EXPECT_EQ(a.poses[p].count, b.poses[p].count) << "pose " << p;
    EXPECT_EQ(a.poses[p].first_drop, b.poses[p].first_drop) << "pose " << p;
    EXPECT_EQ(a.poses[p].orientation.coeffs(), b.poses[p].orientation.coeffs()) << "pose " << p;
  }
}

TEST(Ensemble, OneAndTwoThreadsGiveIdenticalTallies) {
  const Study s("irregular:seed=3");
  expect_same_tally(s.run({0, drops(300)}, 1), s.run({0, drops(300)}, 2));
  expect_same_tally(s.run({0, 2000}, 1, PoseMethod::quasi_static),
                    s.run({0, 2000}, 2, PoseMethod::quasi_static));
}

TEST(Ensemble, SplitRunsMergeIntoTheWholeRun) {
  const Study s("box:x=1,y=2,z=3");
  const std::uint64_t n = 2 * drops(200);
  const EnsembleTally whole = s.run({0, n}, 2);
  const EnsembleTally merged = merge_tallies(s.run({n / 2, n}, 1), s.run({0, n / 2}, 2));
  expect_same_tally(whole, merged);
  EXPECT_EQ(merged.drops(), n);
  std::uint64_t counted = 0;
  for (const PoseTally& p : whole.poses) counted += p.count;
  EXPECT_EQ(counted + whole.status_counts[2] + whole.status_counts[3], n);
}

TEST(Ensemble, MergeRejectsOverlapsAndMismatches) {
  const Study s("box:x=1,y=1,z=1");
  const EnsembleTally a = s.run({0, 20}, 1), b = s.run({10, 30}, 1);
  EXPECT_THROW(merge_tallies(a, b), Error);
  EnsembleTally other_seed = s.run({20, 30}, 1);
  other_seed.seed = 43;
  EXPECT_THROW(merge_tallies(a, other_seed), Error);
  EXPECT_THROW(merge_tallies(a, s.run({20, 30}, 1, PoseMethod::quasi_static)), Error);
}

// Stopping a drop once its energy is below the barrier of the pose it rolls into must not change where it
// rests: the engine never gains energy (tests/sim), so the particle cannot climb out. Checked drop by drop
// through the tallies of single-drop batches.
TEST(Ensemble, EarlyDecisionNeverChangesThePose) {
  for (const char* spec : {"irregular:seed=1", "box:x=1,y=2,z=3", "cylinder:r=0.5,h=0.6,n=32"}) {
    const Study s(spec);
    for (std::uint64_t i = 0; i < drops(60); ++i) {
      const EnsembleTally early = s.run({i, i + 1}, 1, PoseMethod::dynamic, true);
      const EnsembleTally full = s.run({i, i + 1}, 1, PoseMethod::dynamic, false);
      for (std::size_t p = 0; p < early.poses.size(); ++p)
        ASSERT_EQ(early.poses[p].count, full.poses[p].count) << spec << " drop " << i << " pose " << p;
      EXPECT_LE(early.steps, full.steps);
    }
  }
}

TEST(Ensemble, SmoothParticleEarlyDecisionMatchesFullSettle) {
  const Study s("ellipsoid:a=0.625,b=0.5,c=0.285,n=6", 0.01);
  ASSERT_EQ(s.catalog.poses.size(), 2u);  // the two ends of the shortest axis
  const std::uint64_t n = drops(12);
  const EnsembleTally early = s.run({0, n}, 2, PoseMethod::dynamic, true);
  const EnsembleTally full = s.run({0, n}, 2, PoseMethod::dynamic, false);
  for (std::size_t p = 0; p < 2; ++p) EXPECT_EQ(early.poses[p].count, full.poses[p].count);
  EXPECT_EQ(early.status_counts[1], n);
  // Not a tolerance: measured 7.2× fewer steps.
  EXPECT_LT(early.steps * 4, full.steps) << "early decision should save most of the rocking";
}

// The early decision is exact only below the barrier: a particle whose energy exceeds the barrier of the
// pose it is heading for may still climb over it. Box with half edges A = 0.5, B = 1, C = 1.5 (closed
// forms): the ±x and ±y poses are left over the edges parallel to z, whose saddle puts the centre of mass at
// sqrt(A² + B²) = sqrt(1.25) above the wall; the ±z poses need sqrt(A² + C²) = sqrt(2.5). Drops whose start
// direction d0 rolls to an x or y face are released from rest with the lowest point at a height that puts
// the centre of mass 1e-8·L above sqrt(1.25) (its height above the lowest point is the box's support
// function A|d0x| + B|d0y| + C|d0z|). During the fall the energy stays above that barrier (the engine's
// drift is < 1e-8·m·g·L, tests/sim), so no decision may come before the touchdown: the run takes at least
// the free-fall time sqrt(2·height/g) in steps of dt. It rests where the full run rests.
TEST(Ensemble, EnergyAboveThePoseBarrierIsNotDecidedInTheAir) {
  const Study s("box:x=1,y=2,z=3");
  const double A = 0.5, B = 1.0, C = 1.5;
  const double low_barrier = std::sqrt(A * A + B * B);
  const double high_barrier = std::sqrt(A * A + C * C);
  EnsembleOptions o;
  o.seed = 42;
  o.params.dt = 1e-3 * std::sqrt(s.particle.length / o.params.gravity);
  o.params.damping =
      0.05 * s.particle.mass.mass * std::sqrt(o.params.gravity * std::pow(s.particle.length, 3));
  const int wanted = kOptimised ? 3 : 1;
  int tested = 0;
  for (std::uint64_t i = 0; tested < wanted && i < 200; ++i) {
    const Vec3 d0 = drop_orientation(o.seed, i).conjugate() * Vec3(0, 0, -1);
    const int face = quasi_static_rest_face(s.particle, s.landscape, d0);
    const Vec3& n = s.particle.hull.faces[static_cast<std::size_t>(face)].normal;
    const double above_lowest = A * std::abs(d0.x()) + B * std::abs(d0.y()) + C * std::abs(d0.z());
    if (std::abs(n.z()) > 0.5 || above_lowest > low_barrier - 0.2) continue;  // a z face, or a short fall
    ++tested;
    // The catalogue's barriers are the closed forms (1e-12: round-off of a square root; measured 0).
    const RestPose& pose = s.catalog.poses[static_cast<std::size_t>(s.catalog.face_pose[face])];
    ASSERT_NEAR(pose.barrier, low_barrier, 1e-12);
    double highest = 0;
    for (const RestPose& p : s.catalog.poses) highest = std::max(highest, p.barrier);
    ASSERT_NEAR(highest, high_barrier, 1e-12);

    o.params.drop_height = low_barrier + 1e-8 * s.particle.length - above_lowest;
    o.decide_early = true;
    const DropOutcome early = simulate_drop(s.particle, s.landscape, s.catalog, o, i);
    o.decide_early = false;
    const DropOutcome full = simulate_drop(s.particle, s.landscape, s.catalog, o, i);
    const double fall = std::sqrt(2 * o.params.drop_height / o.params.gravity);
    // Steps are dt long or shorter (cut at events), so the touchdown takes at least floor(fall / dt) steps.
    EXPECT_GE(early.steps, static_cast<long>(std::floor(fall / o.params.dt))) << "drop " << i;
    EXPECT_EQ(early.status, Status::rest) << "drop " << i;
    EXPECT_EQ(early.pose, full.pose) << "drop " << i;
  }
  EXPECT_EQ(tested, wanted);
}

// Published values (Newcombe, Stat. Med. 17:857, 1998, Table II): 81/263 → [0.2553, 0.3662] and 0/10 →
// [0, 0.2775], to 4 decimals, so 5e-5 (half a unit of the last digit; measured 1.2e-5, 9.6e-6, 3.3e-5). The
// same bounds to 15 digits, evaluated at 30 digits (mpmath) from (x + z²/2 ± z·sqrt(x(n − x)/n + z²/4)) /
// (n + z²), z = sqrt(2)·erfinv(0.95): 1e-12 relative is a round-off margin (measured ≤ 2.3e-16).
TEST(Ensemble, ATossedDropIsTheSettleOfItsOwnToss) {
  // Drop i of a tossed batch is exactly settle() from drop_orientation(seed, i) with drop_toss(seed, i)'s
  // velocity and spin (full settle, so the rest face itself is compared, and the steps).
  const Study s("box:x=1,y=2,z=3");
  EnsembleOptions o;
  o.seed = 42;
  o.params.drop_height = 0.5;
  o.params.restitution = 0.5;
  o.params.friction = 0.4;
  o.toss = {2.0, 5.0};
  o.decide_early = false;
  for (std::uint64_t i = 0; i < drops(40); ++i) {
    const DropOutcome d = simulate_drop(s.particle, s.landscape, s.catalog, o, i);
    SettleParams p = o.params;
    const Toss toss = drop_toss(o.seed, i, o.toss);
    p.velocity = toss.velocity;
    p.spin = toss.spin;
    const SettleResult r = settle(s.particle, p, drop_orientation(o.seed, i));
    ASSERT_EQ(r.status, Status::rest) << i;
    EXPECT_EQ(d.pose, s.catalog.face_pose[r.rest_face]) << i;
    EXPECT_EQ(d.steps, r.steps) << i;
    EXPECT_EQ(d.orientation.coeffs(), r.orientation.coeffs()) << i;
  }
}

TEST(Ensemble, WilsonIntervalMatchesPublishedValues) {
  const auto a = wilson_interval(81, 263);
  EXPECT_NEAR(a[0], 0.2553, 5e-5);
  EXPECT_NEAR(a[1], 0.3662, 5e-5);
  EXPECT_NEAR(a[0], 0.255288519878274226, 1e-12 * a[0]);
  EXPECT_NEAR(a[1], 0.366209576982800070, 1e-12 * a[1]);
  const auto b = wilson_interval(0, 10);
  EXPECT_EQ(b[0], 0.0);
  EXPECT_NEAR(b[1], 0.2775, 5e-5);
  EXPECT_NEAR(b[1], 0.277532799862889253, 1e-12 * b[1]);
  const auto c = wilson_interval(10, 10);
  EXPECT_NEAR(c[0], 1 - 0.2775, 5e-5);
  EXPECT_NEAR(c[0], 0.722467200137110747, 1e-12 * c[0]);
  EXPECT_EQ(c[1], 1.0);
  // A probability bound never leaves [0, 1], even where round-off would take it out: n − 1 of n = 10^15 at
  // z = 10 evaluates to 1 + 2^-52 before the clamp (checked in double precision by the same formula).
  const auto d = wilson_interval(999'999'999'999'999, 1'000'000'000'000'000, 10.0);
  EXPECT_LE(d[1], 1.0);
  EXPECT_GT(d[1], 1.0 - 1e-12);
}

// A caller's cancel flag (Ctrl-C in Python) stops a run between drops with repose::Cancelled; an unset or
// false flag changes nothing.
TEST(Ensemble, ACancelledRunStopsWithCancelled) {
  const Study s("box:x=1,y=1,z=1");
  EnsembleOptions o;
  o.drops = {0, 200};
  o.threads = 2;
  const EnsembleTally plain = run_ensemble(s.particle, s.landscape, s.catalog, o);
  std::atomic<bool> cancel{false};
  o.cancel = &cancel;
  const EnsembleTally watched = run_ensemble(s.particle, s.landscape, s.catalog, o);
  for (std::size_t p = 0; p < plain.poses.size(); ++p)
    EXPECT_EQ(plain.poses[p].count, watched.poses[p].count);
  cancel = true;
  EXPECT_THROW(run_ensemble(s.particle, s.landscape, s.catalog, o), Cancelled);
}

TEST(Ensemble, RejectsBadOptions) {
  const Study s("box:x=1,y=1,z=1");
  EnsembleOptions o;
  o.drops = {5, 3};
  EXPECT_THROW(run_ensemble(s.particle, s.landscape, s.catalog, o), Error);
  o.drops = {0, 3};
  o.threads = -1;
  EXPECT_THROW(run_ensemble(s.particle, s.landscape, s.catalog, o), Error);
  o.threads = 1;
  o.params.dt = -1;
  EXPECT_THROW(run_ensemble(s.particle, s.landscape, s.catalog, o), Error);
  EXPECT_THROW(parse_pose_method("static"), Error);
}

}  // namespace
