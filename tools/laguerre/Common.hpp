#pragma once
/// @file
/// Pieces shared by the subcommands: loading a graph ready for packing, output paths.

#include <string>

#include "laguerre/core/graph/GraphIO.hpp"
#include "laguerre/core/graph/GraphKind.hpp"

namespace laguerre::tools {

/// A graph read from a file and prepared for packing (kind decided, outer face chosen).
struct LoadedGraph {
  core::GraphInput input;  ///< graph, positions, name
  core::GraphKind kind{};  ///< triangulated disc or 3-connected
};

/// Reads graph number `index` (from 1) of `path` in `format` and prepares it for packing.
LoadedGraph load_graph(const std::string& path, const std::string& format, std::size_t index);

/// Refuses (std::invalid_argument, a full sentence naming --force) to overwrite `path` unless `force`.
void check_writable(const std::string& path, bool force);

/// "dir/name.ext" → "name".
std::string file_stem(const std::string& path);

}  // namespace laguerre::tools
