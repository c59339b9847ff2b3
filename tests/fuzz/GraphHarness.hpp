#pragma once
/// @file
/// The harness of every graph format of core/graph/GraphIO.hpp: read, check each graph's invariants,
/// write it back in the same format (where there is a writer) and read that again.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "FuzzTarget.hpp"
#include "laguerre/core/Error.hpp"
#include "laguerre/core/graph/GraphIO.hpp"

namespace laguerre::fuzz {

/// The input in `format`, or "" when the format has no writer (coords).
inline std::string write_graph(const core::GraphInput& g, core::GraphFormat format) {
  switch (format) {
    case core::GraphFormat::edges: return core::write_edge_list(g.graph);
    case core::GraphFormat::planar_code: return core::write_planar_code({g.graph});
    case core::GraphFormat::graphml: return core::write_graphml(g.graph, g.positions);
    case core::GraphFormat::dot: return core::write_dot(g.graph, g.positions);
    default: return {};
  }
}

/// The user ids of g's boundary walk, rotated to start at the smallest.
inline std::vector<std::uint64_t> boundary_ids(const core::PlanarGraph& g) {
  std::vector<std::uint64_t> ids;
  for (core::Vertex v : g.boundary_cycle()) ids.push_back(g.id(v));
  std::rotate(ids.begin(), std::min_element(ids.begin(), ids.end()), ids.end());
  return ids;
}

/// Whether the boundary walk is a simple cycle of at least 3 vertices (the writers give such an outer
/// face of a drawing always, of a graph alone when it determines the embedding).
inline bool simple_boundary(const core::PlanarGraph& g) {
  std::vector<core::Vertex> cycle = g.boundary_cycle();
  std::sort(cycle.begin(), cycle.end());
  return cycle.size() >= 3 && std::adjacent_find(cycle.begin(), cycle.end()) == cycle.end();
}

inline std::vector<std::uint64_t> sorted_ids(const core::PlanarGraph& g) {
  std::vector<std::uint64_t> ids = g.ids();
  std::sort(ids.begin(), ids.end());
  return ids;
}

/// Reads `data` in `format`; on success checks every graph and its round trip through the writer.
inline int fuzz_graph_format(const std::uint8_t* data, std::size_t size, core::GraphFormat format) {
  std::vector<core::GraphInput> graphs;
  if (!parses<core::GraphInputError, core::InputError, std::invalid_argument>(
          [&] { graphs = core::read_graphs_from_string(as_text(data, size), "<fuzz>", format); }))
    return 0;
  for (const core::GraphInput& g : graphs) {
    LAGUERRE_FUZZ_CHECK(g.graph.is_valid(true));
    LAGUERRE_FUZZ_CHECK(g.positions.empty() || g.positions.size() == g.graph.num_vertices());
    const std::string written = write_graph(g, format);
    if (written.empty()) continue;
    std::vector<core::GraphInput> again;
    try {
      again = core::read_graphs_from_string(written, "<written>", format);
    } catch (const std::exception& e) {
      fail(std::string("the writer's output does not read back (") + e.what() + "):\n" + written);
    }
    LAGUERRE_FUZZ_CHECK(again.size() == 1);
    const core::PlanarGraph& h = again[0].graph;
    LAGUERRE_FUZZ_CHECK(h.num_vertices() == g.graph.num_vertices() && h.num_edges() == g.graph.num_edges() &&
                        h.num_faces() == g.graph.num_faces());
    if (format != core::GraphFormat::planar_code) LAGUERRE_FUZZ_CHECK(sorted_ids(h) == sorted_ids(g.graph));
    // An outer face that was written is read back (the edges reader gives one only when it was written).
    const bool outer_written = format != core::GraphFormat::planar_code &&
                               (g.positions.empty() ? again[0].outer_given : simple_boundary(g.graph));
    if (outer_written) LAGUERRE_FUZZ_CHECK(boundary_ids(h) == boundary_ids(g.graph));
    LAGUERRE_FUZZ_CHECK(std::equal(g.positions.begin(), g.positions.end(), again[0].positions.begin(),
                                   again[0].positions.end(),
                                   [](core::Point2 p, core::Point2 q) { return p.x == q.x && p.y == q.y; }));
  }
  return 0;
}

}  // namespace laguerre::fuzz
