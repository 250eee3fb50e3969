// The compiled part of the Python package `evas` (python/evas/__init__.py):
// a scene's model (its size, initial state, f, K, C, the first-order residual
// and its iteration matrix), runs of any integrator (built in or plug-in) and
// results files, with NumPy arrays (pybind11). Sparse matrices cross as their
// compressed-column parts (data, indices, indptr, shape); the Python side makes
// them scipy.sparse.csc_matrix. docs/extending.md documents the API.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dae/consistent.h"
#include "dae/formulation.h"
#include "integrators/integrator.h"
#include "integrators/plugin.h"
#include "integrators/settings.h"
#include "io/outputs.h"
#include "io/results.h"
#include "io/scene.h"
#include "python/array_util.h"
#include "python/problem_binding.h"
#include "run/run.h"
#include "solver/system.h"
#include "study/scene_edit.h"

namespace py = pybind11;
using evas::SpMat;
using evas::Vec;

namespace {

using evas::py_util::Array;
using evas::py_util::csc_parts;
using evas::py_util::to_array;
using evas::py_util::to_vec;

class Model {
 public:
  // A scene file, or (with `text`) YAML text read as if it were the file
  // `path` (relative body files are resolved from its folder); `params` are
  // ITEM.KEY=VALUE edits as evas run --param takes them.
  Model(const std::string& path, const std::optional<std::string>& text,
        const std::vector<std::string>& params)
      : scene_(load(path, text, params)),
        sys_(std::make_unique<evas::System>(*scene_.model)),
        out_(std::make_unique<evas::OutputSet>(scene_.output, *sys_, scene_.t_start, scene_.t_end)),
        n_(sys_->size()),
        K_(sys_->jacobian_pattern()),
        C_(sys_->jacobian_pattern()),
        f_(n_) {}

  static evas::Scene load(const std::string& path, const std::optional<std::string>& text,
                          const std::vector<std::string>& params) {
    if (!text && params.empty()) return evas::read_scene(path);
    const evas::study::SceneSource src =
        text ? evas::study::edited(evas::study::SceneSource{path, *text, false}, params, "params")
             : evas::study::load_scene_source(path, params);
    return src.parse();
  }

  int size() const { return n_; }
  std::string name() const { return scene_.name; }
  double t_start() const { return scene_.t_start; }
  double t_end() const { return scene_.t_end; }
  std::vector<std::string> channels() const {
    std::vector<std::string> names;
    for (const auto& c : out_->channels()) names.push_back(c.name);
    return names;
  }
  std::vector<double> output_times() const { return out_->times(); }
  // every setting with its type: float, int, bool or str (a choice)
  py::dict settings() const {
    py::dict d;
    for (const auto& s : evas::integrator_settings()) {
      const std::string v = evas::get_integrator_setting(scene_.integrator, s.key);
      if (s.kind == "number")
        d[py::str(s.key)] = py::float_(std::stod(v));
      else if (s.kind == "integer")
        d[py::str(s.key)] = py::int_(std::stol(v));
      else if (s.kind == "bool")
        d[py::str(s.key)] = py::bool_(v == "true" || v == "1" || v == "yes");
      else
        d[py::str(s.key)] = py::str(v);
    }
    return d;
  }
  std::vector<std::string> warnings() const { return scene_.warnings; }

  py::tuple initial_state() const {
    Vec q, v;
    sys_->initial_state(q, v);
    return py::make_tuple(to_array(q), to_array(v));
  }

  Array force(double t, const Array& q, const Array& v) {
    const Vec qq = to_vec(q, n_, "q"), vv = to_vec(v, n_, "v");
    sys_->force(t, qq.data(), vv.data(), f_.data());
    return to_array(f_);
  }

  py::tuple jacobian(double t, const Array& q, const Array& v) {
    const Vec qq = to_vec(q, n_, "q"), vv = to_vec(v, n_, "v");
    sys_->force_jacobian(t, qq.data(), vv.data(), K_, C_);
    return py::make_tuple(csc_parts(K_), csc_parts(C_));
  }

  // y' = [v; -f(t, q, v)]
  Array rhs(double t, const Array& y) {
    const Vec yy = to_vec(y, 2 * n_, "y");
    sys_->force(t, yy.data(), yy.data() + n_, f_.data());
    Vec r(2 * n_);
    r << yy.tail(n_), -f_;
    return to_array(r);
  }

  // d(rhs)/dy = [0 I; -K -C]
  py::tuple rhs_jacobian(double t, const Array& y) {
    const Vec yy = to_vec(y, 2 * n_, "y");
    sys_->force_jacobian(t, yy.data(), yy.data() + n_, K_, C_);
    return csc_parts(block(0.0, 1.0, -1.0));
  }

  // F(t, y, y') = [y'_q - v; y'_v + f(t, q, v)] (the residual IDA solves)
  Array residual(double t, const Array& y, const Array& yd) {
    const Vec yy = to_vec(y, 2 * n_, "y"), dd = to_vec(yd, 2 * n_, "yd");
    sys_->force(t, yy.data(), yy.data() + n_, f_.data());
    Vec r(2 * n_);
    r << dd.head(n_) - yy.tail(n_), dd.tail(n_) + f_;
    return to_array(r);
  }

  // dF/dy + cj dF/dy' = [cj I, -I; K, cj I + C]
  py::tuple iteration_matrix(double t, const Array& y, const Array& yd, double cj) {
    const Vec yy = to_vec(y, 2 * n_, "y");
    (void)to_vec(yd, 2 * n_, "yd");
    sys_->force_jacobian(t, yy.data(), yy.data() + n_, K_, C_);
    return csc_parts(block(cj, -1.0, 1.0));
  }

  // Joints (solver/joint.h): m equations g(t, q) = 0 with G = dg/dq.
  int constraint_count() const { return sys_->constraint_count(); }
  std::vector<std::string> constraint_names() const {
    std::vector<std::string> names;
    for (int i = 0; i < sys_->constraint_count(); ++i) names.push_back(sys_->constraint_name(i));
    return names;
  }
  // (g, g' = G v + g_t, ga) with d(g')/dt = G qdd + ga
  py::tuple constraint(double t, const Array& q, const Array& v) {
    const Vec qq = to_vec(q, n_, "q"), vv = to_vec(v, n_, "v");
    const int m = sys_->constraint_count();
    Vec g(m), gv(m), ga(m);
    sys_->constraint(t, qq.data(), vv.data(), g.data(), gv.data(), ga.data());
    return py::make_tuple(to_array(g), to_array(gv), to_array(ga));
  }
  py::tuple constraint_jacobian(double t, const Array& q) {
    const Vec qq = to_vec(q, n_, "q");
    SpMat G = sys_->constraint_pattern();
    sys_->constraint_jacobian(t, qq.data(), G);
    return csc_parts(G);
  }
  // Positions and velocities projected onto the constraints, and the multipliers
  // of the consistent start (dae/consistent.h), as evas run starts.
  py::tuple consistent_state(double t, const Array& q, const Array& v) {
    const Vec qq = to_vec(q, n_, "q"), vv = to_vec(v, n_, "v");
    const evas::dae::ConsistentState cs = evas::dae::consistent_state(*sys_, t, qq, vv);
    return py::make_tuple(to_array(cs.q), to_array(cs.v), to_array(cs.lambda));
  }

  // The full residual of a jointed scene's DAE in a formulation (index-3,
  // index-2, ggl, index-1; dae/formulation.h), y = [q; v; lambda (; mu); z]:
  // what IDA solves, where residual() above is the unconstrained part only.
  evas::dae::DaeForm& form(const std::string& formulation) {
    const evas::dae::Formulation f =
        evas::dae::parse_formulation(formulation, evas::dae::Formulation::ggl);
    if (f == evas::dae::Formulation::penalty)
      throw evas::InputError(
          "formulation penalty is an ODE (rhs, residual): take index-3, "
          "index-2, ggl or index-1");
    const std::string key = evas::dae::formulation_name(f);
    auto& slot = forms_[key];
    if (!slot) slot = std::make_unique<evas::dae::DaeForm>(*sys_, f, 0.0, 0.0);
    return *slot;
  }
  int dae_size(const std::string& formulation) { return form(formulation).size(); }
  Array dae_residual(double t, const Array& y, const Array& yd, const std::string& formulation) {
    evas::dae::DaeForm& d = form(formulation);
    const Vec yy = to_vec(y, d.size(), "y"), dd = to_vec(yd, d.size(), "yd");
    Vec F(d.size());
    d.residual(t, yy.data(), dd.data(), F.data());
    return to_array(F);
  }
  py::tuple dae_iteration_matrix(double t, const Array& y, const Array& yd, double cj,
                                 const std::string& formulation) {
    evas::dae::DaeForm& d = form(formulation);
    const Vec yy = to_vec(y, d.size(), "y"), dd = to_vec(yd, d.size(), "yd");
    SpMat J = d.residual_pattern();
    d.residual_jacobian(t, yy.data(), dd.data(), cj, J);
    return csc_parts(J);
  }
  py::tuple dae_consistent_start(double t, const Array& q, const Array& v,
                                 const std::string& formulation) {
    evas::dae::DaeForm& d = form(formulation);
    const Vec qq = to_vec(q, n_, "q"), vv = to_vec(v, n_, "v");
    Vec y(d.size()), yd(d.size());
    const double r = d.consistent_start(t, qq, vv, y.data(), yd.data());
    return py::make_tuple(to_array(y), to_array(yd), r);
  }

  Array outputs(double t, const Array& q, const Array& v) {
    const Vec qq = to_vec(q, n_, "q"), vv = to_vec(v, n_, "v");
    Vec row(out_->size());
    out_->values(t, qq.data(), vv.data(), row.data());
    return to_array(row);
  }

  // Runs the scene with an integrator; returns a dict of NumPy arrays and stats.
  py::dict run(const std::string& integrator, const std::map<std::string, py::object>& settings,
               py::object t_end) {
    evas::IntegratorSettings s = scene_.integrator;
    if (!integrator.empty()) s.name = integrator;
    for (const auto& kv : settings)
      evas::set_integrator_setting(s, kv.first, py::str(kv.second).cast<std::string>());
    const double tend = t_end.is_none() ? scene_.t_end : t_end.cast<double>();
    evas::run::SceneRun sr(scene_, tend);
    evas::run::MemorySink sink;
    const std::unique_ptr<evas::Integrator> integ = evas::make_integrator(s.name);
    evas::run::Outcome o;
    {
      py::gil_scoped_release release;
      o = sr.perform(*integ, s, sink);
    }
    py::dict stats;
    for (const evas::StatField& f : evas::stat_fields()) {
      if (f.integer)
        stats[f.name] = static_cast<long long>(f.get(o.stats));
      else
        stats[f.name] = f.get(o.stats);
    }
    const long nc = sink.width(), nr = static_cast<long>(sink.times().size());
    py::array_t<double> values({nr, nc});
    std::copy(sink.values().begin(), sink.values().end(), values.mutable_data());
    py::dict d;
    d["time"] = py::array_t<double>(nr, sink.times().data());
    d["values"] = values;
    std::vector<std::string> names;
    for (const auto& c : sink.channels()) names.push_back(c.name);
    d["channels"] = names;
    d["stats"] = stats;
    d["status"] = o.status_text();
    d["integrator"] = s.name;
    return d;
  }

 private:
  // [a I, b I; c K, a I + c C] with the pattern of K (and C)
  SpMat block(double a, double b, double c) const {
    std::vector<Eigen::Triplet<double>> tr;
    for (int i = 0; i < n_; ++i) {
      if (a != 0.0) tr.emplace_back(i, i, a);
      tr.emplace_back(i, n_ + i, b);
      if (a != 0.0) tr.emplace_back(n_ + i, n_ + i, a);
    }
    for (int col = 0; col < n_; ++col) {
      for (SpMat::InnerIterator it(K_, col); it; ++it)
        tr.emplace_back(n_ + static_cast<int>(it.row()), col, c * it.value());
      for (SpMat::InnerIterator it(C_, col); it; ++it)
        tr.emplace_back(n_ + static_cast<int>(it.row()), n_ + col, c * it.value());
    }
    SpMat A(2 * n_, 2 * n_);
    A.setFromTriplets(tr.begin(), tr.end());
    return A;
  }

  evas::Scene scene_;
  std::unique_ptr<evas::System> sys_;
  std::unique_ptr<evas::OutputSet> out_;
  int n_;
  SpMat K_, C_;
  Vec f_;
  std::map<std::string, std::unique_ptr<evas::dae::DaeForm>> forms_;
};

py::dict read_results(const std::string& path) {
  const evas::ResultsData r = evas::read_results(path);
  py::dict d;
  d["time"] = py::array_t<double>(static_cast<long>(r.time.size()), r.time.data());
  py::array_t<double> values(
      {static_cast<long>(r.values.rows()), static_cast<long>(r.values.cols())});
  for (long i = 0; i < r.values.rows(); ++i)
    for (long j = 0; j < r.values.cols(); ++j) values.mutable_at(i, j) = r.values(i, j);
  d["values"] = values;
  d["channels"] = r.names;
  d["units"] = r.units;
  d["status"] = r.status;
  d["integrator"] = r.integrator;
  d["scene"] = r.scene;
  return d;
}

// A results file from Python (e.g. an analytic or SciPy reference for
// `evas study --reference-file`): time (rows), values (rows x channels).
void write_results(const std::string& path, const Array& time, const Array& values,
                   const std::vector<std::string>& names, const std::vector<std::string>& units,
                   const std::string& integrator) {
  const long nr = time.ndim() == 1 ? time.shape(0) : -1;
  if (nr < 0) throw evas::InputError("write_results: time must be a vector");
  if (values.ndim() != 2 || values.shape(0) != nr ||
      values.shape(1) != static_cast<long>(names.size()))
    throw evas::InputError("write_results: values must be rows x channels (" + std::to_string(nr) +
                           " x " + std::to_string(names.size()) + ")");
  if (!units.empty() && units.size() != names.size())
    throw evas::InputError("write_results: one unit per channel (or none)");
  std::vector<evas::Channel> channels;
  for (std::size_t c = 0; c < names.size(); ++c)
    channels.push_back({names[c], units.empty() ? "" : units[c]});
  evas::ResultsWriter::Options o;
  o.integrator = integrator;
  evas::ResultsWriter w(path, channels, o);
  for (long r = 0; r < nr; ++r) w.append(time.at(r), values.data(r, 0));
  w.finish(evas::IntegratorStats{}, "completed");
}

}  // namespace

PYBIND11_MODULE(_evas, m) {
  m.doc() = "evas: engine vibration analysis models and integrators (compiled part)";
  py::register_exception<evas::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<evas::RunError>(m, "RunError", PyExc_RuntimeError);
  bind_problems(m);
  py::class_<Model>(m, "Model")
      .def(py::init<const std::string&, const std::optional<std::string>&,
                    const std::vector<std::string>&>(),
           py::arg("scene"), py::arg("text") = py::none(),
           py::arg("params") = std::vector<std::string>{})
      .def_property_readonly("warnings", &Model::warnings)
      .def_property_readonly("size", &Model::size)
      .def_property_readonly("name", &Model::name)
      .def_property_readonly("t_start", &Model::t_start)
      .def_property_readonly("t_end", &Model::t_end)
      .def_property_readonly("channels", &Model::channels)
      .def_property_readonly("output_times", &Model::output_times)
      .def_property_readonly("settings", &Model::settings)
      .def("initial_state", &Model::initial_state)
      .def("force", &Model::force, py::arg("t"), py::arg("q"), py::arg("v"))
      .def("_jacobian", &Model::jacobian)
      .def("rhs", &Model::rhs, py::arg("t"), py::arg("y"))
      .def("_rhs_jacobian", &Model::rhs_jacobian)
      .def("residual", &Model::residual, py::arg("t"), py::arg("y"), py::arg("yd"))
      .def("_iteration_matrix", &Model::iteration_matrix)
      .def_property_readonly("constraint_count", &Model::constraint_count)
      .def_property_readonly("constraint_names", &Model::constraint_names)
      .def("constraint", &Model::constraint, py::arg("t"), py::arg("q"), py::arg("v"))
      .def("_constraint_jacobian", &Model::constraint_jacobian)
      .def("consistent_state", &Model::consistent_state, py::arg("t"), py::arg("q"), py::arg("v"))
      .def("outputs", &Model::outputs, py::arg("t"), py::arg("q"), py::arg("v"))
      .def("dae_size", &Model::dae_size, py::arg("formulation") = "default")
      .def("dae_residual", &Model::dae_residual, py::arg("t"), py::arg("y"), py::arg("yd"),
           py::arg("formulation") = "default")
      .def("_dae_iteration_matrix", &Model::dae_iteration_matrix)
      .def("dae_consistent_start", &Model::dae_consistent_start, py::arg("t"), py::arg("q"),
           py::arg("v"), py::arg("formulation") = "default")
      .def("_run", &Model::run);
  m.def("_read_results", &read_results);
  m.def("_write_results", &write_results);
  m.def("integrators", &evas::integrator_names, "names of the integrators (built in and loaded)");
  m.def("load_plugin", &evas::load_plugin, py::arg("spec"),
        "loads an integrator plug-in; returns the names it registered");
}
