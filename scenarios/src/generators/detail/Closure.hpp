#pragma once
/// @file
/// Internals shared by the uniform samplers: platform-independent random draws, the cycle lemma, and
/// the closure of blossoming trees (plane trees carrying stems) into maps with a fixed face degree.
///
/// Closure (Poulalhon–Schaeffer 2006 for triangulations, Fusy–Poulalhon–Schaeffer 2008 for
/// dissections). Walk around the tree with the tree on the right; write `a` for a stem and `b` for an
/// edge side. With face degree k (3 for triangles, 4 for quadrangles), every stem followed by k−1 sides
/// is closed: the stem becomes an edge to the vertex reached after those sides, creating a face of
/// degree k, and the factor a b…b is replaced by one side (the outer side of the new edge). Giving `a`
/// the weight k−2 and `b` the weight −1, a stem is closed at the first
/// point where the walk from it goes one below its starting level, so the result does not depend on the
/// order of the closures and one linear pass with a stack does them all, provided the pass starts right
/// after a minimum of the cyclic walk (no closure then wraps around). The "complete closure" then puts
/// the remaining stems on `outer_count` new vertices around the outside (2 for triangulations, whose
/// last two faces share the edge between the two new vertices; 6 for dissections of the hexagon).

#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "laguerre/core/graph/PlanarGraph.hpp"
#include "laguerre/core/random/Random.hpp"

namespace laguerre::scenarios::detail {

using core::Vertex;

/// Cycle lemma. `steps` are the integer steps (each ≥ −1) of a cyclic walk of total −k (k ≥ 1). Returns
/// the k starting positions p (0 ≤ p < size) from which the walk, read cyclically, first reaches −k at
/// its very end; they are the first visits of the levels M, …, M+k−1 of the prefix walk (M its minimum).
std::vector<std::size_t> cycle_lemma_starts(const std::vector<int>& steps, int k);

/// Marker for a stem (a dangling half-edge) in a blossoming tree.
inline constexpr Vertex stem = core::none;

/// A plane map under construction: per vertex a cyclic counter-clockwise list of slots (half-edges),
/// each pointing to a neighbour or being a stem, with O(1) insertion (an arena of linked lists).
class Blossoming {
 public:
  /// Adds a vertex with no slots and returns it.
  Vertex add_vertex();
  /// Number of vertices.
  std::size_t num_vertices() const { return first_.size(); }
  /// Appends a stem at the end of v's counter-clockwise list.
  void add_stem(Vertex v) { append(v, stem); }
  /// Appends an edge u–v at the end of both counter-clockwise lists.
  void add_edge(Vertex u, Vertex v);
  /// Reserves room for `vertices` vertices and `slots` slots.
  void reserve(std::size_t vertices, std::size_t slots);
  /// Appends a half-edge towards `neighbour` (or a stem) at the end of v's list; returns its slot.
  std::uint32_t append(Vertex v, Vertex neighbour);
  /// Makes two half-edges (slots) the two halves of one edge.
  void set_twins(std::uint32_t a, std::uint32_t b) {
    twin_[a] = b;
    twin_[b] = a;
  }

  /// Closes every stem it can (the partial closure) and then hangs the remaining stems on
  /// `outer_count` new vertices (the complete closure), for faces of degree `face_degree`.
  /// Returns the rotation system (counter-clockwise neighbour lists) of the closed map; the tree's
  /// vertices keep their indices and the outer vertices are num_vertices() … + outer_count − 1.
  /// For outer_count 2 the rotation of new vertex c is (its stems in order, the other new vertex), and
  /// `last_before_switch[c]` receives the last stem vertex on c, so that the dart c → it has the face
  /// (c, it, other) on its left. For outer_count 6 the rotation of hexagon vertex j is (its stems,
  /// j+1, j−1). Throws std::logic_error if the tree is not a valid blossoming tree for these parameters.
  std::vector<std::vector<Vertex>> close(unsigned face_degree, unsigned outer_count,
                                         std::vector<Vertex>* last_before_switch = nullptr);

 private:
  std::uint32_t insert_before(std::uint32_t slot, Vertex neighbour);
  std::uint32_t new_slot(Vertex owner, Vertex neighbour);

  std::vector<std::uint32_t> first_;  // per vertex, a slot or none
  std::vector<Vertex> owner_, neighbour_;
  std::vector<std::uint32_t> next_, prev_, twin_;  // next_ = counter-clockwise successor
};

}  // namespace laguerre::scenarios::detail
