#include "io/outputs.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "io/body_cache.h"

namespace evas {

namespace {
constexpr double kDeg = 180.0 / M_PI;
}

void check_output_rows(double rows, const char* grid) {
  if (!(rows <= kMaxOutputRows)) {
    std::ostringstream os;
    os << "output: the " << grid << " grid gives " << std::setprecision(3) << rows
       << " output rows, more than the limit of " << kMaxOutputRows
       << " (a larger step or a shorter run)";
    throw InputError(os.str());
  }
}

std::vector<double> crank_angle_times(const Lof& lof, double t0, double t1, double step_deg,
                                      double start_deg, bool start_given) {
  std::vector<double> times;
  const double a0 = lof.spin_angle(t0) * kDeg, a1 = lof.spin_angle(t1) * kDeg;
  if (!(step_deg > 0.0) || a1 == a0) return times;
  check_output_rows(std::abs(a1 - a0) / step_deg, "crank-angle");
  const double dir = a1 > a0 ? 1.0 : -1.0;
  // g increases along the run; targets are g-values start, start + step, ...
  auto g = [&](double t) { return dir * lof.spin_angle(t) * kDeg; };
  const double g0 = dir * a0, g1 = dir * a1;
  double target;
  if (start_given) {
    target = dir * start_deg;
    if (target < g0) target += std::ceil((g0 - target) / step_deg - 1e-9) * step_deg;
  } else {
    target = std::ceil(g0 / step_deg - 1e-9) * step_deg;
  }
  double lo = t0;
  for (long k = 0; target <= g1 + 1e-9 * step_deg; ++k) {
    double a = lo, b = t1;
    if (g(a) >= target) {
      times.push_back(a);
    } else {
      for (int it = 0; it < 200 && b - a > 1e-15 * std::max(1.0, std::abs(b)); ++it) {
        const double m = 0.5 * (a + b);
        (g(m) < target ? a : b) = m;
      }
      times.push_back(std::min(b, t1));
    }
    lo = times.back();
    target += step_deg;
    if (k > 100000000) break;
  }
  // Strictly ascending (rounding can repeat a time when step is tiny).
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

const std::vector<std::tuple<unsigned, const char*, const char*>>& marker_quantities() {
  static const std::vector<std::tuple<unsigned, const char*, const char*>> q = {
      {ChannelRequest::kPosition, "p", "m"},
      {ChannelRequest::kVelocity, "v", "m/s"},
      {ChannelRequest::kAcceleration, "a", "m/s^2"},
      {ChannelRequest::kAngularVelocity, "w", "rad/s"},
      {ChannelRequest::kAngularAcceleration, "al", "rad/s^2"}};
  return q;
}

OutputSet::OutputSet(const OutputSpec& spec, System& system, double t_start, double t_end)
    : sys_(system) {
  Model& model = sys_.model();
  if (spec.grid == "crank-angle") {
    crank_body_ = model.find_body(spec.crank_body);
    channels_.push_back({"crank_angle", "deg"});
    times_ = crank_angle_times(model.bodies()[crank_body_].lof, t_start, t_end, spec.step,
                               spec.start, spec.start_given);
  } else {
    const double start = spec.start_given ? spec.start : t_start;
    if (!(spec.step > 0.0)) throw InputError("output: step must be > 0");
    const double span = t_end - start;
    check_output_rows(span / spec.step, "time");
    const long count = static_cast<long>(std::floor(span / spec.step + 1e-9));
    for (long k = 0; k <= count; ++k) times_.push_back(std::min(t_end, start + k * spec.step));
  }
  for (const ChannelRequest& req : spec.channels) {
    Source src{req.kind, req.index, static_cast<int>(channels_.size()), 0u, false};
    switch (req.kind) {
      case ChannelRequest::Kind::Marker: {
        const std::string& m = model.markers().at(req.index).name;
        // name prefix and unit per quantity, in the order of marker_quantities()
        const char* suffix = req.local ? "_local" : "";
        for (const auto& [bit, prefix, unit] : marker_quantities())
          if (req.quantities & bit)
            for (const char* axis : {"x", "y", "z"})
              channels_.push_back({m + "." + prefix + axis + suffix, unit});
        src.quantities = req.quantities;
        src.local = req.local;
        if (req.quantities &
            (ChannelRequest::kAcceleration | ChannelRequest::kAngularAcceleration)) {
          if (sys_.constraint_count() > 0)
            throw InputError(
                "output: marker '" + m +
                "': acceleration channels are not available in a scene with joints (the "
                "constraint forces G^T lambda are not in the accelerations yet); request "
                "position, velocity or angular_velocity");
          accelerations_ = true;
        }
        break;
      }
      case ChannelRequest::Kind::Element: {
        const Element& e = *model.elements().at(req.index);
        for (const Channel& c : e.channels())
          channels_.push_back({e.name() + "." + c.name, c.unit});
        break;
      }
      case ChannelRequest::Kind::Modal: {
        const Body& b = model.bodies().at(req.index);
        for (int k = 0; k < b.n(); ++k)
          channels_.push_back({b.name + ".q" + std::to_string(k), ""});
        break;
      }
      case ChannelRequest::Kind::Torsion: {
        const Marker &a = model.markers().at(req.index), &b = model.markers().at(req.index2);
        Torsion tr;
        tr.offset = model.bodies().at(a.body).offset;
        tr.a = a.Bt.transpose() * req.axis;
        tr.b = b.Bt.transpose() * req.axis;
        src.torsion = static_cast<int>(torsion_.size());
        torsion_.push_back(std::move(tr));
        for (const char* c : {"angle_a", "angle_b", "twist"})
          channels_.push_back({req.name + "." + c, "rad"});
        for (const char* c : {"rate_a", "rate_b", "twist_rate"})
          channels_.push_back({req.name + "." + c, "rad/s"});
        break;
      }
      case ChannelRequest::Kind::Surface: {
        const Body& b = model.bodies().at(req.index);
        src.surface = static_cast<int>(surfaces_.size());
        surfaces_.push_back(surface_radiation_cached(
            b.data, *req.surface, req.rho_c, req.per_node,
            "output: surface '" + req.name + "' (body '" + b.name + "', set '" + req.set + "')"));
        const SurfaceRadiation& sr = surfaces_.back();
        channels_.push_back({req.name + ".vn_mean", "m/s"});
        channels_.push_back({req.name + ".vn_rms", "m/s"});
        channels_.push_back({req.name + ".erp", "W"});
        channels_.push_back({req.name + ".erp_elastic", "W"});
        channels_.push_back({req.name + ".erp_rigid", "W"});
        for (int k = 0; k < sr.components(); ++k)
          channels_.push_back({req.name + ".c" + std::to_string(k), "W^0.5"});
        for (int k = 0; k < sr.elastic_components(); ++k)
          channels_.push_back({req.name + ".e" + std::to_string(k), "W^0.5"});
        if (req.per_node)
          for (long id : req.surface->nodes)
            channels_.push_back({req.name + ".vn_" + std::to_string(id), "m/s"});
        break;
      }
    }
    sources_.push_back(src);
    if (req.kind == ChannelRequest::Kind::Marker) markers_.push_back(req.index);
    if (req.kind == ChannelRequest::Kind::Element)
      for (int mk : model.elements()[req.index]->markers()) markers_.push_back(mk);
  }
  // every channel under its own name (a torsion request may be named like an
  // element: the motor's `twist` would then appear twice)
  {
    std::vector<std::string> names;
    for (const Channel& c : channels_) names.push_back(c.name);
    std::sort(names.begin(), names.end());
    const auto twice = std::adjacent_find(names.begin(), names.end());
    if (twice != names.end())
      throw InputError("output: two channels are named '" + *twice +
                       "': give the torsion or surface request another 'name'");
  }
  std::sort(markers_.begin(), markers_.end());
  markers_.erase(std::unique(markers_.begin(), markers_.end()), markers_.end());
  const int m = sys_.constraint_count();
  if (m > 0) {
    constraint_first_ = static_cast<int>(channels_.size());
    for (int i = 0; i < m; ++i) {
      const std::string c = sys_.constraint_name(i);
      channels_.push_back({c + ".g", ""});
      channels_.push_back({c + ".g_dot", ""});
    }
    gbuf_.resize(static_cast<std::size_t>(m));
    gvbuf_.resize(static_cast<std::size_t>(m));
  }
}

void OutputSet::add_multiplier_channels() {
  const int m = sys_.constraint_count();
  if (m == 0 || lambda_first_ >= 0) return;
  lambda_first_ = static_cast<int>(channels_.size());
  for (int i = 0; i < m; ++i) channels_.push_back({sys_.constraint_name(i) + ".lambda", ""});
}

double OutputSet::crank_angle(double t) const {
  if (crank_body_ < 0) throw std::logic_error("OutputSet::crank_angle: no crank-angle grid");
  return sys_.model().bodies()[crank_body_].lof.spin_angle(t) * kDeg;
}

void OutputSet::values(double t, const double* q, const double* v, double* out,
                       const double* lambda) {
  Model& model = sys_.model();
  // the channels' markers (with inertial elements every marker and the full
  // accelerations: those elements report the solved ones)
  if (accelerations_)
    sys_.observe_accelerations(t, q, v);  // every marker, with the modal accelerations
  else
    sys_.observe(t, q, v, markers_);
  if (crank_body_ >= 0) out[0] = crank_angle(t);
  for (const Source& src : sources_) {
    double* o = out + src.first;
    switch (src.kind) {
      case ChannelRequest::Kind::Marker: {
        const MarkerMotion& m = sys_.motion(src.index);
        int k = 0;
        for (const auto& [bit, prefix, unit] : marker_quantities()) {
          if (!(src.quantities & bit)) continue;
          const Vec3& x = bit == ChannelRequest::kPosition          ? m.p
                          : bit == ChannelRequest::kVelocity        ? m.v
                          : bit == ChannelRequest::kAcceleration    ? m.a
                          : bit == ChannelRequest::kAngularVelocity ? m.w
                                                                    : m.al;
          const Vec3 y = src.local ? Vec3(m.R.transpose() * x) : x;
          for (int a = 0; a < 3; ++a) o[k++] = y[a];
        }
        break;
      }
      case ChannelRequest::Kind::Element: {
        const Element& e = *model.elements()[src.index];
        scratch_.clear();
        for (int m : e.markers()) scratch_.push_back(sys_.motion(m));
        e.channel_values_z(t, scratch_.data(), sys_.element_internal(src.index), o);
        break;
      }
      case ChannelRequest::Kind::Modal: {
        const Body& b = model.bodies()[src.index];
        for (int k = 0; k < b.n(); ++k) o[k] = q[b.offset + k];
        break;
      }
      case ChannelRequest::Kind::Torsion: {
        const Torsion& tr = torsion_[static_cast<std::size_t>(src.torsion)];
        const Eigen::Index n = tr.a.size();
        const Eigen::Map<const Vec> qb(q + tr.offset, n), vb(v + tr.offset, n);
        o[0] = tr.a.dot(qb);
        o[1] = tr.b.dot(qb);
        o[2] = o[1] - o[0];
        o[3] = tr.a.dot(vb);
        o[4] = tr.b.dot(vb);
        o[5] = o[4] - o[3];
        break;
      }
      case ChannelRequest::Kind::Surface: {
        const Body& b = model.bodies()[src.index];
        surfaces_[static_cast<std::size_t>(src.surface)].evaluate(b.lof.at(t), v + b.offset, o);
        break;
      }
    }
  }
  if (constraint_first_ >= 0) {
    sys_.constraint(t, q, v, gbuf_.data(), gvbuf_.data(), nullptr);
    for (std::size_t i = 0; i < gbuf_.size(); ++i) {
      out[constraint_first_ + 2 * static_cast<int>(i)] = gbuf_[i];
      out[constraint_first_ + 2 * static_cast<int>(i) + 1] = gvbuf_[i];
    }
  }
  if (lambda_first_ >= 0) {
    if (!lambda) throw RunError("output: the multipliers are missing at t = " + std::to_string(t));
    for (std::size_t i = 0; i < gbuf_.size(); ++i)
      out[lambda_first_ + static_cast<int>(i)] = lambda[i];
  }
}

}  // namespace evas
