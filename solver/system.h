// The Problem of a Model: Eq. 1 for every body plus the element loads.
//
// State layout: q = [q_body0; q_body1; ...] (Body::offset), v likewise.
// Per body b:
//   f_b = S^T a_L + sum W_ab p_ab + (Lambda + KW) q_b + (C + G) v_b - Q_b(t, q, v)
// with a_L = R_LG (a_GL - g). Jacobian blocks: (Lambda + KW, C + G) dense on the
// body's diagonal block, plus Lm^T D Pq / Lm^T D Pv for every pair of markers
// an element touches (Lm = [R Bu; R Bt], the marker map in G).
//
// Inertial elements (Element::inertia_rank() > 0) make the equation
//     M qdd + f_0(t, q, v) = 0,   M = I - U W^T,
// U = sum Lm^T P, W = sum Lm^T Q (n x r, r = total rank, e.g. 1 per coupled
// piston), f_0 = f with the element loads at the accelerations of qdd = 0.
// force() returns the eliminated f = M^-1 f_0 (Woodbury: one r x r solve), so
// that qdd + f = 0 still holds and no integrator needs to know; force_jacobian()
// returns M^-1 K, M^-1 C (K, C at the solved accelerations, without the
// derivative of the accelerations at qdd = 0, i.e. of the LOF and velocity terms
// 2 w x (A Bu v), w x (A Bt v)). The pattern gets the blocks the
// product fills: inertial bodies x their neighbours. See docs/theory.md s.2.6.
#pragma once

#include <limits>
#include <vector>

#include "model/joint.h"
#include "model/model.h"
#include "model/problem.h"

namespace evas {

class System : public Problem {
 public:
  explicit System(Model& model);

  int size() const override { return model_.size(); }
  void initial_state(Vec& q, Vec& v) const override;
  void force(double t, const double* q, const double* v, double* f) override;
  void force_jacobian(double t, const double* q, const double* v, SpMat& K, SpMat& C) override;
  /// ck K + cc C with half the products of force_jacobian() (one set of pair blocks).
  void force_jacobian_combination(double t, const double* q, const double* v, double ck, double cc,
                                  SpMat& S) override;
  const SpMat& jacobian_pattern() const override { return pattern_; }
  void body_operator(double t, SpMat& KB, SpMat& CB) override;
  double next_stop(double t) const override;
  bool at_stop(double t, double* q, double* v) override;
  std::string describe_state(double t, const double* q, const double* v) const override;
  std::string describe_coordinate(int i) const override;
  /// The bodies' quasi-static modes (Body::quasi_static) as coordinates.
  const std::vector<int>& quasi_static() const override { return qs_; }

  // Joints as constraints (solver/joint.h; implemented in solver/system_joints.cpp).
  int constraint_count() const override { return mrows_; }
  void constraint(double t, const double* q, const double* v, double* g, double* gv,
                  double* ga) override;
  void constraint_jacobian(double t, const double* q, SpMat& G) override;
  const SpMat& constraint_pattern() const override { return gpattern_; }
  bool constraints_linear() const override { return linear_; }
  std::string constraint_name(int i) const override;

  // Element internal states (Element::internal_count; solver/system_internal.cpp).
  int internal_count() const override { return nz_; }
  bool internal_algebraic(int i) const override;
  void internal_initial(double t, const Vec& q, const Vec& v, Vec& z) override;
  void set_internal(const double* z) override;
  const double* internal() const override { return nz_ > 0 ? z_.data() : nullptr; }
  void internal_rate(double t, const double* q, const double* v, double* h) override;
  void internal_jacobian(double t, const double* q, const double* v, SpMat& Fz, SpMat& Hq,
                         SpMat& Hv, SpMat& Hz) override;
  void internal_patterns(SpMat& Fz, SpMat& Hq, SpMat& Hv, SpMat& Hz) const override;
  std::string internal_name(int i) const override;
  /// The current internal states of element e (nullptr if it has none).
  const double* element_internal(int e) const {
    return zoff_[static_cast<std::size_t>(e)] >= 0 ? z_.data() + zoff_[static_cast<std::size_t>(e)]
                                                   : nullptr;
  }

  /// Marker motions at (t, q, v), accelerations at qdd = 0 (MarkerMotion::a).
  /// `reads_only`: only what some element reads (Element::motion_reads); the
  /// other translations and rotations are then not current.
  void update_markers(double t, const double* q, const double* v, bool reads_only = false);
  /// force() computes only the marker rows the elements read (default); false:
  /// every row, as the other paths do (tests compare the two).
  void set_read_rows_only(bool on) { reads_only_ = on; }
  /// Marker motions for outputs; with inertial elements also the full accelerations
  /// (qdd = -f solved), else the accelerations at qdd = 0.
  void observe(double t, const double* q, const double* v);
  /// The same for the motions of `markers` alone (an output set names those its
  /// channels read); the others are then not current. With inertial elements,
  /// every marker as observe().
  void observe(double t, const double* q, const double* v, const std::vector<int>& markers);
  /// Marker motions with the full accelerations of every marker: qdd = -f
  /// solved (one force evaluation), the modal part added to MarkerMotion::a and
  /// al. For the acceleration output channels; the unconstrained part only
  /// (with joints, G^T lambda is not in f).
  void observe_accelerations(double t, const double* q, const double* v);
  /// Total rank of the inertial elements (0: M = I).
  int inertia_rank() const { return rank_; }
  const MarkerMotion& motion(int marker) const { return motion_[marker]; }
  const LofState& lof_state(int body) const { return lof_[body]; }
  Model& model() { return model_; }

 private:
  struct ElementWork {
    std::vector<MarkerMotion> motion;
    std::vector<MarkerLoad> loads;
    Mat D;
    Mat P, Q;        // inertial elements: 6k x r
    Vec dacc, r_1;   // scratch: 6k accelerations, r-vector
    int col = 0;     // first column of this element in U, W
    Mat Dz, Hm, Hz;  // internal states: d(loads)/dz, dh/d(motion), dh/dz
  };
  struct BodyWork {
    Vec f0;
    Mat KW, G;
    Mat3 W, Om;  // frame matrices KW, G were last built for
    bool built = false;
    bool frame_free = false;  // KW = G = 0 (the products are skipped)
    Mat3 R_axes;              // the frame's rotation the marker axes axes_ were formed at
    bool axes_built = false, axes_current = false;
  };
  // ---- Construction (solver/system.cpp): the constructor calls these in this order ----
  /// lof_ and bwork_ (per body the frame state and the frame terms f0, KW, G).
  void setup_body_work();
  /// Per marker: motion_ (the constant motion of the ground markers), axes_ and
  /// the maps Lm_, Pq_, Pv_.
  void setup_marker_work();
  /// mrow_ and per body the stacked marker maps bstack_, bstackT_ with bq_, bv_, bload_.
  void setup_body_stacks();
  /// ework_, pairs_, pair_index_ and the inertial elements (inertial_, piecewise_,
  /// rank_); marks in `pair` ([bi * nb + bj]) the body pairs an element couples.
  void setup_element_work(std::vector<char>& pair);
  /// rank_ > 0: adds to `pair` the blocks M^-1 K fills; sizes U_, W_, Z_, WtA_, f0_,
  /// y_, lu_.
  void setup_inertial_work(std::vector<char>& pair);
  /// pattern_ and block_start_ from the body pairs `pair` (solver/system_jacobian.cpp).
  void build_pattern(const std::vector<char>& pair);

  void update_lof(double t);
  void force_impl(double t, const double* q, const double* v, double* f, bool reads_only = false);
  /// rset_, unread_ from the elements' motion_reads(); timed_, lset_, tset_ from
  /// their state dependence (constructor).
  void build_row_sets();
  /// Subtracts the generalised loads Lm^T (F, M) of marker `id` from f.
  void apply_load(int id, const Vec3& F, const Vec3& M, double* f) const;
  /// Adds (F, M) of marker `id` (G components) to its body's load buffer;
  /// flush_loads() subtracts all of them from f with one product per body.
  void accumulate_load(int id, const Vec3& F, const Vec3& M);
  /// Element e's loads at t from the current marker motions, into bload_.
  void load_element(int e, double t);
  /// Rows of a body's stack (the translation and/or rotation rows of some
  /// markers), stacked, with work vectors y, z of their size; all: every row
  /// (update_markers then uses the body's stack and bq_, bv_ themselves).
  struct RowSet {
    std::vector<int> rows;
    Mat stack;   // those rows of the body's stack
    Mat stackT;  // stack^T, stored: the loads back by a column-major product
    Vec y, z;
    std::vector<int> tpos, rpos;  // per marker of the body: first translation /
                                  // rotation row in y (-1: not in the set)
    bool all = true;
  };
  /// Per body the rows of `parts` (per marker: bit 1 the translation or force
  /// rows, bit 2 the rotation or moment rows).
  std::vector<RowSet> row_sets(const std::vector<unsigned>& parts) const;
  /// y = stack q_b, z = stack v_b of every body's set in `sets` that has rows.
  void row_products(std::vector<RowSet>& sets, const double* q, const double* v) const;
  /// f = the bodies' own terms (Eq. 1 without the element loads) + ftime.
  void body_terms(const double* q, const double* v, const Vec& ftime, double* f) const;

  // ---- The residual from the rows the elements read (solver/system_rows.cpp) ----
  // force() with reads_only (no inertial elements): the marker products give the
  // rows some element reads (rset_), each element slot's motion is made from them
  // in place, and its loads go straight to the rows of its marker that some
  // element loads (lset_; of time alone: tset_). No full marker rows, no copies.
  struct SlotRows {
    int body = -1;         // -1: ground (its motion is constant, set at set-up)
    int uq = -1, tq = -1;  // translation / rotation rows in rset_[body].y, .z
    int fl = -1, ml = -1;  // force / moment rows in the element's load set
  };
  std::vector<std::vector<SlotRows>> slot_rows_;  // per element
  /// slot_rows_ from rset_, lset_, tset_ (after build_row_sets()).
  void build_slot_rows();
  void force_rows(double t, const double* q, const double* v, double* f);
  /// Element e's slots' motion from rset_ (current), its loads added to `sets`.
  void load_element_rows(int e, double t, std::vector<RowSet>& sets);
  /// ftime_ = the generalised loads of the elements of time alone at t (rows of tset_).
  void time_loads(double t);
  /// ftime_full_: the same from every row (the full path, which tests compare).
  void time_loads_full(double t);
  /// f -= bstackT_ bload_ per body (every row).
  void flush_all_loads(double* f);
  /// Inertial elements: f_0 -> M^-1 f_0; leaves their ElementWork::motion at the
  /// solved accelerations and U_, W_, lu_ for apply_inverse_mass().
  void solve_inertia(double t, double* f);
  /// solve_inertia(), one pass: the inertial elements' loads at the accelerations
  /// of qdd = 0 into f, and their U_, W_ (zeroed by the caller).
  void add_inertial_loads(double t, double* f);
  /// solve_inertia(): each inertial element's accelerations from the solved f
  /// (qdd = -f) become its linearisation point; returns the largest change.
  double relinearise_inertia(const double* f);
  void apply_inverse_mass(SpMat& A);
  static void add_rotation_correction(const Body& B, const Vec3& w_L, const Vec3& al_L, Mat& KW);
  void marker_maps(int marker);
  /// values += ck (Lambda + KW) + cc (C + G) on each body's diagonal block.
  void add_body_terms(double* values, double ck, double cc) const;
  /// Adds scale B (B dense: rows of body bi, columns of body bj) into values.
  void add_block(double* values, int bi, int bj, const Eigen::Ref<const Mat>& B,
                 double scale = 1.0) const;
  void reanchor(int body, double t, double* q, double* v);
  /// Offsets of the element internal states and the patterns of their Jacobians.
  void setup_internal();
  /// qs_ from the bodies; refuses what the quasi-static rows cannot be
  /// combined with (inertial elements, undamped modes).
  void setup_quasi_static();
  /// Copies the current motion of element e's markers into its work; returns it.
  const MarkerMotion* gather_motion(std::size_t e);
  /// Element e's loads at the current internal states.
  void evaluate_element(int e, double t);

  struct JointWork {
    int row0 = 0;  // first constraint row
    JointSide s1, s2;
    Mat G1, G2;                   // rows x n_b blocks of dg/dq
    std::vector<int> pos1, pos2;  // value index in gpattern_ of (r, c): [r * n_b + c]
  };
  /// Checks the joints against the frames and each other; builds gpattern_.
  void setup_joints();
  /// One side of a joint (marker mi) at (t, q, v); update_lof(t) done.
  void joint_side(int mi, const double* q, const double* v, JointSide& s) const;
  void joint_sides(double t, const double* q, const double* v);

  Model& model_;
  std::vector<int> qs_;  // quasi-static coordinates
  SpMat pattern_;
  std::vector<JointWork> jwork_;
  SpMat gpattern_;
  Vec zero_;  // joints: zero velocities for constraint_jacobian
  int mrows_ = 0;
  // internal states
  int nz_ = 0;
  Vec z_;
  std::vector<int> zoff_;   // per element: first state, -1 if none
  std::vector<int> zelem_;  // per state: its element
  SpMat fz_pat_, hq_pat_, hv_pat_, hz_pat_;
  bool linear_ = true;
  std::vector<LofState> lof_;
  std::vector<MarkerMotion> motion_;
  std::vector<ElementWork> ework_;
  std::vector<BodyWork> bwork_;
  std::vector<Mat> Lm_, Pq_, Pv_;  // per marker (G components): 6 x n, 12 x n, 12 x n
  // Per body: the maps [Bu; Bt] of all its markers stacked (6 rows per marker),
  // their products with q_b, v_b, and the marker loads in L components, so that
  // the markers cost one matrix-vector product per body and direction.
  std::vector<Mat> bstack_;
  std::vector<Mat> bstackT_;  // bstack_ transposed (the loads back by column-major products)
  using PairRowMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  std::vector<Vec> bq_, bv_, bload_;
  std::vector<int> mrow_;  // per marker: first row in its body's stack (-1: ground)
  // The rows force() computes: the rows some element reads (rset_; unread_: the
  // markers none reads).
  std::vector<RowSet> rset_;
  std::vector<char> unread_;
  std::vector<RowSet> oset_;   // observe(..., markers): the rows of those markers
  std::vector<int> observed_;  // ... and the markers they were formed for
  bool reads_only_ = true;
  // Elements whose loads depend on t alone (not state_dependent(), no inertia, no
  // internal states): their generalised loads ftime_ at t_time_, computed once per
  // t on the rows of their markers (tset_); the other elements' loads on the rows
  // of theirs (lset_), each residual: loaded_ (no inertia, not of time alone).
  std::vector<int> timed_, loaded_;
  std::vector<char> is_timed_;
  Vec ftime_, ftime_full_;
  double t_time_ = std::numeric_limits<double>::quiet_NaN();
  double t_time_full_ = std::numeric_limits<double>::quiet_NaN();
  std::vector<Mat3> axes_;  // per body marker: its axes R_GL R_LM at t_lof_
  std::vector<RowSet> lset_, tset_;
  // Jacobian: per body pair an element couples, Y = sum E_ij [Bu; Bt]_j over the
  // marker pairs (6 rows per marker of bi), then K_ij -= [Bu; Bt]_i^T Y.
  // Only the rows of bi's markers that an element of the pair loads carry
  // anything: Y keeps those (crow), Bc is the same rows of bi's stack (constant).
  struct PairWork {
    int bi = 0, bj = 0;
    std::vector<int> crow;  // per marker of bi: first row in Y (-1: not loaded)
    PairRowMat Y;           // [YK YC]: the loaded rows of bi, 2 n_bj columns
    PairRowMat Bc;          // the same rows of bi's stack
    Mat blk;                // -[Bu; Bt]^T [YK YC]
  };
  /// crow, Y, Bc of every pair from the elements that are not of time alone
  /// (after build_row_sets()).
  void build_pair_rows();
  /// force_jacobian() (comb null: K and C) or, with comb = (ck, cc), ck K + cc C
  /// into K alone (C unused).
  void jacobian(double t, const double* q, const double* v, const double* comb, SpMat& K, SpMat* C);
  /// jacobian(): D of element e (not of time alone) at the current motions.
  void element_derivatives(std::size_t e, double t);
  /// jacobian(): element e's D_ij added to the Y of its body pairs (comb as jacobian()).
  void add_element_pairs(std::size_t e, const double* comb);
  /// jacobian(): the pair blocks -Bc^T Y added to K (and C; comb as jacobian()).
  void add_pair_blocks(const double* comb, SpMat& K, SpMat* C);
  std::vector<PairWork> pairs_;
  std::vector<int> pair_index_;  // [bi * nb + bj] -> index in pairs_, -1 if none
  // block_start_[bi * nb + bj][c]: value index of the first row of body bi in
  // column offset(bj) + c of the pattern (-1 if the block is absent).
  std::vector<std::vector<int>> block_start_;
  double t_lof_ = std::numeric_limits<double>::quiet_NaN();
  // inertial elements
  std::vector<int> inertial_;  // element indices
  bool piecewise_ = false;
  int rank_ = 0;
  Mat U_, W_, Z_, WtA_;
  Vec f0_, y_, scratch_f_;
  Eigen::PartialPivLU<Mat> lu_;
};

}  // namespace evas
