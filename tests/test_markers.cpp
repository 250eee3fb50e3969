// Markers (formulation.md s. 4): a weighted node-set marker follows a rigid
// motion of its body exactly (translation and small rotation), a single-node
// marker has no rotation, and loads spread back preserve virtual work.
#include <gtest/gtest.h>

#include "elements/spring_damper.h"
#include "model/marker.h"
#include "model/model.h"
#include "random_body.h"

using namespace evas;

TEST(Markers, SetMarkerFollowsRigidMotionExactly) {
  const ModalBody b = test_bodies::random_body(30, 3, 4);
  std::vector<long> ids(b.node_ids.begin(), b.node_ids.begin() + 12);
  std::vector<double> w;
  for (int i = 0; i < 12; ++i) w.push_back(1.0 + 0.1 * i);
  const Marker m = make_set_marker("m", 0, b, ids, w);
  ASSERT_TRUE(m.has_rotation);
  // A rigid displacement: translation T and small rotation th about the
  // centre of mass, expressed as nodal displacements and projected on modes.
  const MassProperties mp = mass_properties(b.s, b.mass);
  const Vec3 T(1e-3, -2e-3, 0.5e-3), th(1e-4, 3e-4, -2e-4);
  Vec u(3 * b.num_nodes());
  for (int i = 0; i < b.num_nodes(); ++i)
    u.segment<3>(3 * i) = T + th.cross(b.s.row(i).transpose() - mp.com);
  const Vec q = b.modes.transpose() * apply_mass(b.mass, u);  // exact: u lies in the rigid span
  const Vec3 u_m = m.Bu * q, th_m = m.Bt * q;
  EXPECT_LT((th_m - th).norm(), 1e-12);
  EXPECT_LT((u_m - (T + th.cross(m.c - mp.com))).norm(), 1e-12);
}

TEST(Markers, NodeMarkerAndVirtualWork) {
  const ModalBody b = test_bodies::random_body(10, 4, 5);
  const Marker m = make_node_marker("n", 0, b, b.node_ids[3]);
  EXPECT_FALSE(m.has_rotation);
  EXPECT_LT((m.Bu - b.modes.middleRows(9, 3)).norm(), 1e-15);  // node index 3: rows 9..11
  // Q = Bu^T F: virtual work dq.Q equals F.du for du = Bu dq.
  const Vec dq = Vec::Random(b.num_modes());
  const Vec3 F(3, -1, 2);
  EXPECT_NEAR(dq.dot(m.Bu.transpose() * F), F.dot(m.Bu * dq), 1e-12);
  EXPECT_THROW(make_node_marker("x", 0, b, 999999), InputError);
}

TEST(Markers, MotionInGroundFrame) {
  const ModalBody b = test_bodies::random_body(10, 2, 6);
  const Marker m = make_node_marker("n", 0, b, b.node_ids[2]);
  const Lof lof = Lof::spin(Vec3(0.1, 0, 0), Mat3::Identity(), Vec3::UnitZ(), 0.0, {0.0}, {10.0});
  const LofState L = lof.at(0.1);
  const Vec q = Vec::Zero(b.num_modes()), v = Vec::Zero(b.num_modes());
  MarkerMotion mm;
  marker_motion(m, L, q.data(), v.data(), mm);
  const Vec3 r = L.R_GL * m.c;
  EXPECT_LT((mm.p - (L.p_GL + r)).norm(), 1e-14);
  EXPECT_LT((mm.v - Vec3(0, 0, 10).cross(r)).norm(), 1e-12);
  EXPECT_NEAR(mm.psi.z(), 1.0, 1e-14);  // 10 rad/s for 0.1 s
}

TEST(Markers, SetMarkerAboutAGivenCentreFollowsRigidMotion) {
  // Found in review: a centre away from the centroid must not change the fitted
  // rotation, and its translation is that of the rigidly attached point.
  const ModalBody b = test_bodies::random_body(30, 3, 4);
  std::vector<long> ids(b.node_ids.begin(), b.node_ids.begin() + 10);
  const Vec3 centre(0.4, -0.3, 0.2);
  const Marker m = make_set_marker("m", 0, b, ids, {}, &centre);
  const MassProperties mp = mass_properties(b.s, b.mass);
  const Vec3 T(1e-3, 2e-3, -1e-3), th(2e-4, -1e-4, 3e-4);
  Vec u(3 * b.num_nodes());
  for (int i = 0; i < b.num_nodes(); ++i)
    u.segment<3>(3 * i) = T + th.cross(b.s.row(i).transpose() - mp.com);
  const Vec q = b.modes.transpose() * apply_mass(b.mass, u);
  EXPECT_LT((m.Bt * q - th).norm(), 1e-12 * th.norm());
  EXPECT_LT((m.Bu * q - (T + th.cross(centre - mp.com))).norm(), 1e-12 * T.norm());
  EXPECT_LT((m.c - centre).norm(), 1e-15);
}

TEST(Markers, MomentOnAMarkerWithoutRotationIsRejected) {
  // A rotational spring on a single-node marker would have its moment dropped
  // by the virtual-work map (Bt = 0): the model refuses it with a clear error.
  auto b = std::make_shared<ModalBody>(test_bodies::random_body(10, 2, 6));
  Model model;
  model.add_body("b", b, Lof::fixed(Vec3::Zero(), Mat3::Identity()));
  const int node = model.add_marker(make_node_marker("node", 0, *b, b->node_ids[2]));
  const int set = model.add_marker(make_set_marker("set", 0, *b, b->node_sets.at("first4"), {}));
  const int g = model.add_marker(make_ground_marker("g", Vec3::Zero(), Mat3::Identity()));
  auto spring = [](const std::string& n, int m0, int m1, double kr) {
    return std::make_unique<SpringDamper>(n, std::vector<int>{m0, m1}, Vec3(1, 1, 1), Vec3::Zero(),
                                          Vec3(kr, kr, kr), Vec3::Zero(), Vec3::Zero(),
                                          Vec3::Zero());
  };
  model.add_element(spring("translational", g, node, 0.0));  // no moment: fine
  model.add_element(spring("rotational", g, set, 5.0));      // set with rotation: fine
  try {
    model.add_element(spring("bad", g, node, 5.0));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("element 'bad': marker 'node' carries no rotation"),
              std::string::npos)
        << e.what();
  }
}

// ModalBody::node_indices (a binary search when the body's ids increase, as
// an FE body's do, else one hash table) against node_index (a linear search),
// and the same InputError for an id the body does not have: below, between and
// above the body's ids.
TEST(Markers, NodeIndicesMatchNodeIndex) {
  for (const bool increasing : {false, true}) {
    ModalBody b = test_bodies::random_body(40, 2, 7);
    const long N = static_cast<long>(b.node_ids.size());
    for (long i = 0; i < N; ++i)
      b.node_ids[static_cast<std::size_t>(i)] = 1000 + 7 * (increasing ? i : N - i);
    std::vector<long> ids;
    for (int i = 39; i >= 0; i -= 3) ids.push_back(b.node_ids[static_cast<std::size_t>(i)]);
    ASSERT_GE(ids.size(), 8u);
    const std::vector<int> rows = b.node_indices(ids);
    ASSERT_EQ(rows.size(), ids.size());
    for (std::size_t k = 0; k < ids.size(); ++k)
      EXPECT_EQ(rows[k], b.node_index(ids[k])) << k << (increasing ? " increasing" : "");
    for (const long missing : {5L, 1003L, 99999L}) {
      std::vector<long> bad = ids;
      bad.push_back(missing);
      try {
        b.node_indices(bad);
        ADD_FAILURE() << "no error for node " << missing;
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("no node with id " + std::to_string(missing)),
                  std::string::npos)
            << e.what();
      }
    }
  }
}
