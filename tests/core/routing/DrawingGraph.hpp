#pragma once
// Test helper shared by the routing suites: a graph whose rotation is the exact counter-clockwise order
// of the neighbours around the circles' centres (a plane straight-line drawing when edges do not cross;
// unlike core::graph_from_drawing it accepts crossing drawings, which some tests need on purpose).

#include <algorithm>
#include <utility>
#include <vector>

#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"

namespace laguerre::core {

/// The graph on the circles' centres with the exact counter-clockwise rotation.
inline PlanarGraph graph_of(const CircleEmbedding& phi, const std::vector<std::pair<Vertex, Vertex>>& edges) {
  std::vector<std::vector<Vertex>> rot(phi.size());
  for (const auto& [a, b] : edges) {
    rot[a].push_back(b);
    rot[b].push_back(a);
  }
  for (Vertex v = 0; v < phi.size(); ++v) {
    const Point2 p = centre(phi[v]);
    auto half = [&](Vertex w) { return (phi[w].y > p.y || (phi[w].y == p.y && phi[w].x > p.x)) ? 0 : 1; };
    std::sort(rot[v].begin(), rot[v].end(), [&](Vertex a, Vertex b) {
      if (half(a) != half(b)) return half(a) < half(b);
      return orientation(p, centre(phi[a]), centre(phi[b])) == Sign::positive;
    });
  }
  return PlanarGraph::from_rotation(std::move(rot));
}

}  // namespace laguerre::core
