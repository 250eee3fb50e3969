// The problems of `evas problem` (problems/library.h) from Python:
// evas.Problem("andrews") with the mechanical problem's parts (M, f, K, C,
// the constraints g and G), the full DAE residual F(t, y, y') of a
// formulation and its iteration matrix dF/dy + cj dF/dy' (dae/formulation.h),
// the published reference at the end point and the test set's score; a
// first-order problem (M y' = f) with its M, f, df/dy and residual M y' - f.
#include "python/problem_binding.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>

#include "dae/formulation.h"
#include "problems/library.h"
#include "python/array_util.h"

namespace py = pybind11;
using evas::Mat;
using evas::SpMat;
using evas::Vec;

namespace {

using evas::py_util::Array;

Vec vec_of(const Array& a, long n, const char* what) { return evas::py_util::to_vec(a, n, what); }
Array array_of(const Vec& v) { return evas::py_util::to_array(v); }
Array array_of(const std::vector<double>& v) {
  return array_of(Eigen::Map<const Vec>(v.data(), static_cast<long>(v.size())));
}
py::tuple csc(const SpMat& A) { return evas::py_util::csc_parts(A); }

py::array_t<double> dense(const Mat& A) {
  py::array_t<double> a({static_cast<long>(A.rows()), static_cast<long>(A.cols())});
  for (long i = 0; i < A.rows(); ++i)
    for (long j = 0; j < A.cols(); ++j) a.mutable_at(i, j) = A(i, j);
  return a;
}

class PyProblem {
 public:
  PyProblem(const std::string& name, const std::string& formulation)
      : lp_(evas::problems::library_problem(name)) {
    if (lp_.implicit()) {
      if (formulation != "default")
        throw evas::InputError("problem '" + name +
                               "' is M y' = f as published: it has no formulations");
      imp_ = lp_.make_implicit();
      formulation_ = "M y' = f";
      return;
    }
    p_ = lp_.make();
    const evas::dae::Formulation f =
        evas::dae::parse_formulation(formulation, evas::dae::Formulation::ggl);
    if (f == evas::dae::Formulation::penalty)
      throw evas::InputError(
          "formulation penalty is an ODE, not a residual of the DAE: take "
          "index-3, index-2, ggl or index-1");
    form_ = std::make_unique<evas::dae::DaeForm>(*p_, f, 0.0, 0.0);
    formulation_ = evas::dae::formulation_name(f);
    K_ = C_ = p_->jacobian_pattern();
    J_ = form_->residual_pattern();
  }

  std::string name() const { return lp_.name; }
  std::string description() const { return lp_.description; }
  std::string formulation() const { return formulation_; }
  double t_end() const { return lp_.t_end; }
  bool first_order() const { return lp_.implicit(); }
  int size() const { return imp_ ? imp_->size() : p_->size(); }
  int constraint_count() const { return imp_ ? 0 : p_->constraint_count(); }
  int dae_size() const { return imp_ ? imp_->size() : form_->size(); }
  std::vector<std::string> component_names() const {
    std::vector<std::string> out;
    if (imp_)
      for (int i = 0; i < imp_->size(); ++i) out.push_back(imp_->component_name(i));
    else
      for (int i = 0; i < p_->size(); ++i) out.push_back(p_->describe_coordinate(i));
    return out;
  }

  py::tuple initial_state() const {
    Vec a, b;
    if (imp_)
      imp_->initial(a, b);
    else
      p_->initial_state(a, b);
    return py::make_tuple(array_of(a), array_of(b));
  }

  // the published end point: {"q", "v", "lambda"} or {"y"}
  py::dict reference() const {
    py::dict d;
    if (imp_) {
      d["y"] = array_of(lp_.reference_y);
      return d;
    }
    const std::size_t n = lp_.reference_qv.size() / 2;
    d["q"] = array_of(std::vector<double>(lp_.reference_qv.begin(), lp_.reference_qv.begin() + n));
    d["v"] = array_of(std::vector<double>(lp_.reference_qv.begin() + n, lp_.reference_qv.end()));
    if (!lp_.reference_lambda.empty()) d["lambda"] = array_of(lp_.reference_lambda);
    d["source"] = lp_.source;
    return d;
  }

  // --- the mechanical problem's parts -----------------------------------------------
  void need_mechanical(const char* what) const {
    if (imp_)
      throw evas::InputError(std::string(what) + ": problem '" + lp_.name +
                             "' is first-order (M y' = f): use rhs, rhs_jacobian, mass_matrix");
  }
  Array force(double t, const Array& q, const Array& v) {
    need_mechanical("force");
    const int n = p_->size();
    const Vec qq = vec_of(q, n, "q"), vv = vec_of(v, n, "v");
    Vec f(n);
    p_->force(t, qq.data(), vv.data(), f.data());
    return array_of(f);
  }
  py::tuple jacobian(double t, const Array& q, const Array& v) {
    need_mechanical("jacobian");
    const int n = p_->size();
    const Vec qq = vec_of(q, n, "q"), vv = vec_of(v, n, "v");
    p_->force_jacobian(t, qq.data(), vv.data(), K_, C_);
    return py::make_tuple(csc(K_), csc(C_));
  }
  py::tuple mass(double t, const Array& q) {
    need_mechanical("mass");
    const int n = p_->size();
    const Vec qq = vec_of(q, n, "q");
    if (!p_->has_mass()) {
      SpMat I(n, n);
      I.setIdentity();
      return csc(I);
    }
    SpMat M = p_->mass_pattern();
    p_->mass(t, qq.data(), M);
    return csc(M);
  }
  py::tuple constraint(double t, const Array& q, const Array& v) {
    need_mechanical("constraint");
    const int n = p_->size(), m = p_->constraint_count();
    const Vec qq = vec_of(q, n, "q"), vv = vec_of(v, n, "v");
    Vec g(m), gv(m), ga(m);
    if (m > 0) p_->constraint(t, qq.data(), vv.data(), g.data(), gv.data(), ga.data());
    return py::make_tuple(array_of(g), array_of(gv), array_of(ga));
  }
  py::tuple constraint_jacobian(double t, const Array& q) {
    need_mechanical("constraint_jacobian");
    const int n = p_->size();
    const Vec qq = vec_of(q, n, "q");
    if (p_->constraint_count() == 0) return csc(SpMat(0, n));
    SpMat G = p_->constraint_pattern();
    p_->constraint_jacobian(t, qq.data(), G);
    return csc(G);
  }
  // (y, y') of the formulation, consistent at (t, q, v), and max |F| there
  py::tuple consistent_start(double t, const Array& q, const Array& v) {
    need_mechanical("consistent_start");
    const int n = p_->size();
    const Vec qq = vec_of(q, n, "q"), vv = vec_of(v, n, "v");
    Vec y(form_->size()), yd(form_->size());
    const double r = form_->consistent_start(t, qq, vv, y.data(), yd.data());
    return py::make_tuple(array_of(y), array_of(yd), r);
  }

  // --- the residual of the DAE (either kind) ----------------------------------------
  Array residual(double t, const Array& y, const Array& yd) {
    const int N = dae_size();
    const Vec yy = vec_of(y, N, "y"), dd = vec_of(yd, N, "yd");
    Vec F(N);
    if (imp_) {
      Vec f(N);
      imp_->rhs(t, yy.data(), f.data());
      F = imp_->mass() * dd - f;
    } else {
      form_->residual(t, yy.data(), dd.data(), F.data());
    }
    return array_of(F);
  }
  // dF/dy + cj dF/dy' (a dense array for a first-order problem)
  py::object iteration_matrix(double t, const Array& y, const Array& yd, double cj) {
    const int N = dae_size();
    const Vec yy = vec_of(y, N, "y"), dd = vec_of(yd, N, "yd");
    if (imp_) {
      Mat J(N, N);
      imp_->rhs_jacobian(t, yy.data(), J);
      return dense(cj * imp_->mass() - J);
    }
    form_->residual_jacobian(t, yy.data(), dd.data(), cj, J_);
    return csc(J_);
  }
  // M, f and df/dy of a first-order problem
  py::array_t<double> mass_matrix() const {
    if (!imp_) throw evas::InputError("mass_matrix: a first-order problem's; here use mass(t, q)");
    return dense(imp_->mass());
  }
  Array rhs(double t, const Array& y) {
    if (!imp_) throw evas::InputError("rhs: a first-order problem's; here use force, residual");
    const Vec yy = vec_of(y, imp_->size(), "y");
    Vec f(imp_->size());
    imp_->rhs(t, yy.data(), f.data());
    return array_of(f);
  }

  // the test set's digits of an end point
  py::dict score(const Array& q, const std::optional<Array>& v, const std::optional<Array>& lambda,
                 double rtol, double atol) const {
    evas::problems::Score s;
    if (imp_) {
      s = evas::problems::score_implicit(lp_, vec_of(q, imp_->size(), "y"), rtol, atol);
    } else {
      const int n = p_->size();
      if (!v) throw evas::InputError("score: give q and v (and lambda where published)");
      const Vec l = lambda ? vec_of(*lambda, p_->constraint_count(), "lambda") : Vec();
      s = evas::problems::score(lp_, vec_of(q, n, "q"), vec_of(*v, n, "v"), l, rtol, atol);
    }
    py::dict d;
    d["mescd"] = s.mescd;
    d["scd"] = s.scd;
    d["mescd_lambda"] = s.mescd_lambda;
    d["worst"] = s.worst;
    return d;
  }

 private:
  const evas::problems::LibraryProblem& lp_;
  std::unique_ptr<evas::Problem> p_;
  std::unique_ptr<evas::ImplicitDae> imp_;
  std::unique_ptr<evas::dae::DaeForm> form_;
  std::string formulation_;
  SpMat K_, C_, J_;
};

}  // namespace

void bind_problems(py::module_& m) {
  py::class_<PyProblem>(m, "Problem")
      .def(py::init<const std::string&, const std::string&>(), py::arg("name"),
           py::arg("formulation") = "default")
      .def_property_readonly("name", &PyProblem::name)
      .def_property_readonly("description", &PyProblem::description)
      .def_property_readonly("formulation", &PyProblem::formulation)
      .def_property_readonly("t_end", &PyProblem::t_end)
      .def_property_readonly("first_order", &PyProblem::first_order)
      .def_property_readonly("size", &PyProblem::size)
      .def_property_readonly("constraint_count", &PyProblem::constraint_count)
      .def_property_readonly("dae_size", &PyProblem::dae_size)
      .def_property_readonly("component_names", &PyProblem::component_names)
      .def("initial_state", &PyProblem::initial_state)
      .def("reference", &PyProblem::reference)
      .def("force", &PyProblem::force, py::arg("t"), py::arg("q"), py::arg("v"))
      .def("_jacobian", &PyProblem::jacobian)
      .def("_mass", &PyProblem::mass)
      .def("constraint", &PyProblem::constraint, py::arg("t"), py::arg("q"), py::arg("v"))
      .def("_constraint_jacobian", &PyProblem::constraint_jacobian)
      .def("consistent_start", &PyProblem::consistent_start, py::arg("t"), py::arg("q"),
           py::arg("v"))
      .def("residual", &PyProblem::residual, py::arg("t"), py::arg("y"), py::arg("yd"))
      .def("_iteration_matrix", &PyProblem::iteration_matrix)
      .def("mass_matrix", &PyProblem::mass_matrix)
      .def("rhs", &PyProblem::rhs, py::arg("t"), py::arg("y"))
      .def("score", &PyProblem::score, py::arg("q"), py::arg("v") = py::none(),
           py::arg("lambda_") = py::none(), py::arg("rtol") = 1.0, py::arg("atol") = 1.0);
  m.def("problems", [] {
    std::vector<std::string> names;
    for (const auto& p : evas::problems::library()) names.push_back(p.name);
    return names;
  });
}
