// CalculiX import (see calculix.h): a ModalBody from ccx's own eigenmodes
// (rigid modes replaced by the rigid basis, elastic shapes projected and
// mass-normalised again, truncated as in build_modal_body).
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "io/calculix.h"

namespace evas {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

}  // namespace

ModalBody body_from_ccx_modes(const std::string& name, const FeModel& fe, const FrdModes& modes,
                              const DatModal& dat, const BuildOptions& opt) {
  auto fail = [&](const std::string& what) { throw InputError("body '" + name + "': " + what); };
  const int N = static_cast<int>(fe.node_ids.size());
  if (fe.s.rows() != N || fe.Ms.rows() != N || fe.Ms.cols() != N)
    fail("FE model sizes disagree (node ids, coordinates, Ms)");
  const int m = static_cast<int>(modes.shapes.cols());
  // Rows of the FE nodes in the .frd.
  std::unordered_map<long, int> frd_row;
  for (std::size_t i = 0; i < modes.node_ids.size(); ++i)
    frd_row[modes.node_ids[i]] = static_cast<int>(i);
  Mat X(3 * N, m);
  for (int i = 0; i < N; ++i) {
    const auto it = frd_row.find(fe.node_ids[i]);
    if (it == frd_row.end()) fail("node " + std::to_string(fe.node_ids[i]) + " has no .frd result");
    X.middleRows(3 * i, 3) = modes.shapes.middleRows(3 * it->second, 3);
  }
  Vec lam(m);
  for (int k = 0; k < m; ++k) {
    const int mn = modes.mode_numbers[k];
    if (mn < 1 || mn > dat.eigenvalues.size())
      fail("mode " + std::to_string(mn) + " of the .frd has no eigenvalue in the .dat");
    lam[k] = dat.eigenvalues[mn - 1];
  }
  const double lmax = lam.cwiseAbs().maxCoeff();
  std::vector<int> order(m);
  for (int k = 0; k < m; ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return lam[a] < lam[b]; });
  int n_rigid = 0;
  while (n_rigid < m && n_rigid < 6 && std::abs(lam[order[n_rigid]]) < 1e-6 * lmax) ++n_rigid;
  const Mat R = rigid_basis(fe.s, fe.Ms);
  const double lambda_cut = opt.max_frequency > 0.0 ? std::pow(kTwoPi * opt.max_frequency, 2) : 0.0;
  std::vector<int> keep;
  for (int j = n_rigid; j < m; ++j) {
    const int k = order[j];
    if (lam[k] <= 0.0) fail("elastic mode " + std::to_string(k + 1) + " has eigenvalue <= 0");
    if (lambda_cut > 0.0 && lam[k] > lambda_cut) continue;
    if (opt.num_elastic > 0 && static_cast<int>(keep.size()) >= opt.num_elastic) break;
    keep.push_back(k);
  }
  if (keep.empty()) fail("no elastic modes in the .frd within the requested count / cut-off");
  if (opt.num_elastic > static_cast<int>(keep.size()) && lambda_cut == 0.0)
    fail(std::to_string(opt.num_elastic) + " elastic modes asked for, but the .frd holds only " +
         std::to_string(keep.size()) + " (run ccx with more *FREQUENCY modes, or ask for fewer)");
  Mat elastic(3 * N, static_cast<Eigen::Index>(keep.size()));
  Vec lam_keep(static_cast<Eigen::Index>(keep.size()));
  for (std::size_t j = 0; j < keep.size(); ++j) {
    Vec phi = X.col(keep[j]);
    for (int pass = 0; pass < 2; ++pass) phi -= R * (R.transpose() * apply_mass(fe.Ms, phi));
    const double nrm2 = phi.dot(apply_mass(fe.Ms, phi).col(0));
    if (!(nrm2 > 0.0)) fail("mode " + std::to_string(keep[j] + 1) + " is a rigid-body motion");
    elastic.col(j) = phi / std::sqrt(nrm2);
    lam_keep[j] = lam[keep[j]];
  }
  // The .frd holds about 6 digits, so the elastic shapes are mass-orthogonal to
  // only ~1e-7: orthogonalise them (Gram-Schmidt in frequency order, twice) so
  // that the body meets the modal contract (solver/modal_contract.h) to round-off.
  for (int pass = 0; pass < 2; ++pass)
    for (Eigen::Index j = 0; j < elastic.cols(); ++j) {
      Vec phi = elastic.col(j);
      if (j > 0) {
        const Vec Mphi = apply_mass(fe.Ms, phi);
        phi -= elastic.leftCols(j) * (elastic.leftCols(j).transpose() * Mphi);
      }
      const double nrm2 = phi.dot(apply_mass(fe.Ms, phi).col(0));
      if (!(nrm2 > 0.0)) fail("mode " + std::to_string(keep[j] + 1) + " repeats another mode");
      elastic.col(j) = phi / std::sqrt(nrm2);
    }
  return assemble_modal_body(name, fe, elastic, lam_keep, opt);
}

}  // namespace evas
