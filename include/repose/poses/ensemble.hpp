// Batches of drops: how often a particle comes to rest in each of its rest poses.
//
// Drop i starts at drop_orientation(seed, i). The batch runs any sub-range [begin, end) of drop indices on
// any number of threads; its tally holds only integer counts and, per pose, the lowest drop index that ended
// there, so tallies of disjoint sub-ranges merge into exactly the tally of their union.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "repose/model/params.hpp"
#include "repose/model/particle.hpp"
#include "repose/poses/rest_poses.hpp"
#include "repose/poses/sampling.hpp"
#include "repose/sim/settle.hpp"

namespace repose {

enum class PoseMethod {
  dynamic,       ///< the settling engine (momentum, impacts, damping)
  quasi_static,  ///< steepest descent of the centre-of-mass height from the initial down direction
};

const char* to_string(PoseMethod method);
/// Parses "dynamic" or "quasi-static"; throws repose::Error otherwise.
PoseMethod parse_pose_method(const std::string& text);

/// A half-open range of drop indices [begin, end).
struct DropRange {
  std::uint64_t begin = 0;
  std::uint64_t end = 0;
  std::uint64_t size() const { return end - begin; }
};

struct EnsembleOptions {
  std::uint64_t seed = 1;
  DropRange drops;
  PoseMethod method = PoseMethod::dynamic;
  SettleParams params;  ///< for the dynamic method
  /// Dynamic method: drop i is tossed with drop_toss(seed, i, toss) (its velocity and spin replace
  /// params.velocity and params.spin) when the distribution is active.
  TossDistribution toss;
  /// Dynamic method: stop a drop as soon as its pose is decided — it touches the wall and its mechanical
  /// energy is below m·g·(barrier of the pose it is rolling into) — instead of simulating the last, slow
  /// rocking. Exact by energy: the engine never gains energy, so the particle cannot climb out.
  bool decide_early = true;
  /// Simulate each pose's first drop to rest if it was decided early, for its final orientation. Off for
  /// the pieces of a larger batch: only the first drop over all pieces needs it (PoseTally::settled).
  bool finish_representatives = true;
  int threads = 0;                                 ///< 0 = all cores
  std::atomic<std::uint64_t>* progress = nullptr;  ///< if set, incremented once per finished drop
  /// If set, read between drops: once true, the run stops and throws repose::Cancelled (an interrupt from
  /// the caller, e.g. Ctrl-C in Python).
  const std::atomic<bool>* cancel = nullptr;
};

/// What one pose collected.
struct PoseTally {
  std::uint64_t count = 0;
  std::uint64_t first_drop = UINT64_MAX;  ///< lowest drop index that ended in this pose
  Quat orientation = Quat::Identity();    ///< final orientation (body → world) of `first_drop`
  /// False if `first_drop` was stopped once its pose was decided and not finished (see
  /// EnsembleOptions::finish_representatives): `orientation` is then where it was stopped, not its rest.
  bool settled = true;
};

/// Status counts: index by static_cast<int>(Status) (running is never counted).
using StatusCounts = std::array<std::uint64_t, 4>;

struct EnsembleTally {
  std::uint64_t seed = 0;
  PoseMethod method = PoseMethod::dynamic;
  std::vector<DropRange> ranges;    ///< the drops counted: disjoint, ascending
  std::vector<PoseTally> poses;     ///< one per catalogue pose
  StatusCounts status_counts{};     ///< how the runs ended (quasi-static: all `rest`)
  std::uint64_t decided_early = 0;  ///< dynamic runs stopped once their pose was decided
  std::uint64_t steps = 0;          ///< engine steps, all runs
  double seconds = 0;               ///< wall-clock time (timing: differs run to run)

  std::uint64_t drops() const;  ///< total number of drops counted
};

/// How one drop ended.
struct DropOutcome {
  int pose = -1;  ///< catalogue index of the rest pose; −1 if the run did not rest
  Status status = Status::running;
  bool decided_early = false;           ///< stopped once the pose was decided (EnsembleOptions::decide_early)
  long steps = 0;                       ///< engine steps taken
  Quat orientation = Quat::Identity();  ///< final orientation (body → world); not meaningful if decided_early
};

/// Drop `index` alone (options.seed, method, params and decide_early apply; options.drops is ignored). For a
/// program that wants the pose of particular drops, and for benchmarks.
DropOutcome simulate_drop(const Particle& particle, const RestLandscape& landscape,
                          const RestPoseCatalog& catalog, const EnsembleOptions& options,
                          std::uint64_t index);

/// The cores this process may run on (its CPU affinity: a container's, taskset's or a batch job's share, as
/// TBB counts them; at least 1): what "all cores" means for a thread count of 0.
int available_cores();

/// Runs drops [options.drops.begin, options.drops.end). Throws repose::Error for invalid options.
EnsembleTally run_ensemble(const Particle& particle, const RestLandscape& landscape,
                           const RestPoseCatalog& catalog, const EnsembleOptions& options);

/// The tally of the union of two batches over disjoint drop ranges of the same particle, seed and method.
/// Throws repose::Error if they differ in seed, method or pose count, or if their ranges overlap.
EnsembleTally merge_tallies(const EnsembleTally& a, const EnsembleTally& b);

/// 95 % Wilson score interval for `count` successes in `n` trials (Wilson, JASA 1927): [lo, hi].
std::array<double, 2> wilson_interval(std::uint64_t count, std::uint64_t n, double z = 1.959963984540054);

}  // namespace repose
