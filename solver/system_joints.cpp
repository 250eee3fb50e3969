// The joints of a Model as the constraints of its System (solver/joint.h,
// solver/problem.h): rows of g, g', the acceleration terms and G = dg/dq.
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "solver/system.h"

namespace evas {

namespace {

// Tolerance on the reference geometry of a joint [m]: markers meant to coincide
// may differ by round-off or a fitted centre, not by a design dimension.
constexpr double kGeometryTol = 1e-6;

bool has_rows(JointType t, char kind) {
  for (const auto& r : joint_rows(t))
    if (r[0] == kind) return true;
  return false;
}

std::string fmt(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

}  // namespace

void System::joint_side(int mi, const double* q, const double* v, JointSide& s) const {
  const Marker& mk = model_.markers()[mi];
  if (mk.on_ground()) {
    s.ground = true;
    s.p = mk.c;
    s.E = mk.R_LM;
    return;  // the rest stays zero
  }
  s.ground = false;
  const Body& B = model_.bodies()[mk.body];
  const LofState& L = lof_[mk.body];
  MarkerMotion mm;
  marker_motion(mk, L, q + B.offset, v + B.offset, mm);
  s.p = mm.p;
  s.v = mm.v;
  s.a0 = mm.a;
  s.E = mm.R;
  s.w = L.w_GL_G;
  s.al = L.al_GL_G;
  s.Du.noalias() = L.R_GL * mk.Bu;
  s.Dt.noalias() = L.R_GL * mk.Bt;
  Eigen::Map<const Vec> qb(q + B.offset, B.n()), vb(v + B.offset, B.n());
  s.th.noalias() = s.Dt * qb;
  const Vec3 r = s.Dt * vb;
  s.thd = s.w.cross(s.th) + r;
  s.thdd0 = s.al.cross(s.th) + s.w.cross(s.w.cross(s.th)) + 2.0 * s.w.cross(r);
}

void System::joint_sides(double t, const double* q, const double* v) {
  update_lof(t);
  const auto& joints = model_.joints();
  for (std::size_t j = 0; j < joints.size(); ++j) {
    joint_side(joints[j].marker1, q, v, jwork_[j].s1);
    joint_side(joints[j].marker2, q, v, jwork_[j].s2);
  }
}

void System::constraint(double t, const double* q, const double* v, double* g, double* gv,
                        double* ga) {
  if (mrows_ == 0) return;
  joint_sides(t, q, v ? v : zero_.data());
  const auto& joints = model_.joints();
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const JointWork& w = jwork_[j];
    joint_equations(joints[j], w.s1, w.s2, g ? g + w.row0 : nullptr, gv ? gv + w.row0 : nullptr,
                    ga ? ga + w.row0 : nullptr, nullptr, nullptr);
  }
}

void System::constraint_jacobian(double t, const double* q, SpMat& G) {
  if (mrows_ == 0) return;
  joint_sides(t, q, zero_.data());
  const auto& joints = model_.joints();
  double* val = G.valuePtr();
  for (std::size_t j = 0; j < joints.size(); ++j) {
    JointWork& w = jwork_[j];
    joint_equations(joints[j], w.s1, w.s2, nullptr, nullptr, nullptr, &w.G1,
                    w.s2.ground ? nullptr : &w.G2);
    const int rows = static_cast<int>(w.G1.rows());
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < w.G1.cols(); ++c) val[w.pos1[r * w.G1.cols() + c]] = w.G1(r, c);
      for (int c = 0; c < w.G2.cols(); ++c) val[w.pos2[r * w.G2.cols() + c]] = w.G2(r, c);
    }
  }
}

std::string System::constraint_name(int i) const {
  const auto& joints = model_.joints();
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const int k = i - jwork_[j].row0;
    const auto& rows = joint_rows(joints[j].type);
    if (k >= 0 && k < static_cast<int>(rows.size())) return joints[j].name + "." + rows[k];
  }
  return Problem::constraint_name(i);
}

void System::setup_joints() {
  const auto& joints = model_.joints();
  const auto& markers = model_.markers();
  const auto& bodies = model_.bodies();
  const int n = size();
  jwork_.assign(joints.size(), {});
  if (joints.empty()) return;
  zero_ = Vec::Zero(n);
  if (rank_ > 0)
    throw InputError("joint '" + joints[0].name +
                     "': joints cannot yet be combined with inertial elements (piston-conrod "
                     "in mode 'coupled'); use mode 'prescribed' or replace the joints by stiff "
                     "elements");
  // The frames: equations r.k are exact only if the frames do not turn relative to
  // each other about e_k; d.k and their derivatives assume frames at rest.
  update_lof(0.0);
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const Joint& J = joints[j];
    const std::string item = "joint '" + J.name + "' (" + joint_type_name(J.type) + "): ";
    const Marker& m1 = markers[J.marker1];
    const Vec3 ez = lof_[m1.body].R_GL * m1.R_LM.col(2);
    for (int mi : {J.marker1, J.marker2}) {
      const Marker& mk = markers[mi];
      if (mk.on_ground()) continue;
      const Body& B = bodies[mk.body];
      const LofState& L = lof_[mk.body];
      if (B.lof.kind() == LofKind::Tracking)
        throw InputError(item + "body '" + B.name +
                         "' has a tracking frame, whose re-anchoring moves the coordinates "
                         "the joint constrains; give it a fixed or spin frame");
      const bool moving =
          B.lof.kind() != LofKind::Fixed || L.v_GL.norm() > 0.0 || L.a_GL.norm() > 0.0;
      if (has_rows(J.type, 'd') && moving)
        throw InputError(item + "body '" + B.name +
                         "' has a moving frame; cylindrical and prismatic joints are "
                         "implemented between bodies whose frames are at rest");
      if (has_rows(J.type, 'r') && B.lof.kind() == LofKind::Spin) {
        const bool axis_ok = J.type == JointType::revolute || J.type == JointType::cylindrical;
        if (!axis_ok || B.lof.axis().cross(ez).norm() > 1e-9)
          throw InputError(item + "body '" + B.name + "' spins about [" + fmt(B.lof.axis()(0)) +
                           ", " + fmt(B.lof.axis()(1)) + ", " + fmt(B.lof.axis()(2)) +
                           "], but the joint locks rotation about that axis (only a revolute "
                           "or cylindrical joint whose axis, marker '" +
                           m1.name + "''s z axis, is the spin axis lets a frame spin)");
      }
    }
    JointWork& w = jwork_[j];
    w.row0 = mrows_;
    mrows_ += static_cast<int>(joint_rows(J.type).size());
    const bool frames_still = [&] {
      for (int mi : {J.marker1, J.marker2}) {
        if (markers[mi].on_ground()) continue;
        const Body& B = bodies[markers[mi].body];
        const LofState& L = lof_[markers[mi].body];
        if (B.lof.kind() != LofKind::Fixed || L.v_GL.norm() > 0.0 || L.a_GL.norm() > 0.0)
          return false;
      }
      return true;
    }();
    // G is constant for point and rotation rows on frames at rest.
    if (!frames_still || has_rows(J.type, 'd') || J.type == JointType::distance) linear_ = false;
  }
  // Pattern: each joint's rows x the coordinates of its bodies.
  std::vector<Triplet> trip;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const int rows = static_cast<int>(joint_rows(joints[j].type).size());
    for (int mi : {joints[j].marker1, joints[j].marker2}) {
      if (markers[mi].on_ground()) continue;
      const Body& B = bodies[markers[mi].body];
      for (int r = 0; r < rows; ++r)
        for (int c = 0; c < B.n(); ++c) trip.emplace_back(jwork_[j].row0 + r, B.offset + c, 1.0);
    }
  }
  gpattern_.resize(mrows_, n);
  gpattern_.setFromTriplets(trip.begin(), trip.end());
  gpattern_.makeCompressed();
  auto index = [&](int r, int c) {
    const int* begin = gpattern_.innerIndexPtr() + gpattern_.outerIndexPtr()[c];
    const int* end = gpattern_.innerIndexPtr() + gpattern_.outerIndexPtr()[c + 1];
    return static_cast<int>(std::lower_bound(begin, end, r) - gpattern_.innerIndexPtr());
  };
  for (std::size_t j = 0; j < joints.size(); ++j) {
    JointWork& w = jwork_[j];
    const int rows = static_cast<int>(joint_rows(joints[j].type).size());
    const Marker &m1 = markers[joints[j].marker1], &m2 = markers[joints[j].marker2];
    const int n1 = bodies[m1.body].n(), n2 = m2.on_ground() ? 0 : bodies[m2.body].n();
    w.G1 = Mat::Zero(rows, n1);
    w.G2 = Mat::Zero(rows, n2);
    w.pos1.resize(static_cast<std::size_t>(rows) * n1);
    w.pos2.resize(static_cast<std::size_t>(rows) * n2);
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < n1; ++c)
        w.pos1[r * n1 + c] = index(w.row0 + r, bodies[m1.body].offset + c);
      for (int c = 0; c < n2; ++c)
        w.pos2[r * n2 + c] = index(w.row0 + r, bodies[m2.body].offset + c);
    }
    w.s1.Du = w.s1.Dt = Mat3X::Zero(3, n1);
    w.s2.Du = w.s2.Dt = Mat3X::Zero(3, n2);
  }
  gpattern_.coeffs().setZero();

  // The reference configuration (q = 0 at t = 0) must meet the joints: they join
  // points (and axes) that coincide, they do not pull distant markers together.
  const Vec zero = Vec::Zero(n);
  Vec g(mrows_);
  constraint(0.0, zero.data(), zero.data(), g.data(), nullptr, nullptr);
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const auto& rows = joint_rows(joints[j].type);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const double x = g(jwork_[j].row0 + static_cast<int>(r));
      if (std::abs(x) <= kGeometryTol) continue;
      const Marker &m1 = markers[joints[j].marker1], &m2 = markers[joints[j].marker2];
      throw InputError("joint '" + joints[j].name + "' (" + joint_type_name(joints[j].type) +
                       "): equation " + rows[r] + " is " + fmt(x) +
                       " m in the reference configuration (markers '" + m1.name + "' and '" +
                       m2.name + "' at t = 0, all modal coordinates zero), more than " +
                       fmt(kGeometryTol) +
                       " m; a joint joins points that coincide (and axes that are aligned): "
                       "move a marker, or use a distance joint");
    }
  }
  // Dependent equations make the multipliers undetermined and every formulation's
  // iteration matrix singular: refuse them here, naming the rank.
  SpMat G = gpattern_;
  constraint_jacobian(0.0, zero.data(), G);
  const Mat Gd(G);
  Eigen::ColPivHouseholderQR<Mat> qr(Gd);
  qr.setThreshold(1e-10);
  if (qr.rank() < mrows_)
    throw InputError("the joints' " + std::to_string(mrows_) +
                     " equations are dependent in the reference configuration (rank " +
                     std::to_string(qr.rank()) +
                     "): two joints fix the same motion, or a body has too few modes to "
                     "move its markers independently; remove a joint, use joints with fewer "
                     "equations (spherical instead of fixed), or keep more modes");
}

}  // namespace evas
