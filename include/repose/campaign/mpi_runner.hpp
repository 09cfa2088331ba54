// Work items across the ranks of an MPI job (built with -DREPOSE_MPI=ON; link repose::mpi).
//
// Rank 0 hands out items one at a time as ranks ask for them (dynamic load balancing: a rank that drew a
// cheap particle simply asks again sooner) and runs items itself on a second thread while it serves. Only
// the main thread of each rank calls MPI (MPI_THREAD_FUNNELED); the drops of an item run on the rank's own
// threads.
#pragma once

#include <memory>

#include "repose/campaign/runner.hpp"

namespace repose {

/// Initialises MPI and returns a runner over all ranks of MPI_COMM_WORLD; MPI is finalised when the runner
/// is destroyed (one runner per process). Throws repose::Error if MPI cannot give MPI_THREAD_FUNNELED.
std::unique_ptr<WorkRunner> make_mpi_runner();

}  // namespace repose
