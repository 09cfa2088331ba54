#include "repose/poses/ensemble.hpp"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>

#include "repose/error.hpp"
#include "repose/poses/sampling.hpp"

namespace repose {

namespace {

// Drops per task: large enough to amortise scheduling, small enough to balance 2 to 64 cores.
constexpr std::uint64_t kGrain = 64;

const Vec3 kDown(0, 0, -1);

// The orientation closest to `q` that puts `face` flush on the wall: tilt `q` by the smallest rotation taking
// the face's outward normal to world −z.
Quat flush_orientation(const Particle& particle, int face, const Quat& q) {
  const Vec3 normal_world = q * particle.hull.faces[face].normal;
  return (Quat::FromTwoVectors(normal_world, kDown) * q).normalized();
}

double highest_barrier_of(const RestPoseCatalog& catalog) {
  double m = -std::numeric_limits<double>::infinity();
  for (const RestPose& pose : catalog.poses) m = std::max(m, pose.barrier);
  return m;
}

// The engine's parameters for drop `index`: the batch's, with the drop's own toss if there is one.
SettleParams drop_params(const EnsembleOptions& options, std::uint64_t index) {
  SettleParams params = options.params;
  if (options.toss.active()) {
    const Toss toss = drop_toss(options.seed, index, options.toss);
    params.velocity = toss.velocity;
    params.spin = toss.spin;
  }
  return params;
}

// Early decision stays exact with tosses and rebounds: the centre of mass is never below h(down) (nothing
// goes below the wall, in flight either) and no impact creates energy, so the argument below holds for every
// phase of the motion.
DropOutcome run_dynamic_drop(const Particle& particle, const RestLandscape& landscape,
                             const RestPoseCatalog& catalog, const SettleParams& params, const Quat& start,
                             bool decide_early) {
  Settler settler(particle, params, start);
  const double weight = particle.mass.mass * params.gravity;
  // Margin on the energy test: the engine's energy drift is < 1e-8·m·g·L at the default tolerance (the
  // property sweep, tests/sim).
  const double margin = 1e-6 * particle.length;
  const double highest_barrier = highest_barrier_of(catalog);
  DropOutcome out;
  int lowest_vertex = 0;  // where the check's walk to the lowest hull vertex starts (the last one found)
  // The check (a walk on the landscape from the current direction) costs less than a step now that a drop
  // takes ~20 steps, so it is made before the first step (a drop released below the barrier of the pose it
  // rolls into is decided at once) and after every step.
  auto decided = [&] {
    const Sample sample = settler.sample();
    // The centre of mass is never below h(down) (no vertex below the wall), so this level bounds how high
    // on the COM-height landscape the particle can still climb.
    const double level = (sample.kinetic_energy + sample.potential_energy) / weight;
    if (!(level < highest_barrier - margin)) return false;
    const Vec3 down = sample.orientation.conjugate() * kDown;
    const int pose = catalog.face_pose[quasi_static_rest_face(particle, landscape, down, lowest_vertex)];
    if (!(level < catalog.poses[pose].barrier - margin)) return false;
    out.pose = pose;
    out.status = Status::rest;
    out.decided_early = true;
    out.steps = settler.result().steps;
    return true;
  };
  if (decide_early && decided()) return out;
  while (settler.step())
    if (decide_early && decided()) return out;
  const SettleResult result = settler.result();
  out.status = result.status;
  out.steps = result.steps;
  out.orientation = result.orientation;
  if (result.status == Status::rest) {
    if (result.rest_face < 0) throw Error(particle.name + ": a run rested on no hull face (internal error)");
    out.pose = catalog.face_pose[result.rest_face];
  }
  return out;
}

DropOutcome run_quasi_static_drop(const Particle& particle, const RestLandscape& landscape,
                                  const RestPoseCatalog& catalog, const Quat& start) {
  const int face = quasi_static_rest_face(particle, landscape, start.conjugate() * kDown);
  DropOutcome out;
  out.pose = catalog.face_pose[face];
  out.status = Status::rest;
  out.orientation = flush_orientation(particle, face, start);
  return out;
}

// The tally of a block of drops.
struct PartialTally {
  EnsembleTally tally;

  explicit PartialTally(std::size_t poses) { tally.poses.resize(poses); }

  void add(std::uint64_t drop, const DropOutcome& outcome) {
    ++tally.status_counts[static_cast<int>(outcome.status)];
    tally.steps += static_cast<std::uint64_t>(outcome.steps);
    if (outcome.decided_early) ++tally.decided_early;
    if (outcome.pose < 0) return;
    PoseTally& pose = tally.poses[outcome.pose];
    ++pose.count;
    if (drop < pose.first_drop) {
      pose.first_drop = drop;
      pose.orientation = outcome.orientation;
      pose.settled = !outcome.decided_early;
    }
  }

  // Integer sums and minima: the result does not depend on the order blocks finish in.
  void absorb(const PartialTally& other) {
    for (int s = 0; s < 4; ++s) tally.status_counts[s] += other.tally.status_counts[s];
    tally.steps += other.tally.steps;
    tally.decided_early += other.tally.decided_early;
    for (std::size_t p = 0; p < tally.poses.size(); ++p) {
      const PoseTally& theirs = other.tally.poses[p];
      PoseTally& ours = tally.poses[p];
      ours.count += theirs.count;
      if (theirs.first_drop < ours.first_drop) {
        ours.first_drop = theirs.first_drop;
        ours.orientation = theirs.orientation;
        ours.settled = theirs.settled;
      }
    }
  }
};

}  // namespace

DropOutcome simulate_drop(const Particle& particle, const RestLandscape& landscape,
                          const RestPoseCatalog& catalog, const EnsembleOptions& options,
                          std::uint64_t index) {
  const Quat start = drop_orientation(options.seed, index);
  return options.method == PoseMethod::dynamic
             ? run_dynamic_drop(particle, landscape, catalog, drop_params(options, index), start,
                                options.decide_early)
             : run_quasi_static_drop(particle, landscape, catalog, start);
}

const char* to_string(PoseMethod method) {
  return method == PoseMethod::dynamic ? "dynamic" : "quasi-static";
}

PoseMethod parse_pose_method(const std::string& text) {
  if (text == "dynamic") return PoseMethod::dynamic;
  if (text == "quasi-static") return PoseMethod::quasi_static;
  throw Error("unknown method '" + text + "' (expected dynamic or quasi-static)");
}

std::uint64_t EnsembleTally::drops() const {
  std::uint64_t n = 0;
  for (const DropRange& r : ranges) n += r.size();
  return n;
}

// std::thread::hardware_concurrency() counts the machine's cores, not those the process may use: an arena of
// that many asked TBB for workers its affinity mask forbids, and TBB printed a warning on every run.
int available_cores() { return std::max(1, tbb::info::default_concurrency()); }

EnsembleTally run_ensemble(const Particle& particle, const RestLandscape& landscape,
                           const RestPoseCatalog& catalog, const EnsembleOptions& options) {
  if (options.drops.end < options.drops.begin)
    throw Error("drop range: end " + std::to_string(options.drops.end) + " is before begin " +
                std::to_string(options.drops.begin));
  if (options.threads < 0)
    throw Error("threads must be >= 0 (0 = all cores), got " + std::to_string(options.threads));
  if (options.method == PoseMethod::dynamic) validate(options.params);
  const auto start_time = std::chrono::steady_clock::now();

  PartialTally total(catalog.poses.size());
  std::mutex total_mutex;
  const auto run_drop = [&](std::uint64_t i) {
    return simulate_drop(particle, landscape, catalog, options, i);
  };
  tbb::task_arena arena(options.threads > 0 ? options.threads : available_cores());
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::uint64_t>(options.drops.begin, options.drops.end, kGrain),
                      [&](const tbb::blocked_range<std::uint64_t>& block) {
                        PartialTally local(catalog.poses.size());
                        for (std::uint64_t i = block.begin(); i != block.end(); ++i) {
                          if (options.cancel && options.cancel->load(std::memory_order_relaxed)) return;
                          local.add(i, run_drop(i));
                          if (options.progress) options.progress->fetch_add(1, std::memory_order_relaxed);
                        }
                        const std::lock_guard lock(total_mutex);
                        total.absorb(local);
                      });
  });

  if (options.cancel && options.cancel->load()) throw Cancelled("interrupted");

  // A pose's representative is its first drop's final orientation; if that drop stopped early, finish it.
  for (std::size_t p = 0; p < catalog.poses.size() && options.finish_representatives; ++p) {
    PoseTally& pose = total.tally.poses[p];
    if (pose.count == 0 || pose.settled) continue;
    const DropOutcome full =
        run_dynamic_drop(particle, landscape, catalog, drop_params(options, pose.first_drop),
                         drop_orientation(options.seed, pose.first_drop), false);
    // Should the full run end elsewhere (it must not, by the energy argument), fall back to the start
    // orientation set flush on the pose's face, which still shows the pose.
    pose.orientation = full.pose == static_cast<int>(p)
                           ? full.orientation
                           : flush_orientation(particle, catalog.poses[p].face,
                                               drop_orientation(options.seed, pose.first_drop));
    pose.settled = true;
  }

  EnsembleTally tally = std::move(total.tally);
  tally.seed = options.seed;
  tally.method = options.method;
  if (options.drops.size() > 0) tally.ranges.push_back(options.drops);
  tally.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return tally;
}

EnsembleTally merge_tallies(const EnsembleTally& a, const EnsembleTally& b) {
  if (a.seed != b.seed)
    throw Error("cannot merge results of different seeds (" + std::to_string(a.seed) + " and " +
                std::to_string(b.seed) + ")");
  if (a.method != b.method)
    throw Error(std::string("cannot merge results of different methods (") + to_string(a.method) + " and " +
                to_string(b.method) + ")");
  if (a.poses.size() != b.poses.size())
    throw Error("cannot merge results with different rest-pose catalogues (" +
                std::to_string(a.poses.size()) + " and " + std::to_string(b.poses.size()) + " poses)");
  EnsembleTally m = a;
  m.ranges.insert(m.ranges.end(), b.ranges.begin(), b.ranges.end());
  std::sort(m.ranges.begin(), m.ranges.end(),
            [](const DropRange& x, const DropRange& y) { return x.begin < y.begin; });
  std::vector<DropRange> coalesced;
  for (const DropRange& r : m.ranges) {
    if (!coalesced.empty() && r.begin < coalesced.back().end)
      throw Error("cannot merge overlapping drop ranges [" + std::to_string(coalesced.back().begin) + ", " +
                  std::to_string(coalesced.back().end) + ") and [" + std::to_string(r.begin) + ", " +
                  std::to_string(r.end) + ")");
    if (!coalesced.empty() && r.begin == coalesced.back().end)
      coalesced.back().end = r.end;
    else
      coalesced.push_back(r);
  }
  m.ranges = std::move(coalesced);
  for (int s = 0; s < 4; ++s) m.status_counts[s] += b.status_counts[s];
  m.decided_early += b.decided_early;
  m.steps += b.steps;
  m.seconds += b.seconds;
  for (std::size_t p = 0; p < m.poses.size(); ++p) {
    m.poses[p].count += b.poses[p].count;
    if (b.poses[p].first_drop < m.poses[p].first_drop) {
      m.poses[p].first_drop = b.poses[p].first_drop;
      m.poses[p].orientation = b.poses[p].orientation;
      m.poses[p].settled = b.poses[p].settled;
    }
  }
  return m;
}

std::array<double, 2> wilson_interval(std::uint64_t count, std::uint64_t n, double z) {
  if (n == 0) return {0.0, 1.0};
  const double nn = static_cast<double>(n);
  const double p = static_cast<double>(count) / nn;
  const double z2 = z * z;
  const double centre = (p + z2 / (2 * nn)) / (1 + z2 / nn);
  const double half = z / (1 + z2 / nn) * std::sqrt(p * (1 - p) / nn + z2 / (4 * nn * nn));
  // At k = 0 and k = n the bounds are exactly 0 and 1; say so rather than leave round-off.
  return {count == 0 ? 0.0 : std::max(0.0, centre - half), count == n ? 1.0 : std::min(1.0, centre + half)};
}

}  // namespace repose
