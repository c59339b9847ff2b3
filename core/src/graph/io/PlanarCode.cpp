// plantri's planar_code: reading (narrow and wide entries, either byte order) and writing.
#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "../detail/EmbeddingDetail.hpp"
#include "Formats.hpp"
#include "laguerre/core/graph/GraphIO.hpp"

namespace laguerre::core {

std::vector<GraphInput> detail::read_planar_code(std::string_view data, const std::string& source) {
  bool big_endian = false;
  std::size_t pos = 0;
  if (data.substr(0, planar_code_magic.size()) == planar_code_magic) {
    for (std::string_view header : {">>planar_code<<", ">>planar_code le<<", ">>planar_code be<<"})
      if (data.substr(0, header.size()) == header) {
        pos = header.size();
        big_endian = header == ">>planar_code be<<";
      }
    if (pos == 0)
      throw GraphInputError(source, 0, 0,
                            "the planar_code header is not one of '>>planar_code<<', '>>planar_code le<<' and "
                            "'>>planar_code be<<'.");
  } else if (!data.empty() && data.find('\0') == std::string_view::npos) {
    // Every planar_code graph holds 0 bytes (list terminators); text never does.
    throw GraphInputError(source, 0, 0,
                          "expected a planar_code file (header '>>planar_code<<'), found " +
                              quoted(trim(data.substr(0, data.find('\n')))) +
                              " (no header, and none of the 0 bytes that end every vertex's neighbour list).");
  }
  std::vector<GraphInput> graphs;
  std::size_t index = 0;
  while (pos < data.size()) {
    ++index;
    const std::string name = source + "#" + std::to_string(index);
    bool wide = false;
    std::size_t n = 0, done = 0;
    auto truncated = [&]() {
      std::string where = n == 0 ? "while reading its number of vertices"
                                 : "after the neighbours of " + std::to_string(done) + " of its " +
                                       std::to_string(n) + " vertices";
      return GraphInputError(source, 0, index,
                             "the planar_code data ends in the middle of graph " + std::to_string(index) + " (" +
                                 where + ").");
    };
    auto byte_at = [&](std::size_t i) { return static_cast<unsigned>(static_cast<unsigned char>(data[i])); };
    auto read_entry = [&]() -> std::size_t {
      if (!wide) {
        if (pos >= data.size()) throw truncated();
        return byte_at(pos++);
      }
      if (pos + 2 > data.size()) throw truncated();
      const unsigned lo = byte_at(big_endian ? pos + 1 : pos), hi = byte_at(big_endian ? pos : pos + 1);
      pos += 2;
      return lo | (hi << 8);
    };
    n = read_entry();
    if (n == 0) {
      wide = true;
      n = read_entry();
      if (n == 0)
        throw GraphInputError(source, 0, index, "graph " + std::to_string(index) + " has no vertices.");
    }
    std::vector<std::vector<Vertex>> rotation(n);
    for (std::size_t v = 0; v < n; ++v) {
      auto& list = rotation[v];
      const std::size_t vertex = v + 1;  // plantri's number of the vertex being read
      for (;;) {
        const std::size_t w = read_entry();
        if (w == 0) break;
        if (w > n)
          throw GraphInputError(source, 0, index,
                                "vertex " + std::to_string(vertex) + " lists neighbour " + std::to_string(w) +
                                    ", outside 1.." + std::to_string(n) + ".");
        if (w == vertex)
          throw GraphInputError(source, 0, index,
                                "vertex " + std::to_string(vertex) + " lists itself as a neighbour; the graph must be simple.");
        list.push_back(static_cast<Vertex>(w - 1));
      }
      std::reverse(list.begin(), list.end());  // plantri lists clockwise, we store counter-clockwise
      done = vertex;
    }
    // Symmetry and simplicity, with messages in plantri's numbering.
    std::vector<std::pair<Vertex, Vertex>> darts;
    for (Vertex v = 0; v < n; ++v)
      for (Vertex w : rotation[v]) darts.emplace_back(v, w);
    std::sort(darts.begin(), darts.end());
    for (std::size_t k = 0; k < darts.size(); ++k) {
      const auto [v, w] = darts[k];
      if (k > 0 && darts[k - 1] == darts[k])
        throw GraphInputError(source, 0, index,
                              "vertex " + std::to_string(v + 1) + " lists neighbour " + std::to_string(w + 1) +
                                  " twice; the graph must be simple.");
      if (!std::binary_search(darts.begin(), darts.end(), std::pair{w, v}))
        throw GraphInputError(source, 0, index,
                              "the planar_code is inconsistent: vertex " + std::to_string(v + 1) + " lists " +
                                  std::to_string(w + 1) + " as a neighbour but vertex " + std::to_string(w + 1) +
                                  " does not list " + std::to_string(v + 1) + ".");
    }
    std::vector<std::uint64_t> ids(n);
    std::iota(ids.begin(), ids.end(), std::uint64_t{1});
    GraphInput input;
    input.graph = build_graph(std::move(rotation), std::move(ids), source, index);
    input.name = name;
    graphs.push_back(std::move(input));
  }
  return graphs;
}

std::string write_planar_code(const std::vector<PlanarGraph>& graphs) {
  std::string out = ">>planar_code le<<";
  for (const PlanarGraph& g : graphs) {
    const std::size_t n = g.num_vertices();
    if (n == 0 || n > 65535)
      throw GraphInputError("planar_code output", 0, 0,
                            "a graph has " + std::to_string(n) + " vertices; planar_code stores 1 to 65535.");
    const bool wide = n > 255;
    auto put = [&](std::size_t value) {
      out.push_back(static_cast<char>(value & 0xff));
      if (wide) out.push_back(static_cast<char>(value >> 8));
    };
    if (wide) out.push_back('\0');
    put(n);
    for (Vertex v = 0; v < n; ++v) {
      const auto list = g.neighbours(v);
      for (auto it = list.rbegin(); it != list.rend(); ++it) put(*it + 1);  // clockwise
      put(0);
    }
  }
  return out;
}

}  // namespace laguerre::core
