#include "laguerre/scenarios/generators/UniformTriangulation.hpp"

#include "laguerre/core/Error.hpp"
#include "laguerre/core/graph/GraphKind.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "detail/Closure.hpp"

namespace laguerre::scenarios {

using core::Vertex;

namespace {

/// Decodes a pair of quaternary trees (Łukasiewicz words, letters 1 = node with four children, 0 =
/// empty) read from `word` starting at `start`, into the stem-rooted plane tree with two stems per node.
/// A quaternary tree encodes a sequence of subtrees: node(q1, q2, q3, q4) is a tree node whose children
/// are q1's subtrees, a stem, q2's subtrees, a stem, q3's subtrees, followed by q4's sequence. The root
/// node carries the root stem, the first sequence, a stem, the second sequence.
detail::Blossoming decode_tree(const std::vector<std::uint8_t>& word, std::size_t start, std::size_t nodes) {
  detail::Blossoming tree;
  tree.reserve(nodes, 6 * nodes);
  std::vector<std::uint64_t> tasks;  // (v << 1) | 1 = append a stem to v; (v << 1) = parse a sequence of v
  const auto parse = [](Vertex v) { return std::uint64_t{v} << 1; };
  const auto stem = [](Vertex v) { return (std::uint64_t{v} << 1) | 1; };
  const Vertex root = tree.add_vertex();
  tree.add_stem(root);
  tasks.push_back(parse(root));
  tasks.push_back(stem(root));
  tasks.push_back(parse(root));
  const std::size_t length = word.size();
  std::size_t read = 0;
  while (!tasks.empty()) {
    const std::uint64_t task = tasks.back();
    tasks.pop_back();
    const auto p = static_cast<Vertex>(task >> 1);
    if (task & 1) {
      tree.add_stem(p);
      continue;
    }
    if (read == length) throw std::logic_error("uniform_triangulation: the tree code ended early.");
    if (!word[(start + read++) % length]) continue;
    const Vertex v = tree.add_vertex();
    tree.add_edge(p, v);
    for (std::uint64_t t : {parse(p), parse(v), stem(v), parse(v), stem(v), parse(v)}) tasks.push_back(t);
  }
  if (read != length || tree.num_vertices() != nodes)
    throw std::logic_error("uniform_triangulation: the tree code is inconsistent.");
  return tree;
}

}  // namespace

core::PlanarGraph uniform_triangulation(std::size_t n, std::uint64_t seed) {
  LAGUERRE_PRECONDITION(n >= 3 && n < (std::size_t{1} << 30),
                        "A uniform random triangulation needs between 3 and 2^30 - 1 vertices, not " +
                            std::to_string(n) + ".");
  const std::size_t m = n - 2;  // tree nodes
  core::SeededRandom random(seed);
  // Uniform word with m - 1 nodes (+3) and 3m - 1 empty trees (-1); its 2 good rotations are the codes
  // of two quaternary trees, i.e. of a stem-rooted tree.
  const std::vector<std::uint8_t> word = random.binary_word(4 * m - 2, m - 1);
  std::vector<int> steps(word.size());
  for (std::size_t i = 0; i < word.size(); ++i) steps[i] = word[i] ? 3 : -1;
  const std::vector<std::size_t> starts = detail::cycle_lemma_starts(steps, 2);
  detail::Blossoming tree = decode_tree(word, starts[random.below(2)], m);

  std::vector<Vertex> last;
  std::vector<std::vector<Vertex>> rotation = tree.close(3, 2, &last);
  // Root face: one of the two triangles (u, last[c], other new vertex), by a fair coin.
  const auto c = static_cast<std::size_t>(random.below(2));
  const Vertex u = static_cast<Vertex>(m + c);
  std::size_t offset = 0;
  for (Vertex v = 0; v < u; ++v) offset += rotation[v].size();
  const auto outer = static_cast<core::Dart>(offset + rotation[u].size() - 2);  // the dart u -> last[c]
  return core::PlanarGraph::from_rotation(std::move(rotation), {}, outer);
}

}  // namespace laguerre::scenarios

namespace laguerre::scenarios {

core::PlanarGraph puncture_at_max_degree(const core::PlanarGraph& g) {
  LAGUERRE_PRECONDITION(g.num_vertices() >= 4, "puncturing needs at least 4 vertices");
  return core::puncture(g, core::puncture_vertex(g));
}

core::PlanarGraph with_largest_outer_face(const core::PlanarGraph& g) {
  core::Face best = 0;
  for (core::Face f = 1; f < g.num_faces(); ++f)
    if (g.face_darts(f).size() > g.face_darts(best).size()) best = f;
  return g.with_outer_dart(g.face_darts(best)[0]);
}

}  // namespace laguerre::scenarios
