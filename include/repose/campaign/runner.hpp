// Where work items run: in this process (LocalRunner) or on every rank of an MPI job (mpi_runner.hpp).
//
// A runner knows nothing about particles or drops beyond the item it hands out. The root (rank 0) holds the
// list of items; `work` may run on any rank and returns its result as text, which reaches `absorb` on the
// root. Results arrive in completion order, so whatever `absorb` builds must not depend on that order (rest-
// pose tallies merge exactly, whatever the order).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "repose/poses/ensemble.hpp"

namespace repose {

/// One piece of a job: drops `drops` of particle number `particle`.
struct WorkItem {
  std::uint32_t particle = 0;
  DropRange drops;
};

/// Raised on a rank other than the root when the root could not start the job or a run failed: exit code 2
/// if the root's error is a repose::Error (bad input), else 1. The root raises the error itself; the other
/// ranks should exit quietly with that code, so that the error is reported once, and only after the root has
/// reported it (an MPI launcher ends the whole job when one rank exits non-zero; see cmd_poses.cpp).
struct RootFailed {
  int exit_code = 2;
};

class WorkRunner {
 public:
  /// Runs `item`; increments `progress` (if not null) once per finished drop. Returns the serialised result.
  using Work = std::function<std::string(const WorkItem& item, std::atomic<std::uint64_t>* progress)>;
  /// Takes one result, on the root only, one call at a time.
  using Absorb = std::function<void(const WorkItem& item, const std::string& result)>;

  virtual ~WorkRunner() = default;

  virtual int rank() const = 0;  ///< 0 on the root
  virtual int ranks() const = 0;
  virtual int ranks_on_this_node() const = 0;
  bool is_root() const { return rank() == 0; }

  /// Collective: every rank returns the root's `value` (the others' argument is ignored).
  virtual std::string broadcast(const std::string& value) = 0;

  /// Collective. On the root: runs every item of `items` on some rank (the root included) and absorbs each
  /// result; `progress` (root only, may be null) counts finished drops. On other ranks: runs the items the
  /// root sends until it says stop. Returns on every rank only once the root is done. If `work` or `absorb`
  /// throws, no new items are handed out, the items already running finish, the root rethrows the first
  /// error and the other ranks throw RootFailed with its exit code.
  virtual void run(const std::vector<WorkItem>& items, const Work& work, const Absorb& absorb,
                   std::atomic<std::uint64_t>* progress) = 0;
};

/// True if this process was started by an MPI launcher (mpirun, mpiexec, srun): its environment names a rank
/// (OMPI_COMM_WORLD_SIZE, PMIX_RANK, PMI_RANK, PMI_SIZE or MV2_COMM_WORLD_RANK).
bool launched_by_mpi();

/// Collective: runs `prepare` on the root and returns its result on every rank. If it throws, the root
/// rethrows and every other rank throws RootFailed.
std::string prepare_on_root(WorkRunner& runner, const std::function<std::string()>& prepare);

/// Runs every item in this process, in the given order. (Not final: a test can override run() to finish items
/// in another order or to stop midway.)
class LocalRunner : public WorkRunner {
 public:
  int rank() const override { return 0; }
  int ranks() const override { return 1; }
  int ranks_on_this_node() const override { return 1; }
  std::string broadcast(const std::string& value) override { return value; }
  void run(const std::vector<WorkItem>& items, const Work& work, const Absorb& absorb,
           std::atomic<std::uint64_t>* progress) override {
    for (const WorkItem& item : items) absorb(item, work(item, progress));
  }
};

}  // namespace repose
