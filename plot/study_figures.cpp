#include "plot/study_figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "io/hdf5_util.h"
#include "model/types.h"
#include "plot/gnuplot.h"
#include "plot/study_file.h"

namespace evas {

namespace {

// `label` without the words whose key (before '=') is in `keys`.
std::string without_keys(const std::string& label, const std::set<std::string>& keys) {
  std::istringstream in(label);
  std::string word, out;
  while (in >> word)
    if (!keys.count(word.substr(0, word.find('=')))) out += (out.empty() ? "" : " ") + word;
  return out;
}

bool usable(double e) { return e > 0.0 && std::isfinite(e); }

}  // namespace

const std::vector<WorkAxis>& work_axes() {
  static const std::vector<WorkAxis> axes = {
      {"residuals", "residual_evals", "residual evaluations"},
      {"steps", "steps", "steps"},
      {"factorizations", "linear_setups", "factorizations (linear setups)"},
      {"jacobians", "jacobian_evals", "Jacobian evaluations"},
      {"iterations", "nonlinear_iterations", "nonlinear iterations"}};
  return axes;
}

const WorkAxis& work_axis(const std::string& name) {
  std::string names;
  for (const auto& a : work_axes()) {
    if (name == a.name) return a;
    names += (names.empty() ? "" : ", ") + std::string(a.name);
  }
  throw InputError("--work '" + name + "': expected wall or one of " + names);
}

WorkPrecisionData read_work_precision(const std::string& path) {
  WorkPrecisionData d;
  h5::Quiet quiet;
  try {
    h5::Handle f = h5::open_file(path);
    expect_study_file(f, path, "work-precision", "plot work-precision",
                      "a work-precision study's file",
                      "`evas study work-precision` writes study.h5");
    d.scene_name = h5::read_string_attribute(f, "scene_name");
    d.window = h5::read_string_attribute(f, "window");
    d.norm = h5::read_string_attribute(f, "norm");
    if (!h5::exists(f, "/cases/family"))
      throw InputError(path +
                       ": the study's file has no /cases/family (written by an evas "
                       "before 2026-11-29): run the study again");
    if (h5::has_attribute(f, "work")) d.work = h5::read_string_attribute(f, "work");
    if (h5::exists(f, "/reference"))
      d.reference = h5::read_string_attribute(h5::open_group(f, "reference"), "description");
    std::vector<hsize_t> dims;
    const auto family = h5::read_strings(f, "/cases/family");
    const auto status = h5::read_strings(f, "/cases/status");
    const auto error = h5::read_doubles(f, "/cases/error", dims);
    const auto wall = h5::read_doubles(f, "/cases/wall", dims);
    const auto res =
        h5::read_doubles(f, std::string("/cases/stats/") + work_axis(d.work).field, dims);
    const std::size_t n = family.size();
    if (status.size() != n || error.size() != n || wall.size() != n || res.size() != n)
      throw h5::Failure("the /cases datasets differ in length");
    for (std::size_t i = 0; i < n; ++i)
      if (status[i] == "completed" && usable(error[i]))
        d.points.push_back({family[i], wall[i], error[i], res[i]});
  } catch (const h5::Failure& e) {
    throw InputError(path + ": " + e.what());
  }
  return d;
}

std::string work_precision_script(const WorkPrecisionData& d, const std::filesystem::path& out) {
  std::map<std::string, std::vector<const WorkPrecisionPoint*>> fam;
  std::vector<std::string> order;
  for (const auto& p : d.points) {
    if (!usable(p.error)) continue;
    if (!fam.count(p.family)) order.push_back(p.family);
    fam[p.family].push_back(&p);
  }
  if (order.empty()) return "";
  // settings every curve shares (e.g. the scene's linear solver) go to the
  // title, so that the legend stays short enough not to cover the curves
  std::vector<std::string> common;  // "key=value" in every family
  std::set<std::string> common_keys;
  if (order.size() > 1) {
    std::istringstream first(order.front());
    std::string word;
    first >> word;  // the integrator's name
    while (first >> word) {
      bool all = true;
      for (const auto& f : order)
        all = all && (" " + f + " ").find(" " + word + " ") != std::string::npos;
      if (all) {
        common.push_back(word);
        common_keys.insert(word.substr(0, word.find('=')));
      }
    }
  }
  std::vector<std::string> legend;
  for (const auto& f : order) legend.push_back(without_keys(f, common_keys));
  std::string shared;
  for (const auto& w : common) shared += (shared.empty() ? "" : " ") + w;
  // one legend for both panels below them: in two columns, or in one when a
  // label is too long for half the width (the second column was cut off)
  std::size_t longest = 0;
  for (const auto& l : legend) longest = std::max(longest, l.size());
  const bool one_column = longest > 70;
  const int key_rows = static_cast<int>(one_column ? order.size() : (order.size() + 1) / 2);
  std::ostringstream gp;
  gp << "# work-precision figure of " << d.scene_name << " (evas study)\n"
     << gp_terminal(out, 1400, 560 + 18 * key_rows);
  // each curve joins its points in order of work: by wall time ($F) and by
  // the work count ($W) for the second panel
  for (std::size_t i = 0; i < order.size(); ++i) {
    for (const char* block : {"F", "W"}) {
      auto pts = fam[order[i]];
      const bool by_wall = block[0] == 'F';
      std::stable_sort(pts.begin(), pts.end(),
                       [by_wall](const WorkPrecisionPoint* a, const WorkPrecisionPoint* b) {
                         return by_wall ? a->wall < b->wall : a->work < b->work;
                       });
      gp << "$" << block << i << " << EOD\n";
      for (const auto* p : pts)
        gp << gp_num(p->wall, 9) << " " << gp_num(p->error, 9) << " " << gp_num(p->work, 12)
           << "\n";
      gp << "EOD\n";
    }
  }
  const std::string ref = d.reference.empty() ? "" : "; reference " + d.reference;
  gp << "set multiplot layout 1,2 title "
     << gp_quote("work-precision: " + d.scene_name + " (window " + d.window + ", --norm " + d.norm +
                 ref + ")" + (common.empty() ? "" : "; all curves: " + shared))
     << "\n"
     << "set logscale xy\nset format y '1e%L'\nset grid\nset bmargin " << key_rows + 5 << "\n"
     << "set key at screen 0.02,screen 0.01 left bottom vertical maxrows " << key_rows
     << " Left reverse samplen 2 width -4\n"
     << "set ylabel " << gp_quote("error (--norm " + d.norm + ")") << "\n";
  auto curves = [&](const char* block, const char* using_) {
    gp << "plot ";
    for (std::size_t i = 0; i < order.size(); ++i)
      gp << (i ? ", " : "") << "$" << block << i << " using " << using_ << " with linespoints pt "
         << (i < 8 ? 7 : 5) << " title " << gp_quote(legend[i]);  // past 8 the colours repeat
    gp << "\n";
  };
  gp << "set xlabel 'wall time [s]'\n";
  curves("F", "1:2");
  gp << "set xlabel " << gp_quote(work_axis(d.work).label) << "\nunset key\n";
  curves("W", "3:2");
  gp << "unset multiplot\n";
  return gp.str();
}

std::string convergence_script(const std::string& scene_name, const std::string& family,
                               const std::string& measure, const std::string& key,
                               const std::vector<double>& x, const std::vector<double>& error,
                               double slope, const std::filesystem::path& out) {
  std::ostringstream data;
  double sx = 0, sy = 0;
  int n = 0;
  for (std::size_t i = 0; i < x.size() && i < error.size(); ++i) {
    if (!usable(error[i]) || !(x[i] > 0.0)) continue;
    data << gp_num(x[i], 12) << " " << gp_num(error[i], 12) << "\n";
    sx += std::log(x[i]);
    sy += std::log(error[i]);
    ++n;
  }
  if (n == 0) return "";
  std::ostringstream gp;
  gp << "# convergence figure of " << scene_name << " (evas study)\n"
     << gp_terminal(out, 900, 600) << "$D << EOD\n"
     << data.str() << "EOD\n"
     << "set logscale xy\nset format y '1e%L'\nset grid\nset key top left\n"
     << "set xlabel " << gp_quote(key) << "\n"
     << "set ylabel 'error'\n"
     << "set title " << gp_quote("convergence: " + family + " on " + scene_name + "; " + measure)
     << "\n";
  if (!std::isnan(slope)) {
    const double b = sy / n - slope * sx / n;  // the fit passes through the centroid
    gp << "f(x) = exp(" << gp_num(b, 12) << ") * x**(" << gp_num(slope, 12) << ")\n"
       << "plot $D using 1:2 with linespoints pt 7 title 'error', f(x) with lines dt 2 title "
       << gp_quote("slope " + gp_num(slope, 3)) << "\n";
  } else {
    gp << "plot $D using 1:2 with linespoints pt 7 title 'error'\n";
  }
  return gp.str();
}

}  // namespace evas
