#pragma once
/// @file
/// A graph with its embedding, as readers and generators hand it out, and embedding a straight-line
/// drawing.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "laguerre/core/geometry/Predicates.hpp"
#include "laguerre/core/graph/GraphError.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"

namespace laguerre::core {

/// One graph read from an input or generated.
struct GraphInput {
  PlanarGraph graph;             ///< the embedded graph, with its outer face
  std::vector<Point2> positions; ///< vertex positions indexed by Vertex; empty unless the input had them
  std::string name;              ///< e.g. "file.txt" or "file.pc#3"
  bool outer_given = false;      ///< whether the input chose the outer face (rather than the default rule)
};

/// Builds a graph from a straight-line drawing: vertex i has user id ids[i] and position positions[i];
/// edges are pairs of vertex indices. The rotation is the exact counter-clockwise order around each
/// position; the outer face is the unbounded one (`outer_given` is true). Throws GraphInputError (with
/// `source` and no line) if the drawing is not a plane drawing of a simple connected graph. The crossing
/// test buckets the edges' bounding boxes in a uniform grid of about one cell per edge and tests each
/// pair of edges whose boxes overlap once, exactly: O(m) for edges of comparable lengths (random
/// drawings); when boxes of very different sizes would list edges in more than 16m cells it sweeps the
/// boxes in x order instead (O(m²) in the worst case). A crossing is named as the x-order sweep finds it
/// first. With `check_crossings` false it is skipped (for drawings known to be plane, e.g. Delaunay
/// triangulations).
/// Preconditions (LAGUERRE_PRECONDITION): one position per id, edge indices below ids.size().
GraphInput graph_from_drawing(std::vector<std::uint64_t> ids, std::vector<Point2> positions,
                              const std::vector<std::pair<Vertex, Vertex>>& edges, const std::string& source,
                              bool check_crossings = true);

}  // namespace laguerre::core
