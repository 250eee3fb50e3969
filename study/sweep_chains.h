// The warm-start chains of a periodic sweep (`evas study sweep --periodic`):
// a point's periodic search starts from the periodic state of the point
// before it in the grid's order (same case), which is closer to its own cycle
// than the scene's initial state, so the search needs fewer cycles. A chain
// runs one point after another; the grid is cut into as many chains as the
// runner runs tasks at once, so warm starts cost no parallelism.
#pragma once

#include <cstddef>
#include <vector>

namespace evas::study {

/// For tasks numbered point-major (task = point * cases + case): the task
/// whose periodic state starts each task, or -1 for a chain's first point
/// (the scene's initial state). The points of every case are cut into
/// min(points, ceil(width / cases)) contiguous chains of near-equal length;
/// width < 1 counts as 1.
std::vector<int> warm_predecessors(std::size_t points, std::size_t cases, int width);

/// The wave of every task: 0 for a chain's first, its predecessor's plus one
/// otherwise. The tasks of one wave run at once; wave w + 1 starts when wave
/// w has ended.
std::vector<int> chain_waves(const std::vector<int>& predecessor);

}  // namespace evas::study
