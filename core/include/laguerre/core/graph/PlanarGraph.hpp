#pragma once
/// @file
/// A connected planar graph with a rotation system (combinatorial embedding) and a chosen outer face.

#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace laguerre::core {

/// Internal vertex index, dense in [0, num_vertices()).
using Vertex = std::uint32_t;
/// Half-edge ("dart") index, dense in [0, num_darts()); the darts leaving v are contiguous.
using Dart = std::uint32_t;
/// Face index, dense in [0, num_faces()).
using Face = std::uint32_t;

/// Sentinel for "no vertex / dart / face".
inline constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();

/// A connected, simple planar graph stored as a rotation system.
///
/// Conventions (used throughout laguerre):
///  - `neighbours(v)` lists the neighbours of v in counter-clockwise order; the darts leaving v are
///    `first_dart(v) .. first_dart(v) + degree(v) - 1` in that same order.
///  - A dart d goes from `tail(d)` to `head(d)`; `twin(d)` goes back.
///  - Faces lie to the *left* of their darts: `next_in_face(u→v) = v→w` where w is the neighbour of v
///    just *before* u in v's counter-clockwise order. Inner faces are therefore traversed
///    counter-clockwise and the outer face clockwise in a planar drawing that respects the rotation.
///  - Vertices carry the user's ids (`id(v)`), which all outputs use.
class PlanarGraph {
public:
  PlanarGraph() = default;

  /// Builds a graph from `rotation[v]` = neighbours of v in counter-clockwise order.
  /// Throws InputError with a full sentence if the rotation is not symmetric, has loops or
  /// repeated neighbours, is disconnected, or does not define a planar embedding (Euler's formula).
  /// `ids` (defaults to 0..n-1) are the user's vertex ids; `outer` selects the outer face by one of its
  /// darts (defaults to `default_outer_dart()`).
  static PlanarGraph from_rotation(std::vector<std::vector<Vertex>> rotation,
                                   std::vector<std::uint64_t> ids = {}, Dart outer = none);

  /// Number of vertices.
  std::size_t num_vertices() const { return offset_.empty() ? 0 : offset_.size() - 1; }
  /// Number of darts (twice the number of edges).
  std::size_t num_darts() const { return head_.size(); }
  /// Number of undirected edges.
  std::size_t num_edges() const { return head_.size() / 2; }
  /// Number of faces, the outer face included.
  std::size_t num_faces() const { return face_offset_.empty() ? 0 : face_offset_.size() - 1; }

  /// Neighbours of v in counter-clockwise order.
  std::span<const Vertex> neighbours(Vertex v) const {
    return {head_.data() + offset_[v], offset_[v + 1] - offset_[v]};
  }
  /// Degree of v.
  std::uint32_t degree(Vertex v) const { return offset_[v + 1] - offset_[v]; }
  /// First dart leaving v (the one towards neighbours(v)[0]).
  Dart first_dart(Vertex v) const { return offset_[v]; }
  /// Head (target vertex) of dart d.
  Vertex head(Dart d) const { return head_[d]; }
  /// Tail (source vertex) of dart d.
  Vertex tail(Dart d) const { return tail_[d]; }
  /// The opposite dart of d.
  Dart twin(Dart d) const { return twin_[d]; }
  /// Next dart counter-clockwise around tail(d).
  Dart next_ccw(Dart d) const { return d + 1 == offset_[tail_[d] + 1] ? offset_[tail_[d]] : d + 1; }
  /// Next dart clockwise around tail(d).
  Dart next_cw(Dart d) const { return d == offset_[tail_[d]] ? offset_[tail_[d] + 1] - 1 : d - 1; }
  /// Next dart along the face to the left of d.
  Dart next_in_face(Dart d) const { return next_cw(twin_[d]); }
  /// The dart u→v, or `none` if u and v are not adjacent. Linear in deg(u).
  Dart find_dart(Vertex u, Vertex v) const;

  /// Face to the left of dart d.
  Face face_of(Dart d) const { return face_of_[d]; }
  /// Darts of face f in traversal order, starting at its canonical first dart.
  std::span<const Dart> face_darts(Face f) const {
    return {face_dart_.data() + face_offset_[f], face_offset_[f + 1] - face_offset_[f]};
  }
  /// Number of edges on the boundary walk of face f.
  std::uint32_t face_size(Face f) const { return face_offset_[f + 1] - face_offset_[f]; }

  /// The outer face.
  Face outer_face() const { return outer_; }
  /// Whether v lies on the outer face.
  bool is_boundary(Vertex v) const { return boundary_[v] != 0; }
  /// Outer-face vertices in boundary order (the order of the outer face's darts).
  std::vector<Vertex> boundary_cycle() const;
  /// Returns a copy whose outer face is the face to the left of dart d.
  PlanarGraph with_outer_dart(Dart d) const;
  /// Deterministic default outer dart: the dart of the edge with the lexicographically smallest
  /// (min id, max id) pair, oriented from the smaller id, whose left face is the outer face. For a
  /// triangulation of the sphere this picks one of the two triangles at that edge.
  Dart default_outer_dart() const;

  /// User id of vertex v.
  std::uint64_t id(Vertex v) const { return ids_[v]; }
  /// All user ids, indexed by vertex.
  const std::vector<std::uint64_t>& ids() const { return ids_; }
  /// Vertex with user id `id`, if any. Linear in the number of vertices (for tools and tests).
  std::optional<Vertex> vertex_of_id(std::uint64_t id) const;

  /// Whether every face other than the outer one is a triangle. Constant time (the graph counts its
  /// non-triangular faces once), so per-vertex code may ask it freely.
  bool inner_faces_are_triangles() const;
  /// Checks all internal invariants; with `verbose`, writes the first violation to std::cerr.
  bool is_valid(bool verbose = false) const;

private:
  void build_faces();

  std::vector<std::uint32_t> offset_;  // size n+1
  std::vector<Vertex> head_;           // size 2m
  std::vector<Vertex> tail_;           // size 2m
  std::vector<Dart> twin_;             // size 2m
  std::vector<Face> face_of_;          // size 2m
  std::vector<std::uint32_t> face_offset_;
  std::vector<Dart> face_dart_;
  std::vector<std::uint64_t> ids_;
  std::vector<std::uint8_t> boundary_;
  std::uint32_t non_triangles_ = 0;  // faces (outer included) whose size is not 3
  Face outer_ = none;
};

}  // namespace laguerre::core
