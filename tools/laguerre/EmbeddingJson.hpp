#pragma once
/// @file
/// The embedding file written by `laguerre pack` and read by `laguerre route`: a self-contained JSON
/// document with the graph (rotation system, outer face), φ and the run's statistics.

#include <nlohmann/json.hpp>

#include <ostream>
#include <string>
#include <vector>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"

namespace laguerre::tools {

/// A graph with its circle embedding, as stored in an embedding file.
struct EmbeddedGraph {
  core::PlanarGraph graph;        ///< the graph with its outer face
  core::CircleEmbedding circles;  ///< φ per vertex
  std::string name;               ///< source name
};

/// Writes an embedding file: `doc` (the run's keys) plus the graph part — "outer_face" (the boundary
/// cycle's ids) and "vertices" (per vertex id, centre, radius, boundary flag, neighbours' ids
/// counter-clockwise, and `local[v]` as "local" when `local` is not empty) — exactly as
/// `nlohmann::json::dump(1)` prints the whole document (keys sorted, doubles in shortest round-trip
/// form), without building the vertices as JSON values: at 10^6 vertices those took about a gigabyte
/// and most of the writing time. Precondition: every key of `doc` sorts before "vertices".
void write_embedding_json(std::ostream& os, nlohmann::json doc, const core::PlanarGraph& g,
                          const core::CircleEmbedding& circles, const std::vector<std::string>& local = {});

/// Reads an embedding file; throws core::GraphInputError naming the file and the offending key.
EmbeddedGraph read_embedding(const std::string& path);

/// Whether `path` looks like an embedding file (JSON object with "format": "laguerre-embedding").
bool is_embedding_file(const std::string& path);

}  // namespace laguerre::tools
