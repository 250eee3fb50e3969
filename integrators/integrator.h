// Integrators behind one interface, chosen by name:
//   ida                  IDA (variable-order BDF) on the implicit residual, KLU or dense LU
//   cvode                CVODE on the explicit form: BDF + Newton + KLU/dense, or Adams
//   generalized-alpha    Chung-Hulbert on the second-order form, Newton-type iteration
//   linear-acceleration  the paper's method: Newmark beta = 1/6, gamma = 1/2, iterated
//                        until the balance error of Eq. 1 is <= balance_tol (by the
//                        paper's fixed point, or Anderson, effective-mass or Newton)
//   radau                Radau IIA, 3 stages, order 5, on the second-order form
//                        (simplified Newton on one real and one complex n x n matrix)
// The two Newmark-family methods and radau step with a fixed step (cut into sub-steps where
// the iteration fails) or adaptively against rtol/atol (settings.step_control).
// All see the model only through Problem (solver/problem.h). Every setting is
// declared once in integrators/settings.cpp.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "model/problem.h"
#include "model/stats.h"

namespace evas {

/// How the Newmark family and radau step (settings.step_control).
enum class StepControl {
  fixed,    ///< steps of settings.step; a failed step ends the run
  substep,  ///< steps of settings.step; a failed step is retried as sub-steps
  adaptive  ///< local error against rtol/atol, from settings.step
};
/// How the Newmark family solves its implicit step (settings.iteration).
enum class Iteration {
  method_default,  ///< the method's own: fixed-point (linear-acceleration), effective-mass
                   ///< (generalized-alpha)
  fixed_point,
  anderson,
  effective_mass,
  newton
};
/// The text forms of the choices, as scenes, the command line and files write them.
const char* to_text(StepControl c);
const char* to_text(Iteration i);

struct IntegratorSettings {
  std::string name = "ida";
  double rtol = 1e-6;
  double atol = 1e-8;
  double step = 1e-4;     ///< fixed step (generalized-alpha, linear-acceleration) [s]
  double max_step = 0.0;  ///< adaptive methods: 0 = no limit [s]
  /// ida, cvode: "klu", "dense" or "second-order" (the n x n reduced matrix,
  /// integrators/second_order_ls.h; problems with M = I, no constraints, no states)
  std::string linear_solver = "klu";
  /// ida with linear_solver=second-order: steps over which K and C are reused
  /// (re-formed at IDA's new cj) before being evaluated again; 0 = at every setup.
  /// A Newton convergence failure always forces a fresh evaluation.
  int jacobian_age = 10;
  std::string method = "bdf";  ///< cvode: "bdf" or "adams"
  /// arkode: the Runge-Kutta table by ARKODE's name (implicit DIRK/ESDIRK or explicit ERK)
  std::string table = "ARKODE_ESDIRK324L2SA_4_2_3";
  /// arkode: the additive split, "none" (the table on all of g), "body" (the
  /// bodies' own modal stiffness and damping implicit, every other force
  /// explicit) or "elements" (the reverse)
  std::string imex = "none";
  double rho_inf = 0.8;       ///< generalized-alpha spectral radius at infinity, [0, 1]
  double balance_tol = 1e-3;  ///< linear-acceleration: balance error tolerance (0.1 %)
  int max_iterations = 50;    ///< fixed-point / Newton iterations per step
  long max_steps = 10000000;  ///< adaptive methods: steps per output interval
  int max_order = 0;          ///< ida, cvode: largest BDF/Adams order (0 = solver's)
  /// ida, cvode: safety factor of the Newton convergence test (IDASetNonlinConvCoef,
  /// CVodeSetNonlinConvCoef); 0 = the solver's (0.33 IDA, 0.1 CVODE)
  double newton_coefficient = 0.0;
  /// generalized-alpha, linear-acceleration: the iteration of the implicit step
  Iteration iteration = Iteration::method_default;
  int anderson_depth = 5;  ///< anderson: number of earlier iterates mixed
  /// generalized-alpha, linear-acceleration, radau: fixed (a failed step ends
  /// the run), substep (a failed step is retried as sub-steps down to min_step)
  /// or adaptive (local error against rtol/atol, from `step`)
  StepControl step_control = StepControl::substep;
  double min_step = 1e-12;  ///< smallest step the step control may take [s]
  /// Constrained problems (Problem::constraint_count() > 0): "index-3", "index-2",
  /// "ggl", "index-1" (with Baumgarte terms when baumgarte_alpha/beta > 0) or
  /// "penalty" (an ODE: constraint forces k g + c g'); "default" = the integrator's
  /// own choice (ida: ggl; generalized-alpha, linear-acceleration: index-3).
  std::string formulation = "default";
  double baumgarte_alpha = 0.0;    ///< index-1: 2 alpha g' term [1/s]
  double baumgarte_beta = 0.0;     ///< index-1: beta^2 g term [1/s]
  double penalty_stiffness = 1e9;  ///< penalty: k (per unit of g) [N/m, N m/rad]
  double penalty_damping = 0.0;    ///< penalty: c (per unit of g') [N s/m]
  /// The settings a plug-in declares for itself (IntegratorCapabilities::
  /// settings) that were set: key -> value. Read them with own_setting(),
  /// which gives the declared default for a key not set.
  std::map<std::string, double> own;
};

/// Observer of the accepted steps of a run: called with the time reached and the
/// step just taken [s], between steps (never from inside a solver callback).
/// It may throw (RunError) to end the run, e.g. on an interrupt or a wall-time
/// limit; the integrator's stats() stay valid.
using StepMonitor = std::function<void(double t, double h)>;

class Integrator {
 public:
  virtual ~Integrator() = default;
  /// Installs the step monitor (empty: none). ida and cvode call it after every
  /// accepted internal step (sundials::step_to); an integrator that does not
  /// call step_done() is observed only at its outputs, by the caller's sink.
  void set_step_monitor(StepMonitor m) { monitor_ = std::move(m); }
  const StepMonitor& step_monitor() const { return monitor_; }
  virtual std::string name() const = 0;
  /// True if the integrator runs problems with internal states (Problem::
  /// internal_count() > 0): it sets the problem's z before every evaluation
  /// and after advance(). integrate() refuses such problems otherwise.
  virtual bool takes_internal_states() const { return false; }
  /// True if the integrator solves quasi-static coordinates (Problem::
  /// quasi_static(): rows without inertia, f_i = 0). integrate() refuses
  /// such problems otherwise.
  virtual bool takes_quasi_static() const { return false; }
  /// Prepare to integrate from t0 with q0, v0 (size n each).
  virtual void init(Problem& p, double t0, const Vec& q0, const Vec& v0,
                    const IntegratorSettings& s) = 0;
  /// Advance to tout (> current time) and return the state there. When `land`
  /// is true the integrator must step exactly onto tout (a stop: the model may
  /// change the state there); otherwise it may interpolate (dense output).
  virtual void advance(double tout, bool land, Vec& q, Vec& v) = 0;
  /// Restart from a changed state at the current time (after Problem::at_stop).
  virtual void restart(double t, const Vec& q, const Vec& v) = 0;
  virtual IntegratorStats stats() const = 0;
  /// Constrained problems: the multipliers lambda (size m) at the state last
  /// returned by advance(); false when the integrator has none (ODE, penalty).
  virtual bool multipliers(Vec& lambda) const {
    (void)lambda;
    return false;
  }

 protected:
  /// For the integrators: report an accepted step to the monitor (if any).
  void step_done(double t, double h) const {
    if (monitor_) monitor_(t, h);
  }

 private:
  StepMonitor monitor_;
};

/// What an integrator declares of itself when it is registered: its kind and
/// the settings it reads. The settings table (integrators/settings.h) takes
/// from these declarations which settings a run's method leaves unread (evas
/// run warns of them, evas study refuses a case key no case reads, summary.json
/// lists them).
/// A setting an integrator declares for itself (a plug-in's own parameter,
/// e.g. HHT-alpha's alpha): set and read like the built-in ones (the scene's
/// `integrator:` block, `--set KEY=VALUE`, case specs of `evas study`,
/// `--help-settings`), stored in IntegratorSettings::own.
struct DeclaredSetting {
  std::string key;                   ///< 1 to 32 of a-z, 0-9, '_'; not a built-in key
  bool integer = false;              ///< whole numbers only
  double default_value = 0.0;        ///< within [min, max]
  double min = -1e300, max = 1e300;  ///< the accepted range (inclusive)
  std::string doc;                   ///< one line: meaning, unit, range
};

struct IntegratorCapabilities {
  bool declared = false;    ///< false: nothing declared (a plug-in's reads are its own)
  bool adaptive = false;    ///< steps against rtol/atol (always, or with step_control=adaptive)
  bool fixed_step = false;  ///< steps at settings.step (step_control fixed or substep)
  /// fixed steps only with step_control=fixed; otherwise adaptive (arkode)
  bool fixed_step_on_request = false;
  /// The constraint formulations it solves in a form of its own (every
  /// integrator also takes constraints as penalty forces).
  std::vector<std::string> formulations;
  /// The keys of the settings it reads (integrators/settings.h), besides name.
  std::vector<std::string> reads;
  /// Settings of its own (read as well; their keys need not be in `reads`).
  std::vector<DeclaredSetting> settings;
  /// A conditionally stable method: the largest h omega at which it is stable
  /// on the undamped oscillator, for the given settings (infinity when
  /// unconditionally stable); empty when not known. The run warns of a fixed
  /// step above it for the model's highest mode (run/step_advice.h).
  std::function<double(const IntegratorSettings&)> stability_limit;
  bool reads_setting(const std::string& key) const;
};

/// Names accepted by make_integrator: the built-in ones, then those registered.
std::vector<std::string> integrator_names();
/// The built-in ones alone (no plug-in).
std::vector<std::string> builtin_integrator_names();
/// Throws InputError when `p` has quasi-static coordinates and `integ` does
/// not take them (Integrator::takes_quasi_static).
void require_quasi_static_support(const Integrator& integ, const Problem& p);
/// Makes a new integrator (one per run).
using IntegratorFactory = std::function<std::unique_ptr<Integrator>()>;
/// Adds an integrator under `name` (1 to 64 of a-z, 0-9, '-', '_', '.'), e.g.
/// from a plug-in's entry point (integrators/plugin.h), after which it is used by
/// name like a built-in one (scenes, `evas run --integrator`, studies, problems).
/// Throws InputError when the name is invalid or taken.
void register_integrator(const std::string& name, IntegratorFactory factory,
                         const std::string& description = "",
                         const IntegratorCapabilities& capabilities = {});
/// A declared setting's value in `s`: the one set, else the default that
/// `s.name` (or, when it does not declare `key`, the first integrator that
/// does) declares. Throws InputError when no registered integrator declares it.
double own_setting(const IntegratorSettings& s, const std::string& key);
/// Every declared setting of the registered integrators: (integrator, setting).
std::vector<std::pair<std::string, DeclaredSetting>> declared_settings();
/// The one-line description given at registration ("" if none).
std::string integrator_description(const std::string& name);
/// The capabilities declared at registration (declared = false when none, or
/// when the name is unknown).
IntegratorCapabilities integrator_capabilities(const std::string& name);
/// A built-in integrator as registry.cpp lists it: one function per
/// integrator's own file (integrators/common.h).
struct IntegratorEntry {
  std::string name;
  IntegratorFactory factory;
  std::string description;
  IntegratorCapabilities capabilities;
};
/// Throws InputError naming the integrator when unknown.
std::unique_ptr<Integrator> make_integrator(const std::string& name);

/// Integrate from t0 to the given output times (ascending, > t0), honouring the
/// problem's stops, calling sink(t, q, v) at every output time. Statistics are
/// accumulated in `stats` (wall time included). Throws RunError on failure with
/// time and state described by the problem.
template <class Sink>
void integrate(Integrator& integ, Problem& p, double t0, const std::vector<double>& outputs,
               Sink&& sink);

}  // namespace evas

#include "integrators/integrate_impl.h"
