#pragma once
/// @file
/// The node-local steps of the layout wave (thesis §5.3.1 step 3): where a vertex goes, given the
/// placed neighbours it is placed from. `lay_out` (Layout.hpp) is these functions applied in waves; a
/// distributed node calls the same functions on what its neighbours told it, so both compute the same
/// bits. The functions are compiled in one translation unit (Layout.cpp) with one set of
/// floating-point options, which is what makes that true: never re-implement them inline.

#include <complex>
#include <cstdint>

#include "laguerre/core/geometry/Circle.hpp"

namespace laguerre::core {

/// A vertex as the layout sees it: its hyperbolic radius and whether it is interior.
struct LayoutVertex {
  double h = 0;          ///< hyperbolic radius (∞ for a boundary vertex: a horocycle)
  bool interior = false; ///< interior vertex (a hyperbolic circle) or boundary vertex (a horocycle)
};

/// Where a placed vertex is.
struct PlacedCircle {
  std::complex<double> centre;  ///< hyperbolic centre (interior vertex) or ideal point (boundary vertex)
  Circle circle;                ///< the Euclidean circle in the Poincaré disc
};

/// The intersection cosines of the three edges of a face (w, a, b): 1 for tangency, 0 for orthogonal.
struct FaceCosines {
  double wa = 1;  ///< edge w–a
  double wb = 1;  ///< edge w–b
  double ab = 1;  ///< edge a–b
  /// Whether triangle angles use the general overlap formula (true whenever the complex has face
  /// vertices, for every triangle of it) or the tangency formula (triangulated discs).
  bool overlap = false;
};

/// The root's circle: centred at the origin. Requires an interior root (h ∈ (0, ∞)).
PlacedCircle place_root(double h_root);

/// The root's first neighbour w, on the positive real axis, with edge cosine `cos_root_w`
/// (1 unless the complex has face vertices).
PlacedCircle place_first_neighbour(double h_root, LayoutVertex w, double cos_root_w);

/// Places w in the inner face (w, a, b) (counter-clockwise) from the placed a and b: rotates about a
/// when a is interior, else about b when b is interior, else (two horocycles) by the Möbius map that
/// matches a's and b's ideal points and tangency point.
PlacedCircle place_in_face(LayoutVertex w, LayoutVertex a, const PlacedCircle& pa, LayoutVertex b,
                           const PlacedCircle& pb, const FaceCosines& cosines);

/// Which of the two anchors of `place_in_face` becomes w's parent in the layout's spanning tree:
/// a if a is interior or b is not (true), otherwise b (false).
inline bool parent_is_first_anchor(bool a_interior, bool b_interior) { return a_interior || !b_interior; }

/// The wave's pair rule, shared by `lay_out` and the distributed node: among the wedges
/// (neighbour i, neighbour i+1), i = 0 … degree−1 in counter-clockwise order, that are inner faces
/// (`inner(i)`) and whose two neighbours are both placed (`placed(j)`, positions from earlier rounds
/// only), the first one containing an interior vertex (`interior(j)`), else the first one. Returns its
/// index i, or `degree` if there is none (the vertex cannot be placed this round).
template <class Inner, class Placed, class Interior>
std::uint32_t choose_placement_wedge(std::uint32_t degree, const Inner& inner, const Placed& placed,
                                     const Interior& interior) {
  std::uint32_t found = degree;
  for (std::uint32_t i = 0; i < degree; ++i) {
    if (!inner(i)) continue;
    const std::uint32_t j = i + 1 == degree ? 0 : i + 1;
    if (!placed(i) || !placed(j)) continue;
    if (found == degree) found = i;
    if (interior(i) || interior(j)) return i;
  }
  return found;
}

}  // namespace laguerre::core
