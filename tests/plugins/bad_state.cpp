// A test plug-in (tests/test_run_faults.cpp): the integrator
// "bad-state-at-output" runs evas's generalized-alpha and hands back, at its
// 100th output, the state with every modal coordinate scaled by 1e3 - a wrong
// state such as a faulty integrator could return. evas must refuse it where
// the output channels are evaluated: name the time, the element and the state,
// keep the rows written before and exit non-zero.
//
// Two more for the study runners (tests/test_study_faults.cpp):
// "crash-at-output" dies of SIGSEGV at its 10th output, as a run with a bug
// would; "stuck-at-output" never returns from its 10th output and does not look
// at the study's stop flag, as a run caught in an endless loop would.
#include <unistd.h>

#include <csignal>
#include <memory>
#include <string>

#include "integrators/integrator.h"
#include "integrators/plugin.h"

namespace {

class BadStateAtOutput final : public evas::Integrator {
 public:
  std::string name() const override { return "bad-state-at-output"; }

  void init(evas::Problem& p, double t0, const evas::Vec& q0, const evas::Vec& v0,
            const evas::IntegratorSettings& s) override {
    inner_ = evas::make_integrator("generalized-alpha");
    inner_->set_step_monitor([this](double t, double h) { step_done(t, h); });
    inner_->init(p, t0, q0, v0, s);
    outputs_ = 0;
  }

  void advance(double tout, bool land, evas::Vec& q, evas::Vec& v) override {
    inner_->advance(tout, land, q, v);
    if (++outputs_ == 100) q *= 1e3;  // the caller's copy only
  }

  void restart(double t, const evas::Vec& q, const evas::Vec& v) override {
    inner_->restart(t, q, v);
  }

  evas::IntegratorStats stats() const override { return inner_->stats(); }

 private:
  std::unique_ptr<evas::Integrator> inner_;
  int outputs_ = 0;
};

// generalized-alpha until its 10th output, then `fault` in place of a return
template <int Kind>
class FaultAtOutput final : public evas::Integrator {
 public:
  std::string name() const override { return Kind == 0 ? "crash-at-output" : "stuck-at-output"; }
  void init(evas::Problem& p, double t0, const evas::Vec& q0, const evas::Vec& v0,
            const evas::IntegratorSettings& s) override {
    inner_ = evas::make_integrator("generalized-alpha");
    inner_->init(p, t0, q0, v0, s);
    outputs_ = 0;
  }
  void advance(double tout, bool land, evas::Vec& q, evas::Vec& v) override {
    inner_->advance(tout, land, q, v);
    if (++outputs_ < 10) return;
    if (Kind == 0) std::raise(SIGSEGV);
    for (;;) ::sleep(1);
  }
  void restart(double t, const evas::Vec& q, const evas::Vec& v) override {
    inner_->restart(t, q, v);
  }
  evas::IntegratorStats stats() const override { return inner_->stats(); }

 private:
  std::unique_ptr<evas::Integrator> inner_;
  int outputs_ = 0;
};

}  // namespace

EVAS_PLUGIN_EXPORT int evas_plugin_init(int abi_version) {
  if (abi_version != EVAS_PLUGIN_ABI_VERSION) return 1;
  evas::register_integrator(
      "bad-state-at-output", [] { return std::make_unique<BadStateAtOutput>(); },
      "test plug-in: generalized-alpha with a wrong state at the 100th output");
  evas::register_integrator(
      "crash-at-output", [] { return std::make_unique<FaultAtOutput<0>>(); },
      "test plug-in: generalized-alpha that dies of SIGSEGV at its 10th output");
  evas::register_integrator(
      "stuck-at-output", [] { return std::make_unique<FaultAtOutput<1>>(); },
      "test plug-in: generalized-alpha that never returns from its 10th output");
  return 0;
}
