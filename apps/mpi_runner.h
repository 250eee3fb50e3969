// Studies over the ranks of an MPI job (OpenMPI from Debian; docs/study.md,
// "Parallel and distributed studies"). `mpirun -n N evas study ...` starts N
// copies of evas: rank 0 runs the command as usual and is the coordinator;
// ranks 1..N-1 only run tasks (study/task.h) rank 0 sends them and send back
// the results' exact bytes. Rank 0 runs tasks of its own in a forked local
// worker meanwhile, so all N ranks compute. Tasks are handed out one at a time
// as ranks become free, so long and short runs balance.
//
// Without MPI support compiled in, a rank of a multi-rank job says so and
// exits 1 (each rank would otherwise run the whole study on its own).
#pragma once

#include <memory>

#include "study/task_runner.h"

namespace evas::cli {

struct MpiJob {
  bool active = false;  ///< this process is one of 2+ ranks of an MPI job
  int rank = 0, size = 1;
};

/// Starts MPI when the environment says this process was launched by an MPI
/// launcher (OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK) with 2+ ranks.
/// Throws InputError when it was and this evas has no MPI.
MpiJob mpi_start(int* argc, char*** argv);

/// The job mpi_start found (inactive before it or without MPI).
const MpiJob& mpi_job();

/// Ranks 1..N-1: runs the tasks rank 0 sends until it says stop, then ends
/// MPI. Returns the process's exit code.
int mpi_worker_loop();

/// Rank 0's task runner (the study's --jobs is then the number of ranks).
std::shared_ptr<study::TaskRunner> mpi_runner();

/// Rank 0 at exit: collects results still under way, tells every worker rank
/// to stop and ends MPI. Nothing when MPI is not active.
void mpi_finish();

}  // namespace evas::cli
