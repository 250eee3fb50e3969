#include "bodies/modal_contract.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "bodies/reduce_body.h"
#include "model/invariants.h"

namespace evas {

namespace {

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

std::string mode_label(const ModalBody& b, int k) {
  const bool rigid = b.kinds[k] == ModeKind::Rigid;
  std::string s = "mode " + std::to_string(k) + " (" + (rigid ? "rigid" : "elastic");
  if (!rigid && b.eigenvalues[k] > 0.0)
    s += ", " + num(std::sqrt(b.eigenvalues[k]) / (2.0 * M_PI)) + " Hz";
  return s + ")";
}

// Largest |x_ij - y_ij| relative to the largest |entry| of either.
template <class A, class B>
double rel_diff(const A& x, const B& y) {
  if (x.size() == 0) return 0.0;
  const double scale = std::max(x.cwiseAbs().maxCoeff(), y.cwiseAbs().maxCoeff());
  return scale > 0.0 ? (x - y).cwiseAbs().maxCoeff() / scale : 0.0;
}

ModalCheck make(const std::string& name, const std::string& measure, double value,
                const std::string& relation, double limit, bool pass, const std::string& detail) {
  ModalCheck c;
  c.name = name;
  c.measure = measure;
  c.value = value;
  c.relation = relation;
  c.limit = limit;
  c.status = pass ? ModalCheck::Status::Pass : ModalCheck::Status::Fail;
  c.detail = detail;
  return c;
}

ModalCheck skipped(const std::string& name, const std::string& measure, const std::string& why) {
  ModalCheck c;
  c.name = name;
  c.measure = measure;
  c.status = ModalCheck::Status::Skipped;
  c.detail = why;
  return c;
}

long count_nonfinite(const ModalBody& b) {
  long bad = 0;
  auto add = [&](const auto& m) { bad += static_cast<long>((!m.array().isFinite()).count()); };
  add(b.s);
  add(b.modes);
  add(b.eigenvalues);
  add(b.damping);
  for (Eigen::Index k = 0; k < b.mass.nonZeros(); ++k) bad += !std::isfinite(b.mass.valuePtr()[k]);
  if (b.invariants) {
    add(b.invariants->S);
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) {
        add(b.invariants->p[a][c]);
        add(b.invariants->M[a][c]);
      }
  }
  if (b.mass_props) {
    const MassProperties& mp = *b.mass_props;
    bad += !std::isfinite(mp.mass);
    add(mp.com);
    add(mp.inertia);
    add(mp.principal_moments);
    add(mp.principal_axes);
  }
  return bad;
}

}  // namespace

bool ModalContract::ok() const { return first_failure() == nullptr; }

const ModalCheck* ModalContract::first_failure() const {
  for (const ModalCheck& c : checks)
    if (c.status == ModalCheck::Status::Fail) return &c;
  return nullptr;
}

std::string describe_failure(const ModalCheck& c) {
  std::string s = "modal check '" + c.name + "' failed: " + c.measure + " = " + num(c.value) +
                  ", must be " + c.relation + " " + num(c.limit);
  if (!c.detail.empty()) s += " (" + c.detail + ")";
  return s;
}

ModalContract check_modal_contract(const ModalBody& b, double tol) {
  ModalContract out;
  out.tolerance = tol;
  auto& checks = out.checks;
  const int n = b.num_modes(), N = b.num_nodes();

  checks.push_back(make("mode count", "modes", n, ">=", 1, n >= 1,
                        n >= 1 ? "" : "the body has no modes: nothing to simulate"));
  if (n < 1) return out;

  const long bad = count_nonfinite(b);
  checks.push_back(make("finite values", "non-finite values", static_cast<double>(bad), "<=", 0,
                        bad == 0,
                        bad == 0 ? "" : "NaN or Inf in the nodes, mass, modes or stored data"));
  if (bad > 0) return out;

  // Phi^T M Phi: from the nodes and the mass matrix of a full body, else from
  // the stored invariants of the full body (a reduced body).
  const bool full = !b.reduced() && b.mass.rows() == N && b.mass.cols() == N;
  std::optional<ModalInvariants> from_nodes;
  const ModalInvariants* inv = nullptr;
  std::string source;
  if (full) {
    try {
      from_nodes = compute_invariants(b);
      inv = &*from_nodes;
      source = "from the nodes and the mass matrix";
    } catch (const InputError&) {
    }
  }
  if (!inv && b.invariants) {
    inv = b.invariants.get();
    source = b.reduced() ? "from the stored invariants of the full body (reduced body)"
                         : "from the stored invariants";
  }
  Mat G;
  if (inv) G = inv->M[0][0] + inv->M[1][1] + inv->M[2][2];

  // Zero shapes: every entry zero (a full body); zero mass norm over the full
  // body (a reduced body keeps only some rows of each shape).
  {
    int zeros = 0, first = -1;
    for (int k = 0; k < n; ++k) {
      bool zero = b.modes.col(k).cwiseAbs().maxCoeff() == 0.0;
      if (!full) zero = zero && G.size() > 0 && std::abs(G(k, k)) <= tol;
      if (zero && first < 0) first = k;
      zeros += zero;
    }
    checks.push_back(make("non-zero shapes", "modes with an all-zero shape", zeros, "<=", 0,
                          zeros == 0,
                          zeros == 0 ? "" : mode_label(b, first) + " has an all-zero shape"));
  }

  // Eigenvalues.
  double lam_max = 0.0;
  for (int k = 0; k < n; ++k) lam_max = std::max(lam_max, std::abs(b.eigenvalues[k]));
  {
    int worst = -1;
    for (int k = 0; k < n; ++k)
      if (b.kinds[k] == ModeKind::Elastic && (worst < 0 || b.eigenvalues[k] < b.eigenvalues[worst]))
        worst = k;
    if (worst < 0) {
      checks.push_back(skipped("elastic eigenvalues", "smallest elastic eigenvalue [rad^2/s^2]",
                               "no elastic modes"));
    } else {
      const double v = b.eigenvalues[worst];
      checks.push_back(make(
          "elastic eigenvalues", "smallest elastic eigenvalue [rad^2/s^2]", v, ">", 0.0, v > 0.0,
          v > 0.0
              ? ""
              : mode_label(b, worst) + " is marked elastic but its eigenvalue is not positive "
                                       "(a rigid mode marked elastic, or a negative eigenvalue)"));
    }
  }
  {
    const double limit = tol * std::max(lam_max, 1.0);
    int worst = -1;
    for (int k = 0; k < n; ++k)
      if (b.kinds[k] == ModeKind::Rigid &&
          (worst < 0 || std::abs(b.eigenvalues[k]) > std::abs(b.eigenvalues[worst])))
        worst = k;
    if (worst < 0) {
      checks.push_back(
          skipped("rigid eigenvalues", "largest |eigenvalue| of a rigid mode", "no rigid modes"));
    } else {
      const double lam = b.eigenvalues[worst], v = std::abs(lam);
      std::string why;
      if (v > limit)
        why = "mode " + std::to_string(worst) + " is marked rigid but has eigenvalue " + num(lam) +
              (lam < 0.0 ? " (negative beyond round-off)"
                         : " (" + num(std::sqrt(lam) / (2.0 * M_PI)) +
                               " Hz: an elastic mode marked rigid?)") +
              "; the limit is " + num(tol) + " x the largest |eigenvalue| (or x 1)";
      checks.push_back(make("rigid eigenvalues", "largest |eigenvalue| of a rigid mode [rad^2/s^2]",
                            v, "<=", limit, v <= limit, why));
    }
  }

  // Orthonormality.
  const std::string gname = "Phi^T M Phi";
  if (!inv) {
    const std::string why = "no mass matrix and no stored invariants";
    checks.push_back(skipped("mass normalisation", "max |diag(" + gname + ") - 1|", why));
    checks.push_back(skipped("mass orthogonality", "max |offdiag(" + gname + ")|", why));
    checks.push_back(skipped("invariant symmetry", "max |M_ab - M_ba^T|", why));
  } else {
    int kn = 0;
    double vn = -1.0;
    for (int k = 0; k < n; ++k)
      if (std::abs(G(k, k) - 1.0) > vn) vn = std::abs(G(k, k) - 1.0), kn = k;
    checks.push_back(make(
        "mass normalisation", "max |diag(" + gname + ") - 1|", vn, "<=", tol, vn <= tol,
        vn <= tol ? source
                  : mode_label(b, kn) + " has phi^T M phi = " + num(G(kn, kn)) + ", " + source));
    int j0 = 0, k0 = 0;
    double vo = 0.0;
    for (int j = 0; j < n; ++j)
      for (int k = j + 1; k < n; ++k)
        if (std::abs(G(j, k)) > vo) vo = std::abs(G(j, k)), j0 = j, k0 = k;
    checks.push_back(make("mass orthogonality", "max |offdiag(" + gname + ")|", vo, "<=", tol,
                          vo <= tol,
                          vo <= tol ? source
                                    : mode_label(b, j0) + " and " + mode_label(b, k0) +
                                          " are not mass-orthogonal, " + source));
    double vs = 0.0;
    for (int a = 0; a < 3; ++a)
      for (int c = a + 1; c < 3; ++c)
        vs = std::max(vs, (inv->M[a][c] - inv->M[c][a].transpose()).cwiseAbs().maxCoeff());
    checks.push_back(make("invariant symmetry", "max |M_ab - M_ba^T|", vs, "<=", tol, vs <= tol,
                          vs <= tol ? source : "the mass matrix is not symmetric, " + source));
  }

  // Rigid-body content R^T M Phi (6 x n).
  bool any_rigid = false;
  for (ModeKind k : b.kinds) any_rigid = any_rigid || k == ModeKind::Rigid;
  Mat P;
  std::string p_source, p_skip;
  if (full) {
    try {
      const Mat R = rigid_basis(b.s, b.mass);
      P = apply_mass(b.mass, R).transpose() * b.modes;
      p_source = "from the nodes and the mass matrix";
    } catch (const InputError& e) {
      p_skip = std::string("no rigid basis: ") + e.what();
    }
  } else if (b.invariants && b.mass_props) {
    bool ok = b.mass_props->mass > 0.0;
    for (double J : b.mass_props->principal_moments) ok = ok && J > 0.0;
    if (ok) {
      P = rigid_participation(*b.invariants, *b.mass_props);
      p_source = "from the stored invariants and mass properties of the full body";
    } else {
      p_skip = "no rigid basis: the stored mass or a principal moment of inertia is not positive";
    }
  } else {
    p_skip = "no mass matrix and no stored invariants";
  }
  const std::string rr = "max (1 - |R^T M phi|^2 / phi^T M phi) over the rigid modes";
  const std::string er = "max |R^T M phi| over the elastic modes";
  if (!any_rigid) {
    checks.push_back(skipped("rigid modes rigid", rr, "no rigid modes"));
    checks.push_back(
        skipped("elastic free of rigid", er,
                "no rigid modes (the elastic modes of a constrained model may move rigidly)"));
  } else if (P.size() == 0 || G.size() == 0) {
    const std::string why = p_skip.empty() ? "no mass matrix and no stored invariants" : p_skip;
    checks.push_back(skipped("rigid modes rigid", rr, why));
    checks.push_back(skipped("elastic free of rigid", er, why));
  } else {
    int kr = -1, ke = -1;
    double vr = 0.0, ve = 0.0;
    for (int k = 0; k < n; ++k) {
      if (b.kinds[k] == ModeKind::Rigid) {
        const double d = G(k, k) > 0.0 ? std::abs(1.0 - P.col(k).squaredNorm() / G(k, k)) : 1.0;
        if (kr < 0 || d > vr) vr = d, kr = k;
      } else {
        const double d = P.col(k).cwiseAbs().maxCoeff();
        if (ke < 0 || d > ve) ve = d, ke = k;
      }
    }
    checks.push_back(make("rigid modes rigid", rr, vr, "<=", tol, vr <= tol,
                          vr <= tol ? p_source
                                    : "mode " + std::to_string(kr) +
                                          " is marked rigid but is not a rigid-body motion "
                                          "(an elastic mode marked rigid?), " +
                                          p_source));
    if (ke < 0)
      checks.push_back(skipped("elastic free of rigid", er, "no elastic modes"));
    else
      checks.push_back(make("elastic free of rigid", er, ve, "<=", tol, ve <= tol,
                            ve <= tol ? p_source
                                      : mode_label(b, ke) +
                                            " carries rigid-body motion (not mass-orthogonal to "
                                            "the rigid modes), " +
                                            p_source));
  }

  // Stored data of a full body against its nodes.
  const std::string sv = "largest relative difference";
  if (b.reduced()) {
    checks.push_back(skipped("stored vs nodes", sv,
                             "reduced body: " + std::to_string(N) + " of " +
                                 std::to_string(b.full_num_nodes) +
                                 " nodes kept and no mass matrix, the stored invariants of the "
                                 "full body cannot be recomputed"));
  } else if (!b.invariants && !b.mass_props) {
    checks.push_back(skipped("stored vs nodes", sv, "no stored invariants or mass properties"));
  } else if (!from_nodes) {
    checks.push_back(skipped("stored vs nodes", sv, "the mass matrix does not fit the nodes"));
  } else {
    double v = 0.0;
    std::string what;
    auto take = [&](double d, const std::string& name) {
      if (d > v) v = d, what = name;
    };
    if (b.invariants) {
      const ModalInvariants& s = *b.invariants;
      take(rel_diff(from_nodes->S, s.S), "/invariants/S");
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) {
          take(rel_diff(from_nodes->p[a][c], s.p[a][c]), "/invariants/p");
          take(rel_diff(from_nodes->M[a][c], s.M[a][c]), "/invariants/M");
        }
    }
    if (b.mass_props) {
      const MassProperties& s = *b.mass_props;
      try {
        const MassProperties c = mass_properties(b.s, b.mass);
        take(std::abs(c.mass - s.mass) / std::max(std::abs(s.mass), std::abs(c.mass)),
             "/mass_properties/mass");
        take(rel_diff(c.com, s.com), "/mass_properties/centre_of_mass");
        take(rel_diff(c.inertia, s.inertia), "/mass_properties/inertia");
      } catch (const InputError& e) {
        v = 1.0;
        what = std::string("/mass_properties (") + e.what() + ")";
      }
    }
    checks.push_back(make("stored vs nodes", sv, v, "<=", tol, v <= tol,
                          v <= tol ? ""
                                   : "stored '" + what +
                                         "' differs from the value recomputed from the nodes and "
                                         "the mass matrix"));
  }
  for (ModalCheck& c : checks)
    c.relative = c.name == "rigid eigenvalues" || c.name == "mass normalisation" ||
                 c.name == "mass orthogonality" || c.name == "invariant symmetry" ||
                 c.name == "rigid modes rigid" || c.name == "elastic free of rigid" ||
                 c.name == "stored vs nodes";
  return out;
}

void require_modal_contract(const ModalBody& b, double tol) {
  const ModalContract c = check_modal_contract(b, tol);
  if (const ModalCheck* f = c.first_failure())
    throw InputError((b.source.empty() ? b.label() : b.source) + ": " + describe_failure(*f));
}

}  // namespace evas
