#include "estimate/geometry/point_selection.h"

#include <algorithm>
#include <tuple>

namespace hapcine {

std::vector<long> SelectWindowTracks(std::vector<TrackCandidate> candidates, int max_points, int grid_cells) {
  const size_t n = candidates.size();
  // Rank of each candidate within its cell (0 = longest); one cell without a grid.
  std::vector<int> rank(n, 0);
  std::vector<size_t> idx(n);
  for (size_t i = 0; i < n; ++i) idx[i] = i;
  auto longer = [&](size_t a, size_t b) {
    return std::make_tuple(-candidates[a].length, candidates[a].id) <
           std::make_tuple(-candidates[b].length, candidates[b].id);
  };
  std::sort(idx.begin(), idx.end(), longer);
  if (grid_cells > 1 && n > 0) {
    Eigen::Vector2d lo = candidates[0].u, hi = candidates[0].u;
    for (const auto& c : candidates) {
      lo = lo.cwiseMin(c.u);
      hi = hi.cwiseMax(c.u);
    }
    const Eigen::Vector2d size = (hi - lo).cwiseMax(Eigen::Vector2d::Constant(1e-12));
    std::vector<int> taken(static_cast<size_t>(grid_cells) * grid_cells, 0);
    for (size_t i : idx) {  // longest first, so ranks count down the lengths
      const Eigen::Vector2d t = (candidates[i].u - lo).cwiseQuotient(size) * grid_cells;
      const int cx = std::clamp(static_cast<int>(t.x()), 0, grid_cells - 1);
      const int cy = std::clamp(static_cast<int>(t.y()), 0, grid_cells - 1);
      rank[i] = taken[static_cast<size_t>(cy) * grid_cells + cx]++;
    }
    std::stable_sort(idx.begin(), idx.end(), [&](size_t a, size_t b) { return rank[a] < rank[b]; });
  }
  std::vector<long> ids;
  for (size_t k = 0; k < idx.size() && static_cast<int>(ids.size()) < max_points; ++k)
    ids.push_back(candidates[idx[k]].id);
  return ids;
}

}  // namespace hapcine
