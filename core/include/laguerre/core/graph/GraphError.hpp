#pragma once
/// @file
/// The typed exception for bad graph input (files, strings, generator arguments that describe a graph).

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

namespace laguerre::core {

/// Bad graph input: a malformed file, an unsupported graph, or a graph of the wrong kind.
///
/// `what()` is a full sentence prefixed by where the problem is:
///  - `"<source>:<line>: <message>"` when a line is known (text formats),
///  - `"<source>#<graph>: <message>"` when a graph of a multi-graph file is known (planar_code),
///  - `"<source>: <message>"` otherwise.
/// For example `graph.txt:12: expected two non-negative integer vertex ids, found 'a b'.`
class GraphInputError : public std::runtime_error {
public:
  /// Builds the error; `line` and `graph_index` are 0 when not applicable (graph indices count from 1).
  GraphInputError(std::string source, std::size_t line, std::size_t graph_index, std::string message)
      : std::runtime_error(compose(source, line, graph_index, message)),
        source_(std::move(source)),
        message_(std::move(message)),
        line_(line),
        graph_index_(graph_index) {}

  /// File name, or "<input>" for in-memory input.
  const std::string& source() const noexcept { return source_; }
  /// One-based line number of the offending text, or 0 if not applicable.
  std::size_t line() const noexcept { return line_; }
  /// One-based index of the offending graph in a multi-graph file, or 0 if not applicable.
  std::size_t graph_index() const noexcept { return graph_index_; }
  /// The message without the location prefix.
  const std::string& message() const noexcept { return message_; }

private:
  static std::string compose(const std::string& source, std::size_t line, std::size_t graph_index,
                             const std::string& message) {
    std::string where = source;
    if (line > 0) where += ":" + std::to_string(line);
    if (graph_index > 0) where += "#" + std::to_string(graph_index);
    return where + ": " + message;
  }

  std::string source_;
  std::string message_;
  std::size_t line_ = 0;
  std::size_t graph_index_ = 0;
};

}  // namespace laguerre::core
