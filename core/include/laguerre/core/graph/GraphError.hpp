#pragma once
/// @file
/// The typed exception for bad graph input (files, strings, generator arguments that describe a graph).

#include <cstddef>
#include <string>
#include <utility>

#include "laguerre/core/Error.hpp"

namespace laguerre::core {

/// Bad graph input: a malformed file, an unsupported graph, or a graph of the wrong kind. An InputError
/// whose `source()` is the file name, or "<input>" for in-memory input.
///
/// `what()` is a full sentence prefixed by where the problem is:
///  - `"<source>:<line>: <message>"` when a line is known (text formats),
///  - `"<source>#<graph>: <message>"` when a graph of a multi-graph file is known (planar_code),
///  - `"<source>: <message>"` otherwise.
/// For example `graph.txt:12: expected two non-negative integer vertex ids, found 'a b'.`
class GraphInputError : public InputError {
public:
  /// Builds the error; `line` and `graph_index` are 0 when not applicable (graph indices count from 1).
  GraphInputError(std::string source, std::size_t line, std::size_t graph_index, std::string message)
      : InputError(compose(source, line, graph_index, message), source, line, message),  // copies: argument order is unspecified
        graph_index_(graph_index) {}

  /// One-based index of the offending graph in a multi-graph file, or 0 if not applicable.
  std::size_t graph_index() const noexcept { return graph_index_; }

private:
  static std::string compose(const std::string& source, std::size_t line, std::size_t graph_index,
                             const std::string& message) {
    std::string where = source;
    if (line > 0) where += ":" + std::to_string(line);
    if (graph_index > 0) where += "#" + std::to_string(graph_index);
    return where + ": " + message;
  }

  std::size_t graph_index_ = 0;
};

}  // namespace laguerre::core
