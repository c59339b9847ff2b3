#pragma once
/// @file
/// The embedding file written by `laguerre pack` and read by `laguerre route`: a self-contained JSON
/// document with the graph (rotation system, outer face), φ and the run's statistics.

#include <nlohmann/json.hpp>

#include <string>

#include "laguerre/core/geometry/Circle.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"

namespace laguerre::tools {

/// A graph with its circle embedding, as stored in an embedding file.
struct EmbeddedGraph {
  core::PlanarGraph graph;        ///< the graph with its outer face
  core::CircleEmbedding circles;  ///< φ per vertex
  std::string name;               ///< source name
};

/// Serializes the graph part of an embedding file: per vertex id, centre, radius, boundary flag and
/// neighbours (ids, counter-clockwise); doubles are written with 17 significant digits (exact round trip).
nlohmann::json embedding_to_json(const core::PlanarGraph& g, const core::CircleEmbedding& circles);

/// Reads an embedding file; throws core::GraphInputError naming the file and the offending key.
EmbeddedGraph read_embedding(const std::string& path);

/// Whether `path` looks like an embedding file (JSON object with "format": "laguerre-embedding").
bool is_embedding_file(const std::string& path);

}  // namespace laguerre::tools
