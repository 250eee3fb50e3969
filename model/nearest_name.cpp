// Nearest names for messages (nearest_name.h).
#include "model/nearest_name.h"

#include <algorithm>
#include <cctype>
#include <numeric>

namespace evas {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (same ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::vector<std::string> nearest_names(const std::string& wanted,
                                       const std::vector<std::string>& names, std::size_t count) {
  std::string w;
  for (char c : wanted)
    if (c != '*' && c != '?') w += c;
  std::vector<std::size_t> order(names.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::vector<std::size_t> dist(names.size());
  for (std::size_t i = 0; i < names.size(); ++i) dist[i] = edit_distance(w, names[i]);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return dist[x] < dist[y]; });
  std::vector<std::string> out;
  for (std::size_t k = 0; k < order.size() && k < count; ++k) out.push_back(names[order[k]]);
  return out;
}

std::string nearest_text(const std::string& wanted, const std::vector<std::string>& names,
                         std::size_t count) {
  if (names.empty()) return "";
  std::string s = "nearest: ";
  const auto near = nearest_names(wanted, names, count);
  for (std::size_t i = 0; i < near.size(); ++i) s += (i ? ", " : "") + near[i];
  if (names.size() > count) s += "; " + std::to_string(names.size()) + " in all";
  return s;
}

}  // namespace evas
