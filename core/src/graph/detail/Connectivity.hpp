#pragma once
// The one connectivity traversal of the graph code (PlanarGraph, the readers, the drawing check).
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace laguerre::core::detail {

/// The smallest vertex of [0, n) that vertex 0 does not reach, or n if the graph is connected (n ≥ 1).
/// `neighbours(v)` is any range of the neighbour indices of v. Depth-first; O(n + m).
template <class Neighbours>
std::size_t first_unreached(std::size_t n, Neighbours&& neighbours) {
  std::vector<std::uint8_t> seen(n, 0);
  std::vector<std::size_t> stack{0};
  seen[0] = 1;
  while (!stack.empty()) {
    const std::size_t v = stack.back();
    stack.pop_back();
    for (const auto w : neighbours(v))
      if (!seen[w]) {
        seen[w] = 1;
        stack.push_back(w);
      }
  }
  std::size_t v = 0;
  while (v < n && seen[v]) ++v;
  return v;
}

/// first_unreached on the graph with n vertices and these edges (pairs of indices below n).
template <class Index>
std::size_t first_unreached_by_edges(std::size_t n, const std::vector<std::pair<Index, Index>>& edges) {
  std::vector<std::vector<Index>> adjacency(n);
  for (auto [a, b] : edges) {
    adjacency[a].push_back(b);
    adjacency[b].push_back(a);
  }
  return first_unreached(n, [&](std::size_t v) -> const std::vector<Index>& { return adjacency[v]; });
}

}  // namespace laguerre::core::detail
