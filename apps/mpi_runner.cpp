// MPI runner of studies (mpi_runner.h).
#include "apps/mpi_runner.h"

#include <poll.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <map>
#include <string>

#include "model/types.h"

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

// Ranks the launcher says there are (0 = not launched by one).
int launched_size() {
  int n = env_int("OMPI_COMM_WORLD_SIZE");
  if (n == 0) n = env_int("PMI_SIZE");
  if (n == 0 && std::getenv("PMIX_RANK")) n = env_int("PMIX_SIZE");
  return n;
}

}  // namespace

#ifdef EVAS_HAVE_MPI

namespace {

constexpr int kTagTask = 1, kTagStop = 2, kTagResult = 3;
MpiJob g_job;
std::map<int, int> g_busy;  // worker rank -> task index under way

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

class MpiRunner : public study::TaskRunner {
 public:
  void run(const std::vector<study::TaskSpec>& tasks, const std::vector<int>& todo,
           const std::function<void(const study::TaskEnd&)>& done,
           const std::function<bool()>& stop) override {
    std::deque<int> queue(todo.begin(), todo.end());
    std::unique_ptr<study::LocalWorker> local;
    auto stopped = [&] { return stop && stop(); };
    for (;;) {
      if (stopped()) return;  // the local worker is killed; busy ranks drain at the end
      if (queue.empty() && !local && g_busy.empty()) return;
      for (int r = 1; r < g_job.size && !queue.empty(); ++r) {
        if (g_busy.count(r)) continue;
        const int i = queue.front();
        queue.pop_front();
        send(with_index(i, study::pack_task(tasks[static_cast<std::size_t>(i)])), r, kTagTask);
        g_busy[r] = i;
      }
      if (!local && !queue.empty()) {
        const int i = queue.front();
        queue.pop_front();
        local = std::make_unique<study::LocalWorker>(i, tasks[static_cast<std::size_t>(i)], stop);
      }
      bool progress = false;
      int flag = 0;
      MPI_Status st;
      MPI_Iprobe(MPI_ANY_SOURCE, kTagResult, MPI_COMM_WORLD, &flag, &st);
      if (flag) {
        const std::string msg = receive(st);
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
        progress = true;
      }
      if (local) {
        pollfd p{local->fd(), POLLIN, 0};
        if (::poll(&p, 1, progress ? 0 : 2) > 0 && !local->read_some()) {
          study::TaskEnd e = local->finish();
          e.worker = "rank 0 (" + e.worker + ")";
          local.reset();
          if (stopped()) return;
          done(e);
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

MpiJob mpi_start(int* argc, char*** argv) {
  if (launched_size() < 2) return {};
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
  for (;;) {
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
    if (!flag) {  // wait without spinning: the ranks may share cores
      pause_briefly();
      continue;
    }
    const std::string msg = receive(st);
    if (st.MPI_TAG == kTagStop) break;
    const int index = index_of(msg);
    study::RunData d;
    try {
      d = study::run_task(study::unpack_task(msg.substr(sizeof(std::int32_t))), stop);
    } catch (const std::exception& e) {
      d.status = study::CaseStatus::failed;
      d.message = std::string("rank ") + std::to_string(g_job.rank) + ": " + e.what();
    }
    send(with_index(index, study::pack_run(d)), 0, kTagResult);
  }
  MPI_Finalize();
  return 0;
}

std::shared_ptr<study::TaskRunner> mpi_runner() { return std::make_shared<MpiRunner>(); }

const MpiJob& mpi_job() { return g_job; }

void mpi_finish() {
  if (!g_job.active || g_job.rank != 0) return;
  for (const auto& [rank, index] : g_busy) {  // results no one waits for any more
    MPI_Status st;
    MPI_Probe(rank, kTagResult, MPI_COMM_WORLD, &st);
    receive(st);
  }
  g_busy.clear();
  for (int r = 1; r < g_job.size; ++r) send("", r, kTagStop);
  MPI_Finalize();
  g_job.active = false;
}

#else  // no MPI compiled in

MpiJob mpi_start(int*, char***) {
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
