#include "laguerre/scenarios/generators/UniformThreeConnected.hpp"

#include "laguerre/core/Error.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "detail/Closure.hpp"

namespace laguerre::scenarios {

using core::Dart;
using core::PlanarGraph;
using core::Vertex;

namespace {

constexpr std::size_t max_attempts = 1000000;

/// A binary tree with its leaves as stems: every node has three items in counter-clockwise order
/// (item 0 towards the parent, or the root stem), each a neighbour node or detail::stem; and a proper
/// 2-colouring (0 = black, the root's colour).
struct BinaryTree {
  std::vector<std::array<Vertex, 3>> items;
  std::vector<std::uint8_t> colour;

  Vertex add_node(Vertex parent, std::uint8_t c) {
    items.push_back({parent, detail::stem, detail::stem});
    colour.push_back(c);
    return static_cast<Vertex>(items.size() - 1);
  }

  detail::Blossoming blossoming() const {
    const std::size_t n = items.size();
    detail::Blossoming tree;
    tree.reserve(n + 6, 4 * n + 8);
    std::vector<std::uint32_t> slot(3 * n);
    for (Vertex v = 0; v < n; ++v) {
      tree.add_vertex();
      for (std::size_t j = 0; j < 3; ++j) slot[3 * v + j] = tree.append(v, items[v][j]);
    }
    for (Vertex v = 0; v < n; ++v)
      for (std::size_t j = 1; j < 3; ++j)
        if (items[v][j] != detail::stem) tree.set_twins(slot[3 * v + j], slot[3 * items[v][j]]);
    return tree;
  }
};

/// A uniformly random binary tree with `nodes` nodes rooted at a leaf (Łukasiewicz word with `nodes`
/// letters +1 and nodes + 1 letters −1, its unique good rotation, decoded in preorder).
BinaryTree random_binary_tree(std::size_t nodes, core::SeededRandom& random) {
  const std::vector<std::uint8_t> word = random.binary_word(2 * nodes + 1, nodes);
  std::vector<int> steps(word.size());
  for (std::size_t i = 0; i < word.size(); ++i) steps[i] = word[i] ? 1 : -1;
  const std::size_t start = detail::cycle_lemma_starts(steps, 1)[0];
  BinaryTree tree;
  tree.items.reserve(nodes);
  tree.colour.reserve(nodes);
  std::size_t read = 0;
  const auto letter = [&]() { return word[(start + read++) % word.size()]; };
  if (!letter()) throw std::logic_error("random_binary_tree: the code does not start with a node.");
  tree.add_node(detail::stem, 0);
  std::vector<std::pair<Vertex, std::size_t>> pending{{0, 2}, {0, 1}};
  while (!pending.empty()) {
    const auto [v, j] = pending.back();
    pending.pop_back();
    if (!letter()) continue;
    const Vertex c = tree.add_node(v, static_cast<std::uint8_t>(tree.colour[v] ^ 1));
    tree.items[v][j] = c;
    pending.push_back({c, 2});
    pending.push_back({c, 1});
  }
  if (read != word.size() || tree.items.size() != nodes)
    throw std::logic_error("random_binary_tree: the code is inconsistent.");
  return tree;
}

/// A uniformly random binary tree rooted at a leaf of a black node, with `black` black and `white`
/// white nodes, adjacent nodes having different colours. Two-type cycle lemma: black node i picks its
/// white children among its 2 slots (a uniform word of 2·black bits with `white` ones), each white node
/// its black children (a uniform word of 2·white bits with black − 1 ones, read in order of the white
/// nodes' creation); "block" i is black node i's bits followed by its white children's bits. The number
/// of black grandchildren of each block gives a Łukasiewicz walk of total −1 over the blocks, whose
/// unique good rotation (rotating both words consistently) is decoded in depth-first order of black
/// nodes. The trees are counted by binomial(2a, b)·binomial(2b, a − 1)/a (a = black, b = white).
BinaryTree random_bicoloured_tree(std::size_t black, std::size_t white, core::SeededRandom& random) {
  const std::vector<std::uint8_t> a_bits = random.binary_word(2 * black, white);
  const std::vector<std::uint8_t> w_bits = random.binary_word(2 * white, black - 1);
  std::vector<std::size_t> w_offset(black);
  std::vector<int> steps(black);
  std::size_t offset = 0;
  for (std::size_t i = 0; i < black; ++i) {
    w_offset[i] = offset;
    const std::size_t children = std::size_t{a_bits[2 * i]} + a_bits[2 * i + 1];
    int grandchildren = 0;
    for (std::size_t j = 0; j < 2 * children; ++j) grandchildren += w_bits[offset + j];
    offset += 2 * children;
    steps[i] = grandchildren - 1;
  }
  const std::size_t start = detail::cycle_lemma_starts(steps, 1)[0];
  BinaryTree tree;
  tree.items.reserve(black + white);
  tree.colour.reserve(black + white);
  std::size_t ia = start, iw = start < black ? w_offset[start] : 0, blocks = 0;
  std::vector<std::pair<Vertex, std::size_t>> pending;
  const auto block = [&](Vertex v) {
    std::array<Vertex, 2> whites{detail::stem, detail::stem};
    for (std::size_t j = 0; j < 2; ++j)
      if (a_bits[2 * ia + j]) {
        whites[j] = tree.add_node(v, 1);
        tree.items[v][j + 1] = whites[j];
      }
    ia = ia + 1 == black ? 0 : ia + 1;
    ++blocks;
    const std::size_t before = pending.size();
    for (Vertex w : whites) {
      if (w == detail::stem) continue;
      for (std::size_t k = 0; k < 2; ++k) {
        if (w_bits[iw]) pending.push_back({w, k + 1});
        iw = iw + 1 == w_bits.size() ? 0 : iw + 1;
      }
    }
    std::reverse(pending.begin() + static_cast<std::ptrdiff_t>(before), pending.end());
  };
  block(tree.add_node(detail::stem, 0));
  while (!pending.empty()) {
    const auto [w, k] = pending.back();
    pending.pop_back();
    const Vertex c = tree.add_node(w, 0);
    tree.items[w][k] = c;
    block(c);
  }
  if (blocks != black || tree.items.size() != black + white)
    throw std::logic_error("random_bicoloured_tree: the code is inconsistent.");
  return tree;
}

/// Closes a binary tree into a dissection of the hexagon, roots its quadrangulation at hexagon vertex
/// `s` (the black end of the root edge s – s+3), and returns the 3-connected map, or an empty graph if
/// the dissection is not admissible for that root. `root_choice` picks s among the hexagon vertices of
/// the requested colour (`black_colour` ≥ 0: among the three of that tree colour, root_choice < 3) or
/// among all six (black_colour < 0, root_choice < 6; the black colour is then s's).
PlanarGraph close_and_convert(const BinaryTree& tree, int black_colour, std::size_t root_choice) {
  const std::size_t n = tree.items.size();
  detail::Blossoming blossoming = tree.blossoming();
  std::vector<std::vector<Vertex>> rotation = blossoming.close(4, 6);
  // Colours: hexagon vertex j is opposite to the colour of its stems (vertex n has at least one).
  std::vector<std::uint8_t> colour(tree.colour);
  const std::uint8_t hex0 = static_cast<std::uint8_t>(colour[rotation[n].front()] ^ 1);
  for (std::size_t j = 0; j < 6; ++j) colour.push_back(static_cast<std::uint8_t>(hex0 ^ (j & 1)));
  std::size_t s_index;
  if (black_colour >= 0) {
    const std::size_t first = colour[n] == black_colour ? 0 : 1;
    s_index = first + 2 * root_choice;
  } else {
    s_index = root_choice;
  }
  const std::uint8_t black = colour[n + s_index];
  const Vertex s = static_cast<Vertex>(n + s_index), t = static_cast<Vertex>(n + (s_index + 3) % 6);

  // Admissible iff the only paths of length 3 from s to t are the two halves of the hexagon.
  {
    std::vector<std::uint8_t> near_t(n + 6, 0);
    for (Vertex q : rotation[t]) near_t[q] = 1;
    std::size_t paths = 0;
    for (Vertex p : rotation[s])
      for (Vertex q : rotation[p])
        if (q != s && near_t[q]) ++paths;
    if (paths != 2) return {};
  }
  // The quadrangulation: add the edge s–t inside the hexagon, between j+1 and j−1 in both rotations.
  rotation[s].insert(rotation[s].end() - 1, t);
  rotation[t].insert(rotation[t].end() - 1, s);
  const PlanarGraph q = PlanarGraph::from_rotation(std::move(rotation));
  for (core::Face f = 0; f < q.num_faces(); ++f)
    if (q.face_size(f) != 4) throw std::logic_error("uniform_three_connected: the closure is not a quadrangulation.");

  // The map: black vertices, one edge per quadrangle (its two black corners). Around a black vertex
  // the faces come in counter-clockwise order, so do their opposite corners.
  std::vector<Vertex> index(q.num_vertices(), core::none);
  Vertex count = 0;
  for (Vertex v = 0; v < q.num_vertices(); ++v)
    if (colour[v] == black) index[v] = count++;
  std::vector<std::vector<Vertex>> map_rotation(count);
  for (Vertex v = 0; v < q.num_vertices(); ++v) {
    if (colour[v] != black) continue;
    auto& rot = map_rotation[index[v]];
    for (Dart d = q.first_dart(v); d < q.first_dart(v) + q.degree(v); ++d)
      rot.push_back(index[q.head(q.next_in_face(d))]);
  }
  // Root face: the face of the white vertex t; its consecutive black neighbours b1, b2 (counter-clockwise
  // around t) bound it, and it lies to the left of b1 -> b2.
  const Vertex b1 = index[q.head(q.first_dart(t))], b2 = index[q.head(q.next_ccw(q.first_dart(t)))];
  std::size_t outer = 0;
  for (Vertex v = 0; v < b1; ++v) outer += map_rotation[v].size();
  const auto& rot1 = map_rotation[b1];
  outer += static_cast<std::size_t>(std::find(rot1.begin(), rot1.end(), b2) - rot1.begin());
  PlanarGraph map = PlanarGraph::from_rotation(std::move(map_rotation), {}, static_cast<Dart>(outer));
  if (map.face_size(map.outer_face()) != q.degree(t))
    throw std::logic_error("uniform_three_connected: the root face does not match the root's white vertex.");
  return map;
}

/// Weights of the face counts: w(b) ∝ binomial(2a, b)·binomial(2b, a − 1)/(2a − b + 1) for
/// b in [lo, hi], from the exact ratios of consecutive weights (decreasing in b, so w is unimodal),
/// normalised to 1 at the mode.
std::vector<double> face_weights(std::size_t a, std::size_t lo, std::size_t hi) {
  const auto ratio = [a](std::size_t b) {  // w(b + 1) / w(b)
    const double A = static_cast<double>(a), B = static_cast<double>(b);
    return 2.0 * (2 * A - B + 1) * (2 * B + 1) / ((2 * B + 3 - A) * (2 * B + 2 - A));
  };
  std::size_t mode = lo;
  while (mode < hi && ratio(mode) >= 1.0) ++mode;
  std::vector<double> w(hi - lo + 1, 0.0);
  w[mode - lo] = 1.0;
  for (std::size_t b = mode; b > lo; --b) w[b - 1 - lo] = w[b - lo] / ratio(b - 1);
  for (std::size_t b = mode; b < hi; ++b) w[b + 1 - lo] = w[b - lo] * ratio(b);
  return w;
}

std::runtime_error too_many_attempts(const std::string& what) {
  return std::runtime_error("No admissible dissection was drawn in " + std::to_string(max_attempts) + " attempts for " +
                            what +
                            "; face counts near the extremes (n + 4)/2 and 2n - 4 have acceptance rates of "
                            "order 1/n^2.");
}

}  // namespace

PlanarGraph uniform_three_connected(std::size_t n, std::uint64_t seed, std::size_t faces, ThreeConnectedStats* stats) {
  LAGUERRE_PRECONDITION(n >= 4 && n < (std::size_t{1} << 28),
                        "A uniform random 3-connected planar graph needs between 4 and 2^28 - 1 vertices, not " +
                            std::to_string(n) + ".");
  const std::size_t lo_faces = (n + 5) / 2, hi_faces = 2 * n - 4;  // n <= 2f - 4 and f <= 2n - 4
  LAGUERRE_PRECONDITION(faces == 0 || (faces >= lo_faces && faces <= hi_faces),
                        "A 3-connected planar graph with " + std::to_string(n) + " vertices has between " +
                            std::to_string(lo_faces) + " and " + std::to_string(hi_faces) + " faces, not " +
                            std::to_string(faces) + " (0 draws the number of faces).");
  core::SeededRandom random(seed);
  const std::size_t a = n - 3;
  std::vector<double> weights;
  double total = 0;
  if (faces == 0) {
    weights = face_weights(a, lo_faces - 3, hi_faces - 3);
    for (double w : weights) total += w;
  }
  for (std::size_t attempt = 1; attempt <= max_attempts; ++attempt) {
    std::size_t b = faces - 3;
    if (faces == 0) {
      double u = random.uniform01() * total;
      std::size_t i = 0;
      while (i + 1 < weights.size() && u >= weights[i]) u -= weights[i++];
      b = lo_faces - 3 + i;
    }
    const BinaryTree tree = random_bicoloured_tree(a, b, random);
    PlanarGraph map = close_and_convert(tree, 0, static_cast<std::size_t>(random.below(3)));
    if (map.num_vertices() == 0) continue;
    if (stats) *stats = {attempt, map.num_faces()};
    return map;
  }
  throw too_many_attempts(std::to_string(n) + " vertices and " +
                          (faces ? std::to_string(faces) : std::string("any number of")) + " faces");
}

PlanarGraph uniform_three_connected_map_by_edges(std::size_t edges, std::uint64_t seed, ThreeConnectedStats* stats) {
  LAGUERRE_PRECONDITION(edges >= 6 && edges != 7 && edges < (std::size_t{1} << 29),
                        "A uniform random 3-connected planar map needs 6 or at least 8 edges (and fewer than 2^29), "
                        "not " + std::to_string(edges) + ".");
  core::SeededRandom random(seed);
  for (std::size_t attempt = 1; attempt <= max_attempts; ++attempt) {
    const BinaryTree tree = random_binary_tree(edges - 4, random);
    PlanarGraph map = close_and_convert(tree, -1, static_cast<std::size_t>(random.below(6)));
    if (map.num_vertices() == 0) continue;
    if (stats) *stats = {attempt, map.num_faces()};
    return map;
  }
  throw too_many_attempts(std::to_string(edges) + " edges");
}

}  // namespace laguerre::scenarios
