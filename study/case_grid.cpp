// Case-grid expansion (case_grid.h).
#include "study/case_grid.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "integrators/settings.h"

namespace evas::study {

namespace {

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r\n");
  return s.substr(a, b - a + 1);
}

bool parse_double(const std::string& s, double& x) {
  if (s.empty()) return false;
  char* end = nullptr;
  errno = 0;
  x = std::strtod(s.c_str(), &end);
  return end != s.c_str() && *end == '\0' && errno != ERANGE && std::isfinite(x);
}

std::string kind_of(const std::string& key) {
  for (const auto& info : integrator_settings())
    if (info.key == key) return info.kind;
  for (const auto& [name, d] : declared_settings())
    if (d.key == key) return d.integer ? "integer" : "number";
  return "";
}

}  // namespace

std::vector<std::string> log_range(const std::string& key, const std::string& item,
                                   const std::string& kind) {
  const auto dots = item.find("..");
  const auto slash = item.rfind('/');
  if (slash == std::string::npos || slash < dots)
    throw InputError(key + ": range '" + item + "' must be A..B/N (N log-spaced values)");
  const std::string a_text = trim(item.substr(0, dots));
  const std::string b_text = trim(item.substr(dots + 2, slash - dots - 2));
  const std::string n_text = trim(item.substr(slash + 1));
  if (kind != "number" && kind != "integer")
    throw InputError(key + ": a range '" + item + "' needs a numeric setting");
  double a = 0, b = 0, n = 0;
  if (!parse_double(a_text, a) || !parse_double(b_text, b))
    throw InputError(key + ": range '" + item + "': A and B must be numbers");
  if (!parse_double(n_text, n) || n != std::floor(n) || n < 1 || n > 10000)
    throw InputError(key + ": range '" + item + "': N must be an integer in [1, 10000]");
  if (!(a > 0) || !(b > 0))
    throw InputError(key + ": range '" + item + "': A and B must be > 0 (log spacing)");
  const int count = static_cast<int>(n);
  if (count == 1 && a != b)
    throw InputError(key + ": range '" + item + "': N must be >= 2 when A != B");
  std::vector<std::string> out;
  for (int k = 0; k < count; ++k) {
    std::string text;
    if (k == 0) {
      text = a_text;
    } else if (k == count - 1) {
      text = b_text;
    } else {
      const double x =
          std::exp(std::log(a) + (std::log(b) - std::log(a)) * k / static_cast<double>(count - 1));
      char buf[40];
      std::snprintf(buf, sizeof buf, "%.10g", x);
      text = buf;
    }
    if (kind == "integer") {
      double x = 0;
      parse_double(text, x);
      text = std::to_string(std::llround(x));
      if (!out.empty() && out.back() == text) continue;
    }
    out.push_back(text);
  }
  return out;
}

std::string number_text(double x) {
  if (x == std::floor(x) && std::abs(x) < 1e15) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.0f", x);
    return buf;
  }
  for (int p = 1; p <= 17; ++p) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.*g", p, x);
    if (std::strtod(buf, nullptr) == x) return buf;
  }
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

bool glob_match(const std::string& pattern, const std::string& text) {
  std::size_t p = 0, t = 0, star = std::string::npos, mark = 0;
  while (t < text.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == text[t])) {
      ++p;
      ++t;
    } else if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      mark = t;
    } else if (star != std::string::npos) {
      p = star + 1;
      t = ++mark;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

std::vector<std::string> split_list(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::string cur;
  int depth = 0;
  for (char c : text) {
    if (c == '[' || c == '{') ++depth;
    if (c == ']' || c == '}') --depth;
    if (c == sep && depth <= 0) {
      out.push_back(trim(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(trim(cur));
  return out;
}

std::vector<std::string> expand_values(const std::string& key, const std::string& values) {
  std::vector<std::string> out;
  for (const std::string& item : split_list(values, ',')) {
    if (item.empty()) throw InputError(key + ": empty value in '" + values + "'");
    if (item.find("..") != std::string::npos) {
      for (auto& v : log_range(key, item, kind_of(key))) out.push_back(v);
    } else {
      out.push_back(item);
    }
  }
  return out;
}

namespace {

// "A..B:S" -> A, A + S, ..., up to B (inclusive within 1e-9 of S).
std::vector<std::string> linear_range(const std::string& where, const std::string& item) {
  const auto dots = item.find(".."), colon = item.find(':', item.find("..") + 2);
  auto num = [&](const std::string& t) {
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || *end || !std::isfinite(v))
      throw InputError(where + ": '" + item + "': expected A..B:STEP with numbers A, B, STEP");
    return v;
  };
  const double a = num(item.substr(0, dots)), b = num(item.substr(dots + 2, colon - dots - 2)),
               step = num(item.substr(colon + 1));
  if (!(step > 0.0) || b < a)
    throw InputError(where + ": '" + item +
                     "': a linear range A..B:STEP needs B >= A and STEP > 0");
  const double n = std::floor((b - a) / step + 1e-9);
  if (n > 100000) throw InputError(where + ": '" + item + "': more than 100000 values");
  // decimals written after the point (-1: an exponent, or none to go by)
  auto decimals = [](const std::string& t) {
    if (t.find_first_of("eE") != std::string::npos) return -1;
    const auto p = t.find('.');
    return p == std::string::npos ? 0 : static_cast<int>(t.size() - p - 1);
  };
  const int da = decimals(item.substr(0, dots)), ds = decimals(item.substr(colon + 1));
  const int d = da < 0 || ds < 0 ? -1 : std::max(da, ds);
  std::vector<std::string> out;
  for (long k = 0; k <= static_cast<long>(n); ++k) {
    // A + k S with one rounding (fma): the same value whatever the compiler
    // contracts, and the nearest double to the exact one
    const double v = std::fma(static_cast<double>(k), step, a);
    // written with the decimals A and S were written with (157.08, not
    // 157.07999999999998 for 104.72 + 52.36): the value the user meant
    std::string text = number_text(v);
    if (d >= 0 && d <= 15) {
      std::ostringstream os;
      os << std::fixed << std::setprecision(d) << v;
      std::string t = os.str();
      if (t.find('.') != std::string::npos) {
        while (t.back() == '0') t.pop_back();
        if (t.back() == '.') t.pop_back();
      }
      if (t == "-0") t = "0";
      if (std::abs(std::strtod(t.c_str(), nullptr) - v) <= 1e-9 * step) text = t;
    }
    out.push_back(text);
  }
  return out;
}

}  // namespace

ParamSweep parse_sweep(const std::string& assignment, const std::string& option) {
  const std::string where = option + " '" + assignment + "'";
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError(where + ": expected ITEM.KEY=V1,V2,...");
  ParamSweep sw;
  sw.key = assignment.substr(0, eq);
  for (const auto& item : split_list(assignment.substr(eq + 1), ',')) {
    if (item.empty()) throw InputError(where + ": empty value");
    const auto dots = item.find("..");
    if (dots != std::string::npos && item.find('/', dots) != std::string::npos) {
      // a log range runs upward (a linear one is refused by linear_range): a
      // downward one is a slip more often than a wish
      double a = 0.0, b = 0.0;
      const auto end = item.find_first_of(":/", dots);
      if (parse_double(item.substr(0, dots), a) &&
          parse_double(
              item.substr(dots + 2, end == std::string::npos ? std::string::npos : end - dots - 2),
              b) &&
          b < a)
        throw InputError(where + ": the range " + item + " runs downward (" + number_text(a) +
                         " to " + number_text(b) +
                         "): write it upward, or list the values in the order wanted");
    }
    if (dots != std::string::npos && item.find(':', dots) != std::string::npos) {
      for (auto& v : linear_range(where, item)) sw.values.push_back(v);
    } else if (dots != std::string::npos && item.find('/') != std::string::npos) {
      for (auto& v : log_range(option + " " + sw.key, item, "number")) sw.values.push_back(v);
    } else {
      sw.values.push_back(item);
    }
  }
  return sw;
}

std::vector<Case> expand_case(const std::string& spec, const IntegratorSettings& base,
                              const std::string& where) {
  const std::string prefix =
      where.empty() ? "--case '" + spec + "': " : where + ": case '" + spec + "': ";
  std::istringstream words(spec);
  std::vector<std::string> tokens;
  for (std::string w; words >> w;) tokens.push_back(w);
  if (tokens.empty()) throw InputError(prefix + "empty case (expected NAME KEY=VALUES ...)");

  IntegratorSettings start = base;
  std::size_t first = 0;
  if (tokens[0].find('=') == std::string::npos) {
    try {
      set_integrator_setting(start, "name", tokens[0]);
    } catch (const InputError& e) {
      throw InputError(prefix + "integrator " + e.what());
    }
    first = 1;
  }
  std::vector<std::pair<std::string, std::vector<std::string>>> axes;
  for (std::size_t i = first; i < tokens.size(); ++i) {
    const auto eq = tokens[i].find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError(prefix + "'" + tokens[i] + "' is not KEY=VALUES");
    const std::string key = tokens[i].substr(0, eq);
    if (key == "name")
      throw InputError(prefix + "the integrator is the first word, not a name= key");
    for (const auto& a : axes)
      if (a.first == key) throw InputError(prefix + "'" + key + "' is given twice");
    try {
      get_integrator_setting(start, key);  // unknown key -> InputError listing the known ones
      axes.emplace_back(key, expand_values(key, tokens[i].substr(eq + 1)));
    } catch (const InputError& e) {
      throw InputError(prefix + e.what());
    }
  }

  std::vector<std::string> swept;
  std::size_t total = 1;
  for (const auto& a : axes) {
    if (a.second.size() > 1) swept.push_back(a.first);
    total *= a.second.size();
    if (total > 100000) throw InputError(prefix + "more than 100000 cases");
  }
  std::vector<Case> cases;
  std::vector<std::size_t> idx(axes.size(), 0);
  std::vector<bool> read(axes.size(), false);  // a key some case's method reads
  for (std::size_t n = 0; n < total; ++n) {
    Case c;
    c.settings = start;
    c.spec = spec;
    c.swept = swept;
    for (std::size_t k = 0; k < axes.size(); ++k) {
      try {
        set_integrator_setting(c.settings, axes[k].first, axes[k].second[idx[k]]);
      } catch (const InputError& e) {
        throw InputError(prefix + e.what());
      }
    }
    for (std::size_t k = 0; k < axes.size(); ++k)
      read[k] = read[k] || setting_unread_reason(c.settings, axes[k].first).empty();
    c.label = settings_label(c.settings);
    cases.push_back(std::move(c));
    // odometer, last key fastest
    for (std::size_t k = axes.size(); k-- > 0;) {
      if (++idx[k] < axes[k].second.size()) break;
      idx[k] = 0;
    }
  }
  // a key no case reads would make its values the same run under other labels
  for (std::size_t k = 0; k < axes.size(); ++k)
    if (!read[k])
      throw InputError(prefix + "'" + axes[k].first +
                       "': " + setting_unread_reason(cases.front().settings, axes[k].first) +
                       ", so it has no effect on these cases");
  return cases;
}

std::vector<std::pair<std::string, std::string>> read_cases_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the cases file");
  std::vector<std::pair<std::string, std::string>> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    line = trim(line);
    if (!line.empty()) out.emplace_back(line, path + ":" + std::to_string(n));
  }
  if (out.empty()) throw InputError(path + ": no case in the cases file");
  return out;
}

}  // namespace evas::study
