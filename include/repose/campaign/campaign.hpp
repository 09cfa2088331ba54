// Rest-pose studies of many particles as one job, on one process or across an MPI job, resumable.
//
// Each particle's drops are cut into work items. Any rank can run an item (drop i depends only on the seed
// and i), and the root merges the items' tallies, which is exact in any order, so the result is identical
// to one uninterrupted run on one process. With a checkpoint directory, the root rewrites a particle's
// merged result there (atomically: temporary file + rename) after every item it absorbs; a rerun of the
// same command reads those files and runs only the drops they do not hold.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "repose/campaign/runner.hpp"
#include "repose/poses/ensemble.hpp"
#include "repose/poses/study.hpp"

namespace repose {

struct CampaignParticle {
  std::string name;       ///< unique, usable as a file name: the file's stem, or the sanitised shape spec
  std::string source;     ///< mesh file or shape spec
  MeshOptions mesh = {};  ///< how its file becomes a particle (scale, inertia model, repair)
};

/// The particles of a job. Each input is a mesh file (STL, OBJ, PLY, OFF), a shape spec, or a directory
/// (its mesh files, sorted by name, not recursive). A manifest (if not empty) lists one input per line;
/// blank lines and lines starting with '#' are skipped, and relative paths are relative to the manifest's
/// directory. Every particle reads its file with `mesh`; a manifest line may override those options for its
/// own input after its path: `scan.ply --mesh-units mm --inertia convex` (options --scale S, --mesh-units
/// mm|cm|m|in, --inertia exact|convex|shell, --repair, --largest-component; `lengths_in_cm`: the run's
/// lengths are centimetres, so --mesh-units converts to them). Throws repose::Error for a missing file, an
/// empty directory, a bad manifest option or two particles with one name.
std::vector<CampaignParticle> resolve_particles(const std::vector<std::string>& inputs,
                                                const std::string& manifest = "",
                                                const MeshOptions& mesh = {}, bool lengths_in_cm = false);

/// The drops of `wanted` not in `done` (disjoint, ascending). Throws repose::Error if `done` holds a drop
/// outside `wanted`.
std::vector<DropRange> remaining_ranges(DropRange wanted, const std::vector<DropRange>& done);

/// Default drops per work item: about 64 items per particle, at least 128 drops per thread (so every thread
/// of a rank has whole blocks of drops) and at most 65,536 (so a kill loses little).
std::uint64_t auto_chunk(std::uint64_t drops, int threads);

/// Cuts every particle's remaining ranges into items of at most `chunk` drops, ordered for load balance:
/// the costliest items first (estimated cost = drops × cost_per_drop[particle]), so that small items fill
/// in at the end (longest-processing-time-first). Ties keep particle and drop order.
std::vector<WorkItem> plan_work(const std::vector<std::vector<DropRange>>& remaining,
                                const std::vector<double>& cost_per_drop, std::uint64_t chunk);

struct CampaignOptions {
  StudySettings settings;
  DropRange drops;             ///< the same drop indices for every particle
  int threads = 0;             ///< threads per rank; 0 = all cores
  std::uint64_t chunk = 0;     ///< drops per work item; 0 = auto_chunk
  std::string checkpoint_dir;  ///< empty: no checkpoint (and no resume)
  /// Root only: called once the drops are planned, with the number still to run and each particle's study
  /// so far (its header: name, L, mass, hull; and what the checkpoint held), in input order.
  std::function<void(std::uint64_t remaining, const std::vector<PosesStudy>& prepared)> on_start;
  /// Root only: every study is complete (one per particle, in input order). Called before the checkpoint is
  /// removed, so that results written here are on disk before it goes.
  std::function<void(const std::vector<PosesStudy>& studies)> on_complete;
  std::atomic<std::uint64_t>* progress = nullptr;  ///< root only: finished drops
  /// Root only, with a checkpoint: the drops the checkpoint files hold (found on resuming, then each item's
  /// once its file is renamed into place), for a message on interruption.
  std::atomic<std::uint64_t>* kept = nullptr;
};

/// Runs the job on `runner` (collective). `particles` is called on the root only (it may also check the
/// caller's options and throw). On the root: returns one complete study per particle, in input order; on
/// other ranks: an empty vector. The checkpoint files are removed once every particle is complete. Throws
/// repose::Error on the root for bad input or an incompatible checkpoint, and RootFailed on the others.
std::vector<PosesStudy> run_campaign(const std::function<std::vector<CampaignParticle>()>& particles,
                                     const CampaignOptions& options, WorkRunner& runner);

/// The checkpoint file of a particle.
std::string checkpoint_path(const std::string& checkpoint_dir, const CampaignParticle& particle);

}  // namespace repose
