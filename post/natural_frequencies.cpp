#include "post/natural_frequencies.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <set>

namespace evas {

namespace {

constexpr double kTwoPiHz = 6.283185307179586;

bool is_mount(const Element& e) { return e.type() == "engine-mount"; }

}  // namespace

MountModes mount_modes(const Model& model, double t0) {
  MountModes out;
  out.M.setZero();
  out.K.setZero();
  out.shapes.setZero();
  const auto& bodies = model.bodies();
  const auto& markers = model.markers();
  const auto& elements = model.elements();

  // The engine: the block side of the mounts plus every other body that can
  // move rigidly, except a mount's support side.
  std::set<int> mounted, support;
  for (const auto& e : elements) {
    if (!is_mount(*e) || e->markers().size() < 2) continue;
    const Marker& block = markers[e->markers()[1]];
    const Marker& base = markers[e->markers()[0]];
    if (!block.on_ground()) mounted.insert(block.body);
    if (!base.on_ground()) support.insert(base.body);
  }
  if (mounted.empty()) return out;
  std::set<int> engine = mounted;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const int bi = static_cast<int>(b);
    const bool moves =
        std::any_of(bodies[b].rigid.begin(), bodies[b].rigid.end(), [](int r) { return r >= 0; });
    if (moves && !support.count(bi)) engine.insert(bi);
  }
  out.bodies.assign(engine.begin(), engine.end());

  // Mass, centre of mass and inertia at the initial LOF pose.
  std::vector<LofState> lof(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) lof[b] = bodies[b].lof.at(t0);
  Vec3 mc = Vec3::Zero();
  for (int b : out.bodies) {
    const MassProperties& mp = bodies[b].mp;
    out.mass += mp.mass;
    mc += mp.mass * (lof[b].p_GL + lof[b].R_GL * mp.com);
  }
  if (!(out.mass > 0.0))
    throw InputError("mount modes: the mounted bodies have no mass (" + std::to_string(out.mass) +
                     " kg)");
  out.point = mc / out.mass;
  for (int b : out.bodies) {
    const MassProperties& mp = bodies[b].mp;
    const Mat3& R = lof[b].R_GL;
    const Vec3 d = lof[b].p_GL + R * mp.com - out.point;
    out.inertia += R * mp.inertia * R.transpose() +
                   mp.mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  }
  out.M.topLeftCorner<3, 3>() = out.mass * Mat3::Identity();
  out.M.bottomRightCorner<3, 3>() = out.inertia;

  // Stiffness: each mount linearised at the initial motion. A marker on the
  // engine moves rigidly with (u, theta) about `point`:
  //   dp = u - skew(rho) theta,  dpsi = theta   (A: 12 x 6 per marker)
  // and its load (F, M) is the generalised force (F, M + rho x F) (E: 6 x 6);
  // K = -sum_ij E_i D_ij A_j, plus the change of the lever arm rho_i under theta
  // of a load present now: d(rho x F)/dtheta = skew(F) skew(rho).
  static const LofState ground;
  for (std::size_t ei = 0; ei < elements.size(); ++ei) {
    const Element& e = *elements[ei];
    if (!is_mount(e)) continue;
    const auto& ids = e.markers();
    const std::size_t k = ids.size();
    std::vector<MarkerMotion> motion(k);
    std::vector<MarkerLoad> loads(k);
    std::vector<bool> moving(k, false);
    bool any = false;
    for (std::size_t s = 0; s < k; ++s) {
      const Marker& m = markers[ids[s]];
      if (m.on_ground()) {
        marker_motion(m, ground, nullptr, nullptr, motion[s]);
      } else {
        const Body& b = bodies[m.body];
        marker_motion(m, lof[m.body], b.q0.data(), b.v0.data(), motion[s]);
        moving[s] = engine.count(m.body) > 0;
        any = any || moving[s];
      }
    }
    if (!any) continue;
    out.mounts.push_back(static_cast<int>(ei));
    const Eigen::Index rows = 6 * static_cast<Eigen::Index>(k);
    Mat D = Mat::Zero(rows, 2 * rows);
    e.derivatives(t0, motion.data(), D);
    e.evaluate(t0, motion.data(), loads.data());
    for (std::size_t i = 0; i < k; ++i) {
      if (!moving[i]) continue;
      const Vec3 rho_i = motion[i].p - out.point;
      Eigen::Matrix<double, 6, 6> E = Eigen::Matrix<double, 6, 6>::Identity();
      E.bottomLeftCorner<3, 3>() = skew(rho_i);
      for (std::size_t j = 0; j < k; ++j) {
        if (!moving[j]) continue;
        const Vec3 rho_j = motion[j].p - out.point;
        Eigen::Matrix<double, 12, 6> A = Eigen::Matrix<double, 12, 6>::Zero();
        A.block<3, 3>(0, 0) = Mat3::Identity();
        A.block<3, 3>(0, 3) = -skew(rho_j);
        A.block<3, 3>(6, 3) = Mat3::Identity();
        const Eigen::Matrix<double, 6, 12> Dij =
            D.block<6, 12>(6 * static_cast<Eigen::Index>(i), 12 * static_cast<Eigen::Index>(j));
        out.K -= E * Dij * A;
      }
      out.K.bottomRightCorner<3, 3>() -= skew(loads[i].F) * skew(rho_i);
    }
  }
  out.K = (0.5 * (out.K + out.K.transpose())).eval();

  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> es(
      out.K, out.M, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (es.info() != Eigen::Success)
    throw InputError("mount modes: the mass matrix of the mounted bodies is not positive definite");
  out.shapes = es.eigenvectors();
  static const char* const kDir[6] = {"x", "y", "z", "rx", "ry", "rz"};
  for (int c = 0; c < 6; ++c) {
    out.hz.push_back(std::sqrt(std::max(0.0, es.eigenvalues()[c])) / kTwoPiHz);
    // components scaled by sqrt(M_ii): translations and rotations compare
    Eigen::Matrix<double, 6, 1> s;
    for (int r = 0; r < 6; ++r) s[r] = out.shapes(r, c) * out.shapes(r, c) * out.M(r, r);
    int best = 0;
    s.maxCoeff(&best);
    out.direction.emplace_back(kDir[best]);
    out.share.push_back(s.sum() > 0.0 ? s[best] / s.sum() : 0.0);
  }
  return out;
}

std::vector<NaturalFrequency> natural_frequencies(const Model& model, double f_max, double t0) {
  if (!(f_max >= 0.0) || !std::isfinite(f_max))
    throw InputError("natural frequencies: f_max must be finite and >= 0, got " +
                     std::to_string(f_max));
  std::vector<NaturalFrequency> out;
  const MountModes mm = mount_modes(model, t0);
  if (!mm.hz.empty()) {
    std::string name;
    for (int b : mm.bodies) {
      const Body& body = model.bodies()[b];
      bool mounted = false;  // name the bodies on the mounts, not the passengers
      for (int e : mm.mounts) {
        const Marker& m = model.markers()[model.elements()[e]->markers()[1]];
        mounted = mounted || m.body == b;
      }
      if (mounted) name += (name.empty() ? "" : "+") + body.name;
    }
    for (int c = 0; c < 6; ++c)
      out.push_back({name, "mount", c, mm.hz[c], mm.direction[c], mm.share[c]});
  }
  for (const Body& b : model.bodies())
    for (int k = 0; k < b.n(); ++k) {
      if (b.data->kinds[k] != ModeKind::Elastic) continue;
      const double hz = std::sqrt(std::max(0.0, b.data->eigenvalues[k])) / kTwoPiHz;
      if (hz <= f_max) out.push_back({b.name, "elastic", k, hz, "", 0.0});
    }
  return out;
}

}  // namespace evas
