#include "run/stop.h"

#include <cstdio>

namespace evas::run {

namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_stop_signal(int sig) { g_signal = sig; }

const char* signal_name(int sig) {
  switch (sig) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "signal";
  }
}

}  // namespace

Stop::Stop(double max_wall_seconds)
    : max_wall_(max_wall_seconds), start_(std::chrono::steady_clock::now()) {
  g_signal = 0;
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  // SA_RESTART: a signal must not make a write of the results file fail with EINTR;
  // SA_RESETHAND: a second signal takes the default action and ends the process.
  sa.sa_flags = SA_RESTART | SA_RESETHAND;
  const auto install = [&](int sig, struct sigaction& old) {
    sigaction(sig, nullptr, &old);
    if (old.sa_handler != SIG_IGN) sigaction(sig, &sa, nullptr);  // nohup stays nohup
  };
  install(SIGINT, old_int_);
  install(SIGTERM, old_term_);
  install(SIGHUP, old_hup_);
}

Stop::~Stop() {
  sigaction(SIGINT, &old_int_, nullptr);
  sigaction(SIGTERM, &old_term_, nullptr);
  sigaction(SIGHUP, &old_hup_, nullptr);
}

bool Stop::due() const {
  return g_signal != 0 ||
         (max_wall_ > 0.0 &&
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() >
              max_wall_);
}

void Stop::stop(double t, double h) const {
  char where[96];
  if (h > 0.0)
    std::snprintf(where, sizeof where, "at t = %.9g s, last step h = %.3g s", t, h);
  else
    std::snprintf(where, sizeof where, "at t = %.9g s", t);
  if (const int sig = g_signal)
    throw Stopped(std::string("interrupted (") + signal_name(sig) + ") " + where, 128 + sig);
  char limit[40];
  std::snprintf(limit, sizeof limit, "%g", max_wall_);
  throw Stopped(std::string("wall-time limit ") + limit + " s reached " + where, 2);
}

}  // namespace evas::run
