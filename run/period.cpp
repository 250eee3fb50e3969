// The period of a scene's forcing (period.h).
#include "run/period.h"

#include <cctype>
#include <cmath>
#include <cstdlib>

namespace evas::run {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The body whose spin gives the crank angle: the output's crank-angle body, or
// the one body with a spin LOF; -1 when there is none, with the reason.
int crank_body(const Scene& scene, std::string& why) {
  const auto& bodies = scene.model->bodies();
  if (scene.output.grid == "crank-angle" && !scene.output.crank_body.empty()) {
    for (std::size_t b = 0; b < bodies.size(); ++b)
      if (bodies[b].name == scene.output.crank_body) return static_cast<int>(b);
  }
  int found = -1;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].lof.kind() != LofKind::Spin) continue;
    if (found >= 0) {
      why = "bodies '" + bodies[static_cast<std::size_t>(found)].name + "' and '" + bodies[b].name +
            "' both spin and the output names no crank-angle body to take the period from";
      return -1;
    }
    found = static_cast<int>(b);
  }
  if (found < 0) why = "no body spins (no crank whose turns set a period)";
  return found;
}

bool has_pistons(const Scene& scene) {
  for (const auto& e : scene.model->elements())
    if (e->type() == "piston-conrod") return true;
  return false;
}

bool near(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() <= 1e-8 * (1.0 + a.cwiseAbs().maxCoeff());
}

// "" when every body's frame is the same at t0 and t0 + T, else which is not.
std::string frames_repeat(const Scene& scene, double T) {
  const double t0 = scene.t_start;
  for (const Body& b : scene.model->bodies()) {
    if (b.lof.kind() == LofKind::Tracking)
      return "body '" + b.name + "' has a tracking LOF, re-anchored as it moves";
    if (b.lof.kind() == LofKind::Spin && !b.lof.speed_profile().is_constant())
      return "body '" + b.name + "' spins at a speed that changes (a speed profile)";
    const LofState a = b.lof.at(t0), c = b.lof.at(t0 + T);
    if (!near(a.p_GL, c.p_GL) || !near(a.v_GL, c.v_GL) || !near(a.a_GL, c.a_GL))
      return "the origin of body '" + b.name + "' moves and is elsewhere one period later";
    if (!near(a.R_GL, c.R_GL) || !near(a.w_GL_G, c.w_GL_G))
      return "the frame of body '" + b.name + "' is turned otherwise one period later";
  }
  return "";
}

// Parses "720deg", "720 deg", "0.04s", "0.04 s": the value and its unit.
bool parse_period(const std::string& text, double& value, std::string& unit) {
  const char* s = text.c_str();
  char* end = nullptr;
  value = std::strtod(s, &end);
  if (end == s) return false;
  std::string rest(end);
  std::string u;
  for (char ch : rest)
    if (!std::isspace(static_cast<unsigned char>(ch))) u += ch;
  if (u != "deg" && u != "s") return false;
  unit = u;
  return std::isfinite(value) && value > 0.0;
}

}  // namespace

std::optional<ScenePeriod> natural_period(const Scene& scene, std::string& why) {
  const int cb = crank_body(scene, why);
  if (cb < 0) return std::nullopt;
  const Body& body = scene.model->bodies()[static_cast<std::size_t>(cb)];
  if (body.lof.kind() != LofKind::Spin) {
    why = "the crank-angle body '" + body.name + "' does not spin";
    return std::nullopt;
  }
  if (!body.lof.speed_profile().is_constant()) {
    why = "body '" + body.name + "' spins at a speed that changes (a speed profile)";
    return std::nullopt;
  }
  const double w = std::abs(body.lof.speed_profile().speeds().front());
  if (!(w > 0.0)) {
    why = "body '" + body.name + "' does not turn (speed 0)";
    return std::nullopt;
  }
  ScenePeriod p;
  p.crank_body = cb;
  const bool pistons = has_pistons(scene);
  p.degrees = pistons ? 720.0 : 360.0;
  p.seconds = p.degrees * kPi / 180.0 / w;
  p.basis = format_number(p.degrees) + " deg of '" + body.name + "' (" +
            (pistons ? "four-stroke pistons" : "one turn") + ") at " + format_number(w) + " rad/s";
  if (const std::string r = frames_repeat(scene, p.seconds); !r.empty()) {
    why = r;
    return std::nullopt;
  }
  return p;
}

ScenePeriod scene_period(const Scene& scene, const std::string& given) {
  std::string why;
  const std::optional<ScenePeriod> own = natural_period(scene, why);
  if (given.empty()) {
    if (!own)
      throw InputError(scene.path + ": the scene has no period: " + why +
                       "; give one with --period (e.g. --period 720deg or --period 0.04s)");
    return *own;
  }
  double value = 0.0;
  std::string unit;
  if (!parse_period(given, value, unit))
    throw InputError("--period: '" + given +
                     "' is not a positive period with its unit (e.g. 720deg or 0.04s)");
  ScenePeriod p;
  if (unit == "deg") {
    const int cb = crank_body(scene, why);
    if (cb < 0 || scene.model->bodies()[static_cast<std::size_t>(cb)].lof.kind() != LofKind::Spin ||
        !scene.model->bodies()[static_cast<std::size_t>(cb)].lof.speed_profile().is_constant())
      throw InputError("--period " + given + ": a period in degrees needs a crank turning at " +
                       "constant speed, and " + (why.empty() ? "its speed changes" : why) +
                       "; give it in seconds");
    const Body& body = scene.model->bodies()[static_cast<std::size_t>(cb)];
    p.crank_body = cb;
    p.degrees = value;
    p.seconds = value * kPi / 180.0 / std::abs(body.lof.speed_profile().speeds().front());
  } else {
    p.seconds = value;
    if (own) {
      p.crank_body = own->crank_body;
      p.degrees = own->degrees * value / own->seconds;
    }
  }
  p.basis = "--period " + given;
  if (own) {
    const double ratio = p.seconds / own->seconds;
    if (std::abs(ratio - std::round(ratio)) > 1e-9 * std::max(1.0, ratio) || std::round(ratio) < 1)
      throw InputError("--period " + given + ": " + scene.path +
                       ": the scene's forcing repeats every " + own->basis + " (" +
                       format_number(own->seconds) +
                       " s); a period must be a whole multiple of it, and this one is " +
                       format_number(ratio) + " times it");
  }
  if (const std::string r = frames_repeat(scene, p.seconds); !r.empty())
    throw InputError("--period " + given + ": " + scene.path + ": the scene does not repeat: " + r);
  return p;
}

}  // namespace evas::run
