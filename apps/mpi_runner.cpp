// MPI runner of studies (mpi_runner.h).
#include "apps/mpi_runner.h"

#include <poll.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <map>
#include <set>
#include <string>

#include "model/types.h"
#include "study/report.h"

#ifdef EVAS_HAVE_MPI
// the C interface only: OpenMPI's and MPICH's headers otherwise pull in the
// C++ bindings, which need a library of their own
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace evas::cli {

namespace {

int env_int(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::atoi(v) : 0;
}

// Ranks the launcher says there are (0 = not launched by one): Open MPI's
// mpirun, a PMI launcher (MPICH's, Slurm's srun --mpi=pmi2) or a PMIx one
// (srun --mpi=pmix, which gives the rank but the size only through Slurm).
int launched_size() {
  int n = env_int("OMPI_COMM_WORLD_SIZE");
  if (n == 0) n = env_int("PMI_SIZE");
  if (n == 0 && std::getenv("PMIX_RANK")) {
    n = env_int("PMIX_SIZE");
    if (n == 0) n = env_int("SLURM_STEP_NUM_TASKS");
    if (n == 0) n = env_int("SLURM_NTASKS");
  }
  return n;
}

// This process's rank as the launcher gives it (0 when none is given).
[[maybe_unused]] int launched_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"})
    if (std::getenv(name)) return env_int(name);
  return 0;
}

}  // namespace

#ifdef EVAS_HAVE_MPI

namespace {

// rank 0 -> worker: a task, the end of the job, a cancel of what runs;
// worker -> rank 0: a result, the cancel's acknowledgement, "I serve no more",
// "not run, give it to another rank"
constexpr int kTagTask = 1, kTagStop = 2, kTagResult = 3, kTagCancel = 4, kTagCancelled = 5,
              kTagGone = 6, kTagRefused = 7;
MpiJob g_job;
std::map<int, int> g_busy;  // worker rank -> task index under way
std::set<int> g_gone;       // worker ranks that serve no more tasks

volatile std::sig_atomic_t g_worker_stop = 0;
extern "C" void on_worker_signal(int sig) {
  g_worker_stop = sig;
  std::signal(sig, SIG_DFL);
}

void pause_briefly() { ::usleep(2000); }

// index (4 bytes) then the payload
std::string with_index(int index, const std::string& bytes) {
  std::string out(sizeof(std::int32_t), '\0');
  const std::int32_t i = index;
  std::memcpy(out.data(), &i, sizeof i);
  return out + bytes;
}

void send(const std::string& msg, int dest, int tag) {
  if (msg.size() > static_cast<std::size_t>(INT32_MAX))
    throw std::runtime_error("MPI: a message of " + std::to_string(msg.size()) +
                             " bytes is above the 2 GiB an MPI count can hold");
  MPI_Send(msg.data(), static_cast<int>(msg.size()), MPI_BYTE, dest, tag, MPI_COMM_WORLD);
}

// Receives the message `st` announced.
std::string receive(const MPI_Status& probed) {
  int n = 0;
  MPI_Get_count(&probed, MPI_BYTE, &n);
  std::string msg(static_cast<std::size_t>(n), '\0');
  MPI_Status st;
  MPI_Recv(msg.data(), n, MPI_BYTE, probed.MPI_SOURCE, probed.MPI_TAG, MPI_COMM_WORLD, &st);
  return msg;
}

int index_of(const std::string& msg) {
  std::int32_t i = -1;
  if (msg.size() < sizeof i) throw std::runtime_error("MPI: malformed message");
  std::memcpy(&i, msg.data(), sizeof i);
  return i;
}

// The hard limit of a task from its own --max-wall (0 = none).
double hard_wall_of_bytes(const std::string& task_bytes) {
  try {
    return study::hard_wall_of(study::unpack_task(task_bytes).max_wall);
  } catch (const std::exception&) {
    return 0.0;  // the worker reports the malformed task itself
  }
}

// Waits up to `ms` for the local worker's output; true when its task ended.
bool local_ended(study::LocalWorker& w, int ms, study::TaskEnd& e) {
  pollfd p{w.fd(), POLLIN, 0};
  return ::poll(&p, 1, ms) > 0 && w.read_some(e);
}

void kill_if_late(study::LocalWorker& w, double hard_wall) {
  if (hard_wall > 0.0 && w.busy() && w.seconds() > hard_wall)
    w.kill_now("timed out: the worker was killed after " + study::gnum(w.seconds(), 4) +
               " s (limit " + study::gnum(hard_wall, 4) + " s)");
}

class MpiRunner : public study::TaskRunner {
 public:
  void run(const std::vector<study::TaskSpec>& tasks, const std::vector<int>& todo,
           const std::function<void(const study::TaskEnd&)>& done,
           const std::function<bool()>& stop) override {
    std::deque<int> queue(todo.begin(), todo.end());
    std::unique_ptr<study::LocalWorker> local;  // rank 0's own share, one task at a time
    double local_hard = 0.0;
    auto stopped = [&] { return stop && stop(); };
    for (;;) {
      if (stopped()) return;  // the local worker is killed; mpi_finish cancels the ranks'
      if (queue.empty() && !(local && local->busy()) && g_busy.empty()) return;
      for (int r = 1; r < g_job.size && !queue.empty(); ++r) {
        if (g_busy.count(r) || g_gone.count(r)) continue;
        const int i = queue.front();
        queue.pop_front();
        send(with_index(i, study::pack_task(tasks[static_cast<std::size_t>(i)])), r, kTagTask);
        g_busy[r] = i;
      }
      if (!queue.empty() && !(local && local->busy())) {
        if (!local || !local->alive()) local = std::make_unique<study::LocalWorker>(stop);
        const int i = queue.front();
        const std::string bytes = study::pack_task(tasks[static_cast<std::size_t>(i)]);
        if (local->start(i, bytes)) {
          queue.pop_front();
          local_hard = hard_wall_of_bytes(bytes);
        }
      }
      bool progress = false;
      int flag = 0;
      MPI_Status st;
      MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
      if (flag) {
        const std::string msg = receive(st);
        progress = true;
        if (st.MPI_TAG == kTagGone) {
          g_gone.insert(st.MPI_SOURCE);
        } else if (st.MPI_TAG == kTagRefused) {  // sent before its Gone arrived
          g_busy.erase(st.MPI_SOURCE);
          queue.push_front(index_of(msg));
        } else if (st.MPI_TAG == kTagResult) {
          g_busy.erase(st.MPI_SOURCE);
          study::TaskEnd e;
          e.index = index_of(msg);
          e.worker = "rank " + std::to_string(st.MPI_SOURCE);
          try {
            e.run = study::unpack_run(msg.substr(sizeof(std::int32_t)));
          } catch (const std::exception& ex) {
            e.run.status = study::CaseStatus::failed;
            e.run.message = e.worker + " sent a malformed result: " + ex.what();
          }
          if (stopped()) return;
          e.ran = true;
          done(e);
        }
      }
      if (local && local->busy()) {
        study::TaskEnd e;
        if (local_ended(*local, progress ? 0 : 2, e)) {
          e.worker = "rank 0 (" + e.worker + ")";
          if (stopped()) return;
          done(e);
        } else {
          kill_if_late(*local, local_hard);
        }
      } else if (!progress) {
        pause_briefly();
      }
    }
  }
  int width() const override { return g_job.size; }
  std::string describe() const override { return "MPI, " + std::to_string(g_job.size) + " ranks"; }
};

}  // namespace

MpiJob mpi_start(int* argc, char*** argv, const std::string& command) {
  if (launched_size() < 2) return {};
  if (command != "study") {
    if (launched_rank() > 0) std::exit(1);  // rank 0 says why
    throw InputError("`evas " + command +
                     "` does not use MPI ranks: under mpirun each rank would run it "
                     "alone; run it without mpirun (mpirun serves `evas study`)");
  }
  int ok = 0;
  MPI_Initialized(&ok);
  if (!ok) MPI_Init(argc, argv);
  g_job.active = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &g_job.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_job.size);
  return g_job;
}

int mpi_worker_loop() {
  std::signal(SIGINT, on_worker_signal);
  std::signal(SIGTERM, on_worker_signal);
  const std::function<bool()> stop = [] { return g_worker_stop != 0; };
  const std::string me = "rank " + std::to_string(g_job.rank);
  std::unique_ptr<study::LocalWorker> local;  // runs the tasks: a crash or a hang stays there
  int task = -1;                              // the task under way (-1: none)
  double hard = 0.0;
  bool gone = false;
  auto answer = [&](int index, const study::RunData& d) {
    send(with_index(index, study::pack_run(d)), 0, kTagResult);
  };
  auto failed = [&](const std::string& why) {
    study::RunData d;
    d.status = study::CaseStatus::failed;
    d.message = why;
    return d;
  };
  for (;;) {
    bool progress = false;
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
    if (flag) {
      const std::string msg = receive(st);
      progress = true;
      if (st.MPI_TAG == kTagStop) break;
      if (st.MPI_TAG == kTagCancel) {  // rank 0 stops: what runs here is not wanted
        local.reset();
        task = -1;
        send("", 0, kTagCancelled);
      } else if (st.MPI_TAG == kTagTask) {
        const int index = index_of(msg);
        const std::string bytes = msg.substr(sizeof(std::int32_t));
        if (gone) {
          send(with_index(index, ""), 0, kTagRefused);
        } else {
          try {
            if (!local || !local->alive()) local = std::make_unique<study::LocalWorker>(stop);
            if (!local->start(index, bytes)) throw std::runtime_error("its worker process ended");
            task = index;
            hard = hard_wall_of_bytes(bytes);
          } catch (const std::exception& e) {
            answer(index, failed(me + " could not start the task: " + e.what()));
          }
        }
      }
    }
    if (task >= 0 && local) {
      study::TaskEnd e;
      if (local_ended(*local, progress ? 0 : 2, e)) {
        task = -1;
        answer(e.index, e.run);
      } else {
        kill_if_late(*local, hard);
      }
    } else if (!progress) {
      pause_briefly();
    }
    // a signal to this rank alone: rank 0 hears first that this rank serves no
    // more (the job itself goes on), then that its task failed; a task already
    // on its way is refused and runs elsewhere
    if (g_worker_stop != 0 && !gone) {
      gone = true;
      send("", 0, kTagGone);
      if (task >= 0) {
        local.reset();
        answer(task, failed(me + " was stopped by signal " + std::to_string(g_worker_stop)));
        task = -1;
      }
    }
  }
  local.reset();
  MPI_Finalize();
  return 0;
}

std::shared_ptr<study::TaskRunner> mpi_runner() { return std::make_shared<MpiRunner>(); }

const MpiJob& mpi_job() { return g_job; }

void mpi_finish() {
  if (!g_job.active || g_job.rank != 0) return;
  // every worker rank stops what it runs and acknowledges; the results and
  // messages it sent before are received on the way (one sender's messages
  // arrive in order), so none is left unreceived at MPI_Finalize
  for (int r = 1; r < g_job.size; ++r) send("", r, kTagCancel);
  for (int r = 1; r < g_job.size; ++r)
    for (;;) {
      MPI_Status st;
      MPI_Probe(r, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
      receive(st);
      if (st.MPI_TAG == kTagCancelled) break;
    }
  g_busy.clear();
  for (int r = 1; r < g_job.size; ++r) send("", r, kTagStop);
  MPI_Finalize();
  g_job.active = false;
}

#else  // no MPI compiled in

MpiJob mpi_start(int*, char***, const std::string&) {
  const int n = launched_size();
  if (n >= 2)
    throw InputError("this evas was built without MPI, but it was started as one of " +
                     std::to_string(n) +
                     " MPI ranks (each would run the whole command alone); build it with "
                     "libopenmpi-dev installed (docs/study.md)");
  return {};
}
int mpi_worker_loop() { return 1; }
const MpiJob& mpi_job() {
  static const MpiJob none;
  return none;
}
std::shared_ptr<study::TaskRunner> mpi_runner() { return nullptr; }
void mpi_finish() {}

#endif

}  // namespace evas::cli
