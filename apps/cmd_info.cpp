// evas info BODY.h5: inventory and sanity checks of a modal-body file.
#include <boost/program_options.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "apps/commands.h"
#include "io/body_file.h"
#include "solver/invariants.h"

namespace evas::cli {

namespace {

void print_vec(const char* label, const Vec3& v, const char* unit) {
  std::printf("%-22s [% .6g, % .6g, % .6g] %s\n", label, v.x(), v.y(), v.z(), unit);
}

}  // namespace

int cmd_info(const std::vector<std::string>& args) {
  po::options_description opts(
      "usage: evas info BODY.h5\n\n"
      "Prints the mode inventory (frequencies), mass properties and invariant checks of a\n"
      "modal-body file:\n"
      "  ||sum_a M_aa - I||     mass normalisation of the modes (should be ~1e-12)\n"
      "  max ||M_ab - M_ba^T||  symmetry of the modal invariants (should be ~0)\n"
      "  elastic max |S|        translational participation of elastic modes (~0)\n"
      "  elastic max |R^T M phi| rigid-body participation of elastic modes (~0)\n\n"
      "options");
  opts.add_options()("help,h", "show this help");
  po::variables_map vm;
  if (parse_args(args, opts, {"body"}, vm)) return 0;
  if (!vm.count("body")) {
    std::cerr << "evas info: missing BODY file\n" << opts << "\n";
    return 1;
  }
  const std::string path = vm["body"].as<std::string>();
  const ModalBody b = read_body_file(path);
  const int N = b.num_nodes(), n = b.num_modes();
  int rigid = 0;
  for (ModeKind k : b.kinds) rigid += k == ModeKind::Rigid;
  bool lumped = true;
  for (int c = 0; c < b.mass.outerSize(); ++c)
    for (SpMat::InnerIterator it(b.mass, c); it; ++it)
      lumped = lumped && (it.row() == it.col() || it.value() == 0.0);

  std::printf("body file:             %s\n", path.c_str());
  std::printf("name:                  %s\n", b.name.c_str());
  std::printf("nodes:                 %d\n", N);
  std::printf("mass matrix:           %s (%ld non-zeros)\n", lumped ? "lumped" : "consistent",
              static_cast<long>(b.mass.nonZeros()));
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

  const MassProperties mp = mass_properties(b.s, b.mass);
  std::printf("\nmass properties (body axes):\n");
  std::printf("%-22s %.9g kg\n", "total mass", mp.mass);
  print_vec("centre of mass", mp.com, "m");
  std::printf("%-22s [% .6g, % .6g, % .6g]\n", "inertia about com", mp.inertia(0, 0),
              mp.inertia(0, 1), mp.inertia(0, 2));
  for (int r = 1; r < 3; ++r)
    std::printf("%-22s [% .6g, % .6g, % .6g]\n", "", mp.inertia(r, 0), mp.inertia(r, 1),
                mp.inertia(r, 2));
  std::printf("%-22s (kg m^2)\n", "");
  print_vec("principal moments", mp.principal_moments, "kg m^2");

  const ModalInvariants inv = compute_invariants(b);
  const Mat sumM = inv.M[0][0] + inv.M[1][1] + inv.M[2][2];
  const double norm_err = (sumM - Mat::Identity(n, n)).norm();
  double sym_err = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c)
      sym_err = std::max(sym_err, (inv.M[a][c] - inv.M[c][a].transpose()).norm());
  double max_S = 0.0, max_R = 0.0;
  const Mat R = rigid_basis(b.s, b.mass);
  const Mat MR = apply_mass(b.mass, R);
  for (int k = 0; k < n; ++k) {
    if (b.kinds[k] != ModeKind::Elastic) continue;
    max_S = std::max(max_S, inv.S.col(k).cwiseAbs().maxCoeff());
    max_R = std::max(max_R, (MR.transpose() * b.modes.col(k)).cwiseAbs().maxCoeff());
  }
  std::printf("\ninvariant checks:\n");
  std::printf("%-26s %.3e\n", "||sum_a M_aa - I||", norm_err);
  std::printf("%-26s %.3e\n", "max ||M_ab - M_ba^T||", sym_err);
  if (rigid < n) {
    std::printf("%-26s %.3e kg^0.5\n", "elastic max |S|", max_S);
    std::printf("%-26s %.3e\n", "elastic max |R^T M phi|", max_R);
  }
  return 0;
}

}  // namespace evas::cli
