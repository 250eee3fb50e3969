// Warm-start chains of a periodic sweep (sweep_chains.h).
#include "study/sweep_chains.h"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace evas::study {

std::vector<int> warm_predecessors(std::size_t points, std::size_t cases, int width) {
  std::vector<int> pred(points * cases, -1);
  if (points == 0 || cases == 0) return pred;
  const std::size_t w = static_cast<std::size_t>(std::max(width, 1));
  const std::size_t chains = std::clamp<std::size_t>((w + cases - 1) / cases, 1, points);
  std::set<std::size_t> first;
  for (std::size_t j = 0; j < chains; ++j) first.insert(j * points / chains);
  for (std::size_t p = 0; p < points; ++p)
    if (!first.count(p))
      for (std::size_t c = 0; c < cases; ++c)
        pred[p * cases + c] = static_cast<int>((p - 1) * cases + c);
  return pred;
}

std::vector<int> chain_waves(const std::vector<int>& predecessor) {
  std::vector<int> wave(predecessor.size(), 0);
  for (std::size_t k = 0; k < predecessor.size(); ++k) {
    const int j = predecessor[k];
    if (j < 0) continue;
    if (static_cast<std::size_t>(j) >= k)
      throw std::logic_error("chain_waves: a predecessor must come before its task");
    wave[k] = wave[static_cast<std::size_t>(j)] + 1;
  }
  return wave;
}

}  // namespace evas::study
