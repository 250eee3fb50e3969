#include "post/assembled_modes.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "model/element.h"

namespace evas {

namespace {

constexpr double kTwoPi = 6.283185307179586;

// What each coordinate belongs to: the group name and its kind.
struct Group {
  std::string name;   // e.g. "crank rigid rx", "crank elastic"
  std::string where;  // mount, driveline, body
};

std::vector<int> group_of_coordinates(const Model& model, std::vector<Group>& groups) {
  static const char* dir[6] = {"tx", "ty", "tz", "rx", "ry", "rz"};
  // bodies an engine-mount carries (either marker) and bodies a motor acts on
  std::vector<char> mounted(model.bodies().size(), 0), driven(model.bodies().size(), 0);
  for (const auto& e : model.elements()) {
    const std::string type = e->type();
    for (int mk : e->markers()) {
      const int b = model.markers()[static_cast<std::size_t>(mk)].body;
      if (b < 0) continue;
      if (type == "engine-mount") mounted[static_cast<std::size_t>(b)] = 1;
      if (type == "motor") driven[static_cast<std::size_t>(b)] = 1;
    }
  }
  std::vector<int> of(static_cast<std::size_t>(model.size()), -1);
  std::map<std::string, int> index;
  auto group = [&](const std::string& name, const std::string& where) {
    auto it = index.find(name);
    if (it != index.end()) return it->second;
    groups.push_back({name, where});
    return index[name] = static_cast<int>(groups.size()) - 1;
  };
  for (std::size_t b = 0; b < model.bodies().size(); ++b) {
    const Body& body = model.bodies()[b];
    for (int k = 0; k < body.n(); ++k) {
      int r = -1;
      for (int j = 0; j < 6; ++j)
        if (body.rigid[static_cast<std::size_t>(j)] == k) r = j;
      std::string where = "body";
      if (r >= 0 && mounted[b]) where = "mount";
      if (r >= 3 && driven[b] && !mounted[b]) where = "driveline";
      const std::string name = r >= 0 ? body.name + " rigid " + dir[r] : body.name + " elastic";
      of[static_cast<std::size_t>(body.offset + k)] = group(name, where);
    }
  }
  return of;
}

}  // namespace

AssembledModes assembled_modes(Problem& problem, const Model& model, const std::vector<double>& t,
                               const std::vector<Vec>& qv, double f_max, double f_min) {
  AssembledModes out;
  const int n = problem.size();
  if (problem.constraint_count() > 0) {
    out.reason = "the scene has joints (constraints): not linearized";
    return out;
  }
  if (!problem.quasi_static().empty()) {
    out.reason = "the scene has quasi-static coordinates: not linearized";
    return out;
  }
  if (problem.internal_count() > 0) {
    out.reason = "elements with internal states (a Maxwell mount, a clutch disk): not linearized";
    return out;
  }
  if (t.empty() || t.size() != qv.size()) {
    out.reason = "no operating state to linearize about";
    return out;
  }
  Mat K = Mat::Zero(n, n), C = Mat::Zero(n, n);
  SpMat Ks = problem.jacobian_pattern(), Cs = problem.jacobian_pattern();
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (qv[i].size() != 2 * n) {
      out.reason = "a linearization state has " + std::to_string(qv[i].size()) +
                   " values, the model needs " + std::to_string(2 * n);
      return out;
    }
    problem.force_jacobian(t[i], qv[i].data(), qv[i].data() + n, Ks, Cs);
    K += Mat(Ks);
    C += Mat(Cs);
  }
  K /= static_cast<double>(t.size());
  C /= static_cast<double>(t.size());
  if (!(K.allFinite() && C.allFinite())) {
    out.reason = "the Jacobian is not finite at the operating states";
    return out;
  }
  out.states = static_cast<int>(t.size());
  Mat A = Mat::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n).setIdentity();
  A.bottomLeftCorner(n, n) = -K;
  A.bottomRightCorner(n, n) = -C;
  Eigen::EigenSolver<Mat> eig(A, true);
  if (eig.info() != Eigen::Success) {
    out.reason = "the eigenvalue solver did not converge";
    return out;
  }
  std::vector<Group> groups;
  const std::vector<int> of = group_of_coordinates(model, groups);
  for (Eigen::Index j = 0; j < A.rows(); ++j) {
    const std::complex<double> lambda = eig.eigenvalues()[j];
    if (!(lambda.imag() > 0.0)) continue;  // one of each pair; no over-damped root
    const double hz = lambda.imag() / kTwoPi;
    if (!(hz > f_min && hz <= f_max)) continue;
    const Eigen::VectorXcd x = eig.eigenvectors().col(j).head(n);
    std::vector<double> share(groups.size(), 0.0);
    double total = 0.0;
    for (int i = 0; i < n; ++i) {
      const double e = std::norm(x[i]);
      total += e;
      if (of[static_cast<std::size_t>(i)] >= 0)
        share[static_cast<std::size_t>(of[static_cast<std::size_t>(i)])] += e;
    }
    std::size_t best = 0;
    for (std::size_t g = 1; g < share.size(); ++g)
      if (share[g] > share[best]) best = g;
    AssembledMode m;
    m.hz = hz;
    m.damping_ratio = -lambda.real() / std::abs(lambda);
    m.share = total > 0.0 && !share.empty() ? share[best] / total : 0.0;
    if (!groups.empty()) {
      m.where = groups[best].where;
      std::ostringstream os;
      os << m.where << ": " << groups[best].name << " " << std::lround(100.0 * m.share) << "%";
      m.label = os.str();
    }
    out.modes.push_back(m);
  }
  std::sort(out.modes.begin(), out.modes.end(),
            [](const AssembledMode& a, const AssembledMode& b) { return a.hz < b.hz; });
  return out;
}

}  // namespace evas
