// Line reading and tokenizing for the text graph formats, and the parts of the edges and coords
// formats they share (the `# outer:` directive, edge lines, repeated edges).
#include "Text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numeric>

#include "../detail/EmbeddingDetail.hpp"
#include "laguerre/core/graph/GraphError.hpp"

namespace laguerre::core::detail {

std::string_view trim(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_blanks(std::string_view s) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < s.size() && s[i] != ' ' && s[i] != '\t' && s[i] != '\r') ++i;
    if (i > start) tokens.push_back(s.substr(start, i - start));
  }
  return tokens;
}

bool parse_id(std::string_view token, std::uint64_t& out) {
  if (token.empty() || token.front() < '0' || token.front() > '9') return false;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  return ec == std::errc() && end == token.data() + token.size();
}

bool parse_coordinate(std::string_view token, double& out) {
  if (token.empty()) return false;
  if (token.front() == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  return ec == std::errc() && end == token.data() + token.size() && std::isfinite(out);
}

std::vector<TextLine> split_lines(std::string_view data) {
  std::vector<TextLine> lines;
  std::size_t number = 0, start = 0;
  while (start <= data.size()) {
    std::size_t end = data.find('\n', start);
    if (end == std::string_view::npos) end = data.size();
    std::string_view raw = data.substr(start, end - start);
    ++number;
    TextLine line;
    line.number = number;
    const std::size_t hash = raw.find('#');
    if (hash != std::string_view::npos) {
      line.has_comment = true;
      line.comment = trim(raw.substr(hash + 1));
      raw = raw.substr(0, hash);
    }
    line.content = trim(raw);
    lines.push_back(line);
    if (end == data.size()) break;
    start = end + 1;
  }
  return lines;
}

std::string quoted(std::string_view s) {
  constexpr std::size_t limit = 60;
  std::string out = "'";
  out += s.size() > limit ? std::string(s.substr(0, limit)) + "..." : std::string(s);
  return out + "'";
}

/// Parses a `# outer:` directive if `line` is one; returns whether it was.
bool parse_outer_directive(const TextLine& line, const std::string& source, TextGraph& out) {
  if (!line.has_comment || !line.content.empty()) return false;
  constexpr std::string_view key = "outer:";
  if (line.comment.substr(0, key.size()) != key) return false;
  if (out.outer_line != 0)
    throw GraphInputError(source, line.number, 0,
                          "a second '# outer:' directive was found (the first is on line " +
                              std::to_string(out.outer_line) + "); give the outer face once.");
  const auto tokens = split_blanks(line.comment.substr(key.size()));
  for (std::string_view t : tokens) {
    std::uint64_t id = 0;
    if (!parse_id(t, id))
      throw GraphInputError(source, line.number, 0,
                            "the '# outer:' directive expects non-negative integer vertex ids, found " + quoted(t) +
                                ".");
    out.outer.push_back(id);
  }
  if (out.outer.size() < 3)
    throw GraphInputError(source, line.number, 0,
                          "the '# outer:' directive must list a cycle of at least 3 vertices, found " +
                              std::to_string(out.outer.size()) + ".");
  auto sorted = out.outer;
  std::sort(sorted.begin(), sorted.end());
  const auto dup = std::adjacent_find(sorted.begin(), sorted.end());
  if (dup != sorted.end())
    throw GraphInputError(source, line.number, 0,
                          "the '# outer:' directive lists vertex " + std::to_string(*dup) +
                              " twice; the outer face must be a simple cycle.");
  out.outer_line = line.number;
  return true;
}

void add_edge_line(std::span<const std::string_view> tokens, const TextLine& line, const std::string& source,
                   TextGraph& out) {
  std::uint64_t a = 0, b = 0;
  if (tokens.size() != 2 || !parse_id(tokens[0], a) || !parse_id(tokens[1], b))
    throw GraphInputError(source, line.number, 0,
                          "expected two non-negative integer vertex ids, found " + quoted(line.content) + ".");
  if (a == b)
    throw GraphInputError(source, line.number, 0,
                          "edge " + edge_name(a, b) + " is a self-loop; the graph must be simple.");
  out.edges.emplace_back(a, b);
  out.edge_lines.push_back(line.number);
}

/// Rejects repeated edges (u v and v u are the same edge), naming both lines.
void check_duplicate_edges(const TextGraph& text, const std::string& source) {
  std::vector<std::size_t> order(text.edges.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto key = [&](std::size_t i) {
    auto [a, b] = text.edges[i];
    return std::pair{std::min(a, b), std::max(a, b)};
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return key(i) < key(j); });
  for (std::size_t k = 1; k < order.size(); ++k)
    if (key(order[k]) == key(order[k - 1])) {
      const std::size_t first = std::min(order[k], order[k - 1]), second = std::max(order[k], order[k - 1]);
      throw GraphInputError(source, text.edge_lines[second], 0,
                            "edge " + edge_name(text.edges[second].first, text.edges[second].second) +
                                " is listed twice (first on line " + std::to_string(text.edge_lines[first]) +
                                "); the graph must be simple.");
    }
}

}  // namespace laguerre::core::detail
