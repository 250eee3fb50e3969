// evas info BODY.h5: inventory and sanity checks of a modal-body file.
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>

#include "apps/commands.h"
#include "bodies/modal_contract.h"
#include "bodies/reduce_body.h"
#include "io/body_file.h"
#include "model/invariants.h"
#include "model/model.h"

namespace evas::cli {

namespace {

void print_vec(const char* label, const Vec3& v, const char* unit) {
  std::printf("%-22s [% .6g, % .6g, % .6g] %s\n", label, v.x(), v.y(), v.z(), unit);
}

// Mass properties and the invariant summary (stored data when the body has
// them); throws InputError when they cannot be formed (e.g. zero mass).
void print_properties(const ModalBody& b);

}  // namespace

int cmd_info(const std::vector<std::string>& args) {
  double tolerance = kModalCheckTolerance;
  po::options_description opts(
      "usage: evas info BODY.h5 [--tolerance TOL]\n\n"
      "Prints the mode inventory (frequencies), mass properties and invariant checks of a\n"
      "modal-body file, and whether it is reduced (only the nodes of its node sets kept):\n"
      "  ||sum_a M_aa - I||     mass normalisation of the modes (should be ~1e-12)\n"
      "  max ||M_ab - M_ba^T||  symmetry of the modal invariants (should be ~0)\n"
      "  elastic max |S|        translational participation of elastic modes (~0)\n"
      "  elastic max |R^T M phi| rigid-body participation of elastic modes (~0)\n"
      "Invariants and mass properties are the stored ones (of the full body) when the\n"
      "file has them; for a full body they are then also checked against the nodes.\n"
      "Then the modal contract (solver/modal_contract.h), each check with its measured\n"
      "value: mode count, finite values, non-zero shapes, elastic eigenvalues > 0, rigid\n"
      "eigenvalues ~ 0, mass normalisation and orthogonality (Phi^T M Phi = I), symmetry,\n"
      "rigid modes rigid, elastic modes free of rigid motion, stored data vs the nodes.\n"
      "A reduced body is checked from its stored full-body invariants; what needs the\n"
      "mass matrix is skipped (stated). Exit code 1 when a check fails (the same checks\n"
      "`evas run` applies to a scene's body files).\n"
      "The load time is that of read_body_file plus Model::add_body.\n\n"
      "options");
  opts.add_options()("help,h", "show this help")(
      "tolerance", po::value<double>(&tolerance)->default_value(kModalCheckTolerance),
      "tolerance of the relative checks (a scene body's 'check_tolerance')");
  po::variables_map vm;
  if (parse_args(args, opts, {"body"}, vm)) return 0;
  if (!vm.count("body")) {
    std::cerr << "evas info: missing BODY file\n" << opts << "\n";
    return 1;
  }
  if (!(tolerance > 0.0 && tolerance <= 1.0)) throw InputError("--tolerance must be > 0 and <= 1");
  const std::string path = vm["body"].as<std::string>();
  // Load time as a simulation sees it: read the file, add the body to a model
  // (invariants, mass properties, rigid modes: stored or computed).
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  auto shared = std::make_shared<const ModalBody>(read_body_file(path));
  const auto t1 = Clock::now();
  std::string add_error;  // a body that breaks the contract may not load into a model
  try {
    Model model;
    model.add_body("body", shared, Lof::fixed(Vec3::Zero(), Mat3::Identity()));
  } catch (const InputError& e) {
    add_error = e.what();
  }
  const auto t2 = Clock::now();
  const double t_read = std::chrono::duration<double>(t1 - t0).count();
  const double t_add = std::chrono::duration<double>(t2 - t1).count();
  const ModalBody& b = *shared;
  const int N = b.num_nodes(), n = b.num_modes();
  int rigid = 0;
  for (ModeKind k : b.kinds) rigid += k == ModeKind::Rigid;
  bool lumped = true;
  for (int c = 0; c < b.mass.outerSize(); ++c)
    for (SpMat::InnerIterator it(b.mass, c); it; ++it)
      lumped = lumped && (it.row() == it.col() || it.value() == 0.0);
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);

  std::printf("body file:             %s\n", path.c_str());
  if (!ec)
    std::printf("file size:             %.3f MB (%ju bytes)\n", bytes / 1e6, std::uintmax_t(bytes));
  std::printf("load time:             %.3f s (read %.3f s, add to a model %.3f s)\n",
              t_read + t_add, t_read, t_add);
  std::printf("name:                  %s\n", b.name.c_str());
  std::printf("nodes:                 %d\n", N);
  if (b.reduced()) {
    std::set<long> in_sets;
    for (const auto& [name, ids] : b.node_sets) in_sets.insert(ids.begin(), ids.end());
    std::printf("reduced:               yes, %d of %ld nodes kept (%zu in node sets, %zu extra)\n",
                N, b.full_num_nodes, in_sets.size(), N - in_sets.size());
    std::printf("mass matrix:           absent (reduced body; stored full-body data used)\n");
  } else {
    std::printf("reduced:               no (full body)\n");
    std::printf("mass matrix:           %s (%ld non-zeros)\n", lumped ? "lumped" : "consistent",
                static_cast<long>(b.mass.nonZeros()));
  }
  std::printf("stored invariants:     %s\n",
              b.invariants && b.mass_props ? "yes (invariants and mass properties of the full body)"
              : b.invariants               ? "invariants only"
              : b.mass_props               ? "mass properties only"
                                           : "no (computed from the nodes when loaded)");
  std::printf("modes:                 %d (%d rigid, %d elastic)\n", n, rigid, n - rigid);
  std::printf("node sets:            ");
  if (b.node_sets.empty()) std::printf(" (none)");
  for (const auto& [name, ids] : b.node_sets) std::printf(" %s(%zu)", name.c_str(), ids.size());
  std::printf("\n\n");

  std::printf("  mode  kind       frequency [Hz]   damping [1/s]   zeta\n");
  for (int k = 0; k < n; ++k) {
    const double omega = std::sqrt(std::max(0.0, b.eigenvalues[k]));
    const double zeta = omega > 0.0 ? b.damping[k] / (2.0 * omega) : 0.0;
    std::printf("  %4d  %-8s %16.6g %15.6g %8.4g\n", k,
                b.kinds[k] == ModeKind::Rigid ? "rigid" : "elastic", omega / (2.0 * M_PI),
                b.damping[k], zeta);
  }

  const ModalContract contract = check_modal_contract(b, tolerance);
  try {
    print_properties(b);
  } catch (const InputError& e) {
    std::printf("\n(mass properties and invariants not available: %s)\n", e.what());
  }

  std::printf("\nmodal checks (tolerance %.3g):\n", tolerance);
  for (const ModalCheck& c : contract.checks) {
    const char* tag = c.status == ModalCheck::Status::Pass   ? "ok  "
                      : c.status == ModalCheck::Status::Fail ? "FAIL"
                                                             : "skip";
    if (c.status == ModalCheck::Status::Skipped) {
      std::printf("  %s %-22s %s: skipped, %s\n", tag, c.name.c_str(), c.measure.c_str(),
                  c.detail.c_str());
      continue;
    }
    std::printf("  %s %-22s %s = %.4g (must be %s %.3g)%s%s\n", tag, c.name.c_str(),
                c.measure.c_str(), c.value, c.relation.c_str(), c.limit,
                c.detail.empty() ? "" : "; ", c.detail.c_str());
  }
  if (!add_error.empty()) std::printf("  FAIL %-22s %s\n", "add to a model", add_error.c_str());
  int code = 0;
  if (const ModalCheck* f = contract.first_failure()) {
    std::cerr << "evas info: " << path << ": " << describe_failure(*f) << "\n";
    code = 1;
  } else if (!add_error.empty()) {
    std::cerr << "evas info: " << path << ": cannot be added to a model: " << add_error << "\n";
    code = 1;
  }
  return code;
}

namespace {

void print_properties(const ModalBody& b) {
  const int n = b.num_modes();
  int rigid = 0;
  for (ModeKind k : b.kinds) rigid += k == ModeKind::Rigid;
  const MassProperties mp = body_mass_properties(b);
  std::printf("\nmass properties (body axes%s):\n", b.mass_props ? ", stored" : "");
  std::printf("%-22s %.9g kg\n", "total mass", mp.mass);
  print_vec("centre of mass", mp.com, "m");
  std::printf("%-22s [% .6g, % .6g, % .6g]\n", "inertia about com", mp.inertia(0, 0),
              mp.inertia(0, 1), mp.inertia(0, 2));
  for (int r = 1; r < 3; ++r)
    std::printf("%-22s [% .6g, % .6g, % .6g]\n", "", mp.inertia(r, 0), mp.inertia(r, 1),
                mp.inertia(r, 2));
  std::printf("%-22s (kg m^2)\n", "");
  print_vec("principal moments", mp.principal_moments, "kg m^2");

  const ModalInvariants inv = body_invariants(b);
  const Mat sumM = inv.M[0][0] + inv.M[1][1] + inv.M[2][2];
  const double norm_err = (sumM - Mat::Identity(n, n)).norm();
  double sym_err = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c)
      sym_err = std::max(sym_err, (inv.M[a][c] - inv.M[c][a].transpose()).norm());
  double max_S = 0.0, max_R = 0.0;
  const Mat P = rigid_participation(inv, mp);  // R^T M Phi from the invariants
  for (int k = 0; k < n; ++k) {
    if (b.kinds[k] != ModeKind::Elastic) continue;
    max_S = std::max(max_S, inv.S.col(k).cwiseAbs().maxCoeff());
    max_R = std::max(max_R, P.col(k).cwiseAbs().maxCoeff());
  }
  std::printf("\ninvariant checks:\n");
  std::printf("%-26s %.3e\n", "||sum_a M_aa - I||", norm_err);
  std::printf("%-26s %.3e\n", "max ||M_ab - M_ba^T||", sym_err);
  if (rigid < n) {
    std::printf("%-26s %.3e kg^0.5\n", "elastic max |S|", max_S);
    std::printf("%-26s %.3e\n", "elastic max |R^T M phi|", max_R);
  }
}

}  // namespace

}  // namespace evas::cli
