// Space-truss beam generator (see truss.h).
//
// Layout. Cross-section k (k = 0..segments) sits at x = origin.x + k * length /
// segments and carries four corner nodes, numbered counter-clockwise when seen
// from +x:
//
//   corner 0: (y, z) = (-w/2, -w/2)     corner 1: (+w/2, -w/2)
//   corner 2: (+w/2, +w/2)              corner 3: (-w/2, +w/2)
//
// Node (k, c) has row index 4k + c and id 4k + c + 1.
//
// Bars:
//   * every cross-section: its 4 edges and both diagonals (in-plane rigid);
//   * every bay k -> k+1: 4 longitudinal bars (k, c)-(k+1, c), one diagonal on
//     each of the 4 side faces and one internal (space) diagonal.
// The face and internal diagonals alternate their direction from bay to bay
// (a Warren-like pattern), so that the beam has no built-in handedness and the
// bending/torsion coupling of a purely one-sided bracing is avoided.
//
// With these bars the free-free stiffness has exactly the 6 rigid-body null
// vectors (checked in tests/test_truss.cpp).
#include "bodies/truss.h"

#include <array>
#include <cmath>
#include <string>
#include <utility>

namespace evas {

namespace {

struct Bar {
  int a, b;  // node rows
};

std::vector<Bar> truss_bars(int segments) {
  std::vector<Bar> bars;
  auto node = [](int k, int c) { return 4 * k + (c % 4); };
  for (int k = 0; k <= segments; ++k) {
    for (int c = 0; c < 4; ++c) bars.push_back({node(k, c), node(k, c + 1)});
    bars.push_back({node(k, 0), node(k, 2)});
    bars.push_back({node(k, 1), node(k, 3)});
  }
  for (int k = 0; k < segments; ++k) {
    const bool even = (k % 2) == 0;
    for (int c = 0; c < 4; ++c) bars.push_back({node(k, c), node(k + 1, c)});
    for (int c = 0; c < 4; ++c) {
      if (even)
        bars.push_back({node(k, c), node(k + 1, c + 1)});
      else
        bars.push_back({node(k, c + 1), node(k + 1, c)});
    }
    if (even)
      bars.push_back({node(k, 0), node(k + 1, 2)});
    else
      bars.push_back({node(k, 1), node(k + 1, 3)});
  }
  return bars;
}

}  // namespace

FeModel make_truss_beam(const TrussBeamSpec& spec) {
  if (spec.segments < 1)
    throw InputError("truss beam: segments = " + std::to_string(spec.segments) + " must be >= 1");
  if (spec.segments > kMaxTrussSegments)
    throw InputError("truss beam: segments = " + std::to_string(spec.segments) +
                     " is more than the limit of " + std::to_string(kMaxTrussSegments));
  if (!std::isfinite(spec.length) || !std::isfinite(spec.width) || !std::isfinite(spec.youngs) ||
      !std::isfinite(spec.area) || !std::isfinite(spec.density))
    throw InputError("truss beam: length, width, youngs, area and density must be finite");
  if (!(spec.length > 0.0) || !(spec.width > 0.0) || !(spec.youngs > 0.0) || !(spec.area > 0.0) ||
      !(spec.density > 0.0))
    throw InputError("truss beam: length, width, youngs, area and density must be positive");
  if (!spec.origin.allFinite()) throw InputError("truss beam: origin is not finite");

  const int sections = spec.segments + 1;
  const int N = 4 * sections;
  const double h = 0.5 * spec.width;
  const std::array<std::pair<double, double>, 4> corner = {{{-h, -h}, {h, -h}, {h, h}, {-h, h}}};

  FeModel fe;
  fe.node_ids.resize(N);
  fe.s.resize(N, 3);
  for (int k = 0; k < sections; ++k) {
    const double x = spec.length * static_cast<double>(k) / spec.segments;
    for (int c = 0; c < 4; ++c) {
      const int i = 4 * k + c;
      fe.node_ids[i] = i + 1;
      fe.s.row(i) = (spec.origin + Vec3(x, corner[c].first, corner[c].second)).transpose();
    }
  }

  const std::vector<Bar> bars = truss_bars(spec.segments);
  std::vector<Triplet> kt;
  kt.reserve(bars.size() * 36);
  Vec lumped = Vec::Zero(N);
  for (const Bar& bar : bars) {
    const Vec3 d = (fe.s.row(bar.b) - fe.s.row(bar.a)).transpose();
    const double L = d.norm();
    const Vec3 e = d / L;
    const Mat3 k3 = (spec.youngs * spec.area / L) * (e * e.transpose());
    const std::array<int, 2> nodes = {bar.a, bar.b};
    for (int p = 0; p < 2; ++p)
      for (int q = 0; q < 2; ++q) {
        const double sign = (p == q) ? 1.0 : -1.0;
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c)
            kt.emplace_back(3 * nodes[p] + r, 3 * nodes[q] + c, sign * k3(r, c));
      }
    const double m = spec.density * spec.area * L;
    lumped[bar.a] += 0.5 * m;
    lumped[bar.b] += 0.5 * m;
  }
  fe.K.resize(3 * N, 3 * N);
  fe.K.setFromTriplets(kt.begin(), kt.end());
  fe.K.makeCompressed();

  std::vector<Triplet> mt;
  mt.reserve(N);
  for (int i = 0; i < N; ++i) mt.emplace_back(i, i, lumped[i]);
  fe.Ms.resize(N, N);
  fe.Ms.setFromTriplets(mt.begin(), mt.end());
  fe.Ms.makeCompressed();

  auto section_ids = [&](int k) {
    std::vector<long> ids(4);
    for (int c = 0; c < 4; ++c) ids[c] = fe.node_ids[4 * k + c];
    return ids;
  };
  for (int k = 0; k < sections; ++k) fe.node_sets["section" + std::to_string(k)] = section_ids(k);
  fe.node_sets["end0"] = section_ids(0);
  fe.node_sets["end1"] = section_ids(spec.segments);
  fe.node_sets["all"] = fe.node_ids;
  return fe;
}

}  // namespace evas
