// Studies over the ranks of an MPI job (OpenMPI from Debian; docs/study.md,
// "Parallel and distributed studies"). `mpirun -n N evas study ...` starts N
// copies of evas: rank 0 runs the command as usual and is the coordinator;
// ranks 1..N-1 only run tasks (study/task.h) rank 0 sends them and send back
// the results' exact bytes. Rank 0 runs tasks of its own meanwhile, so all N
// ranks compute. Tasks are handed out one at a time as ranks become free, so
// long and short runs balance.
//
// Every rank runs its tasks in a forked worker process (study::LocalWorker,
// the child never calls MPI): a run that crashes ends as one failed task, a
// run stuck inside one step is killed after the hard limit of its --max-wall,
// and a cancel from rank 0 (its study was stopped) kills the run at once. A
// worker rank that gets SIGINT/SIGTERM itself fails its task with the signal,
// tells rank 0 it serves no more and waits for the end of the job. Forking
// after MPI_Init is safe with the shared-memory and TCP transports Debian's
// Open MPI uses on one machine or Ethernet; InfiniBand verbs transports may
// not allow it (docs/study.md).
//
// Without MPI support compiled in, a rank of a multi-rank job says so and
// exits 1 (each rank would otherwise run the whole study on its own).
#pragma once

#include <memory>
#include <string>

#include "study/task_runner.h"

namespace evas::cli {

struct MpiJob {
  bool active = false;  ///< this process is one of 2+ ranks of an MPI job
  int rank = 0, size = 1;
};

/// Starts MPI when the environment says this process was launched by an MPI
/// launcher (OMPI_COMM_WORLD_SIZE, PMI_SIZE, or PMIX_RANK with PMIX_SIZE or
/// Slurm's task count) with 2+ ranks. Only `evas study` (`command`) runs over
/// ranks: for any other command rank 0 throws InputError saying so and the
/// other ranks exit 1. Throws InputError when launched so and this evas has
/// no MPI.
MpiJob mpi_start(int* argc, char*** argv, const std::string& command);

/// The job mpi_start found (inactive before it or without MPI).
const MpiJob& mpi_job();

/// Ranks 1..N-1: runs the tasks rank 0 sends until it says stop, then ends
/// MPI. Returns the process's exit code.
int mpi_worker_loop();

/// Rank 0's task runner (the study's --jobs is then the number of ranks).
std::shared_ptr<study::TaskRunner> mpi_runner();

/// Rank 0 at exit: cancels what the worker ranks still run, receives every
/// message they sent up to their acknowledgement, tells them to stop and ends
/// MPI. Nothing when MPI is not active.
void mpi_finish();

}  // namespace evas::cli
