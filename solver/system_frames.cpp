// The bodies' frames (LOF) in the System: their state at t with the frame terms
// f0, KW, G and the marker axes (update_lof), the rigid rotation correction, and
// the stops of spin and tracking frames with the re-anchoring of the latter.
#include <algorithm>
#include <cmath>

#include "solver/system.h"

namespace evas {

void System::update_lof(double t) {
  if (t == t_lof_) return;
  auto& bodies = model_.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const LofState& L = lof_[b] = bodies[b].lof.at(t);
    const Vec3 a_L = L.R_GL.transpose() * (L.a_GL - model_.gravity);
    const Vec3 w_L = L.R_GL.transpose() * L.w_GL_G;
    const Vec3 al_L = L.R_GL.transpose() * L.al_GL_G;
    BodyWork& w = bwork_[b];
    const Mat3 Om = skew(w_L);
    const Mat3 W = skew(al_L) + Om * Om;
    frame_force(bodies[b].inv, a_L, W, w.f0);
    // KW and G cost O(n^2): rebuild them only when the frame's rotation rates change
    // (never for a fixed LOF, a constant-speed spin or between tracking anchors).
    const double tol = 1e-13 * (1.0 + W.norm() + Om.norm());
    if (!w.built || (W - w.W).norm() > tol || (Om - w.Om).norm() > tol) {
      frame_matrices(bodies[b].inv, W, Om, w.KW, w.G);
      add_rotation_correction(bodies[b], w_L, al_L, w.KW);
      w.frame_free = w.KW.isZero(0.0) && w.G.isZero(0.0);
      w.W = W;
      w.Om = Om;
      w.built = true;
    }
  }
  // the marker axes of the bodies whose frame turned since they were formed
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    BodyWork& w = bwork_[b];
    w.axes_current = w.axes_built && lof_[b].R_GL == w.R_axes;
    w.R_axes = lof_[b].R_GL;
    w.axes_built = true;
  }
  const auto& markers = model_.markers();
  for (std::size_t m = 0; m < markers.size(); ++m) {
    const int b = markers[m].body;
    if (b >= 0 && !bwork_[b].axes_current) axes_[m].noalias() = lof_[b].R_GL * markers[m].R_LM;
  }
  t_lof_ = t;
}

void System::add_rotation_correction(const Body& B, const Vec3& w_L, const Vec3& al_L, Mat& KW) {
  bool any = false;
  for (int k = 3; k < 6; ++k) any = any || B.rigid[k] >= 0;
  if (!any) return;  // no explicit rotation basis: nothing linearised to correct
  // theta = T q_R with T = E diag(1/sqrt(J_k)) (solver/modal_body.cpp rigid_basis).
  // A body with only some rotation modes (e.g. a disk that only turns about its
  // axis) gets the sub-block of the present ones: the others are held fixed.
  Mat3 T;
  for (int k = 0; k < 3; ++k)
    T.col(k) = B.mp.principal_axes.col(k) / std::sqrt(B.mp.principal_moments[k]);
  const Mat3 Kq = T.transpose() * rigid_rotation_correction(B.mp.inertia, w_L, al_L) * T;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (B.rigid[3 + i] >= 0 && B.rigid[3 + j] >= 0)
        KW(B.rigid[3 + i], B.rigid[3 + j]) += Kq(i, j);
}

double System::next_stop(double t) const {
  double next = std::numeric_limits<double>::infinity();
  for (const auto& b : model_.bodies()) {
    const double tol = 1e-12 * std::max(1.0, std::abs(t));
    if (b.lof.kind() == LofKind::Spin) {
      for (double k : b.lof.knots())
        if (k > t + tol) {
          next = std::min(next, k);
          break;
        }
    } else if (b.lof.kind() == LofKind::Tracking) {
      const double h = b.lof.interval();
      double k = std::floor(t / h) + 1.0;
      if (k * h <= t + tol) k += 1.0;
      next = std::min(next, k * h);
    }
  }
  return next;
}

bool System::at_stop(double t, double* q, double* v) {
  bool changed = false;
  const auto& bodies = model_.bodies();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].lof.kind() != LofKind::Tracking) continue;
    const double h = bodies[b].lof.interval();
    const double k = std::round(t / h);
    if (std::abs(t - k * h) > 1e-9 * h) continue;
    reanchor(static_cast<int>(b), t, q, v);
    changed = true;
  }
  if (changed) t_lof_ = t_time_ = t_time_full_ = std::numeric_limits<double>::quiet_NaN();
  return changed;
}

void System::reanchor(int bi, double t, double* q, double* v) {
  Body& B = model_.bodies()[bi];
  const MassProperties& mp = B.mp;
  double* qb = q + B.offset;
  double* vb = v + B.offset;
  const double sm = std::sqrt(mp.mass);
  Vec3 dc, dcd, th, thd;
  for (int a = 0; a < 3; ++a) {
    dc[a] = qb[B.rigid[a]] / sm;
    dcd[a] = vb[B.rigid[a]] / sm;
  }
  th.setZero();
  thd.setZero();
  for (int k = 0; k < 3; ++k) {
    const double sj = std::sqrt(mp.principal_moments[k]);
    th += mp.principal_axes.col(k) * (qb[B.rigid[3 + k]] / sj);
    thd += mp.principal_axes.col(k) * (vb[B.rigid[3 + k]] / sj);
  }
  const LofState L = B.lof.at(t);
  LofState N;
  N.R_GL = L.R_GL * rotation_from_vector(th);
  const Vec3 rc = L.R_GL * (mp.com + dc);
  N.p_GL = L.p_GL + rc - N.R_GL * mp.com;
  N.w_GL_G = L.w_GL_G + L.R_GL * thd;
  const Vec3 v_com = L.v_GL + L.w_GL_G.cross(rc) + L.R_GL * dcd;
  N.v_GL = v_com - N.w_GL_G.cross(N.R_GL * mp.com);
  N.psi_G = L.psi_G + L.R_GL * th;
  B.lof.reanchor(t, N);
  for (int r : B.rigid) {
    qb[r] = 0.0;
    vb[r] = 0.0;
  }
}

}  // namespace evas
