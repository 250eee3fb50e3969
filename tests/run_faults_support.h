// Helpers of the `evas run` fault tests (test_run_faults.cpp,
// test_run_faults_output.cpp): temporary folders, the demo scene, spawning the
// real evas program, waiting for rows, and checks of CSV and JSON files.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "io/results.h"
#include "io/text_escape.h"

namespace fs = std::filesystem;
using namespace evas;
using Clock = std::chrono::steady_clock;

extern char** environ;

namespace run_faults {

// The tests read results files that evas is still writing: HDF5 1.10 locks
// files open for writing unless told not to, and reads this once, when it
// starts. The evas runs themselves do not inherit it (spawn_evas).
const int kNoFileLocking = setenv("HDF5_USE_FILE_LOCKING", "FALSE", 1);

fs::path evas_binary() {
  return fs::canonical("/proc/self/exe").parent_path().parent_path() / "evas";
}

std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  f << text;
}

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// A fresh folder under the test temp dir, removed with everything in it.
class TempFolder {
 public:
  TempFolder() {
    std::string tmpl = ::testing::TempDir() + "evas_faults_XXXXXX";
    if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
    path_ = tmpl;
  }
  ~TempFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void replace_once(std::string& s, const std::string& from, const std::string& to) {
  const auto pos = s.find(from);
  if (pos == std::string::npos) throw std::runtime_error("demo.yaml has no '" + from + "'");
  s.replace(pos, from.size(), to);
}

// scenes/demo.yaml with another name, end time and output step.
std::string demo_scene(const std::string& name_yaml, const std::string& t_end,
                       const std::string& out_step) {
  std::string s = read_text(fs::path(EVAS_SOURCE_DIR) / "scenes" / "demo.yaml");
  replace_once(s, "name: demo\n", "name: " + name_yaml + "\n");
  replace_once(s, "time: {start: 0, end: 0.15}", "time: {start: 0, end: " + t_end + "}");
  replace_once(s, "  step: 5e-4\n", "  step: " + out_step + "\n");
  return s;
}

// In a forked child: standard output and error to `log`.
inline void output_to(const fs::path& log) {
  const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    dup2(fd, 1);
    dup2(fd, 2);
    close(fd);
  }
}

// Processes whose parent is `parent` (a study's forked workers, mpirun's
// ranks), from /proc.
inline std::vector<pid_t> children_of(pid_t parent) {
  std::vector<pid_t> kids;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(e.path() / "stat");
    std::string line;
    std::getline(stat, line);
    const auto close = line.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(line.substr(close + 2));
    char state;
    int ppid = 0;
    rest >> state >> ppid;
    if (ppid == parent) kids.push_back(std::stoi(name));
  }
  return kids;
}

// Starts `evas ARGS...` in `cwd` with extra environment entries (an entry
// NAME=VALUE replaces the inherited NAME); stdout and stderr go to `log`.
pid_t spawn_evas(const std::vector<std::string>& args, const fs::path& log,
                 const std::vector<std::string>& env = {}, const fs::path& cwd = {}) {
  const std::string exe = evas_binary().string();
  std::vector<std::string> argv_s{exe};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<std::string> env_s;
  auto given = [&env](const char* entry) {
    for (const std::string& g : env) {
      const std::size_t eq = g.find('=');
      if (eq != std::string::npos && std::strncmp(entry, g.c_str(), eq + 1) == 0) return true;
    }
    return false;
  };
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, "HDF5_USE_FILE_LOCKING=", 22) != 0 && !given(*e)) env_s.emplace_back(*e);
  env_s.insert(env_s.end(), env.begin(), env.end());
  std::vector<char*> argv, envp;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  for (auto& e : env_s) envp.push_back(e.data());
  envp.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    output_to(log);
    if (!cwd.empty() && chdir(cwd.c_str()) != 0) _exit(120);
    // default dispositions: a test run started under nohup (SIGHUP ignored, which
    // evas keeps, as it should) must still see evas handle the signals it sends
    for (int sig : {SIGHUP, SIGINT, SIGTERM}) signal(sig, SIG_DFL);
    execve(exe.c_str(), argv.data(), envp.data());
    _exit(127);
  }
  return pid;
}

// Exit code of the child, or 1000 + N when signal N killed it (a crash).
int wait_code(pid_t pid) {
  int st = 0;
  if (waitpid(pid, &st, 0) != pid) return -1;
  if (WIFEXITED(st)) return WEXITSTATUS(st);
  if (WIFSIGNALED(st)) return 1000 + WTERMSIG(st);
  return -1;
}

struct Outcome {
  int code = -1;
  std::string log;
  double seconds = 0.0;
};

Outcome run_evas(const std::vector<std::string>& args, const fs::path& log,
                 const std::vector<std::string>& env = {}, const fs::path& cwd = {}) {
  const auto t0 = Clock::now();
  Outcome o;
  o.code = wait_code(spawn_evas(args, log, env, cwd));
  o.seconds = seconds_since(t0);
  o.log = read_text(log);
  return o;
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// Rows in a results file another process may be writing (at most 250), -1 if
// it cannot be read yet. Read in a child process: a failed open of a file
// being written may leave HDF5 1.10 state behind.
int rows_now(const fs::path& p) {
  if (!fs::exists(p)) return -1;
  const pid_t pid = fork();
  if (pid == 0) {
    try {
      const std::size_t n = read_results(p.string()).time.size();
      _exit(static_cast<int>(std::min<std::size_t>(n, 250)) + 1);
    } catch (...) {
      _exit(0);
    }
  }
  const int code = wait_code(pid);
  return code >= 1 && code <= 251 ? code - 1 : -1;
}

// Waits until `pred()` or the timeout; returns the seconds waited (< 0: timed out).
template <class Pred>
double wait_for(Pred pred, double timeout) {
  const auto t0 = Clock::now();
  while (seconds_since(t0) < timeout) {
    if (pred()) return seconds_since(t0);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return -1.0;
}

// The JSON file parses (strict UTF-8) with python3; false with `why` if not.
bool json_valid(const fs::path& p, std::string& why) {
  const std::string cmd =
      "python3 -c 'import json,sys; json.load(open(sys.argv[1], encoding=\"utf-8\"))' '" +
      p.string() + "' 2>&1";
  FILE* f = popen(cmd.c_str(), "r");
  if (!f) {
    why = "popen failed";
    return false;
  }
  char buf[512];
  while (std::fgets(buf, sizeof buf, f)) why += buf;
  return pclose(f) == 0;
}

bool have_python3() { return std::system("python3 -c 'import json' >/dev/null 2>&1") == 0; }

// The first record of a CSV text (RFC 4180: quoted fields with doubled quotes).
std::vector<std::string> csv_first_record(const std::string& text) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c == '\n') {
      break;
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

// Folder left clean: no lock or reserve file after the run.
void expect_no_leftovers(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    EXPECT_TRUE(n == "results.h5" || n == "summary.json" || n == "results.csv")
        << "left behind: " << e.path();
  }
}

// A long run whose outputs are far apart: t = 0 and t = 100 s only, so that
// nothing but the per-step check can act for minutes.
fs::path sparse_scene(const fs::path& dir) {
  const fs::path p = dir / "sparse.yaml";
  write_text(p, demo_scene("sparse", "100", "100"));
  return p;
}

}  // namespace run_faults

using namespace run_faults;
