#pragma once
// Line reading and tokenizing for the text graph formats (edges, coords, and the values inside GraphML
// and DOT), and the content of an edges or coords file before any graph is built.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "laguerre/core/geometry/Predicates.hpp"

namespace laguerre::core::detail {

/// `data` without a leading UTF-8 byte-order mark.
inline std::string_view without_bom(std::string_view data) {
  return data.starts_with("\xEF\xBB\xBF") ? data.substr(3) : data;
}

/// `s` without leading and trailing blanks (space, tab, CR, VT, FF).
std::string_view trim(std::string_view s);

/// The words of `s`, separated by spaces, tabs and CRs.
std::vector<std::string_view> split_blanks(std::string_view s);

/// Whether `token` is a non-negative decimal integer that fits in 64 bits; stores it in `out`.
bool parse_id(std::string_view token, std::uint64_t& out);

/// Whether `token` is a finite decimal number (an optional leading '+' allowed); stores it in `out`.
bool parse_coordinate(std::string_view token, double& out);

/// `s` in single quotes, cut after 60 characters.
std::string quoted(std::string_view s);

/// One line of a text input: its number, the content before any comment, and the comment.
struct TextLine {
  std::size_t number = 0;
  std::string_view content;
  std::string_view comment;  // text after '#', empty if none
  bool has_comment = false;
};

/// The lines of `data` (split at '\n'), numbered from 1, comments (from '#') split off, trimmed.
std::vector<TextLine> split_lines(std::string_view data);

/// The content of a text file in the edges or coords format, before any graph is built.
struct TextGraph {
  std::vector<std::uint64_t> vertex_ids;  // coords only, declaration order
  std::vector<Point2> positions;          // coords only
  std::vector<std::pair<std::uint64_t, std::uint64_t>> edges;
  std::vector<std::size_t> edge_lines;
  std::vector<std::uint64_t> outer;
  std::size_t outer_line = 0;
};

/// Parses a `# outer:` directive if `line` is one; returns whether it was.
bool parse_outer_directive(const TextLine& line, const std::string& source, TextGraph& out);

/// Adds the edge `u v` of an edge line (tokens), or throws naming the line.
void add_edge_line(std::span<const std::string_view> tokens, const TextLine& line, const std::string& source,
                   TextGraph& out);

/// Rejects repeated edges (u v and v u are the same edge), naming both lines.
void check_duplicate_edges(const TextGraph& text, const std::string& source);

}  // namespace laguerre::core::detail
