#include "laguerre/core/power/LocalPowerDiagram.hpp"

#include <cmath>

#include <cassert>

#include "../detail/FastFilter128.hpp"
#include "PowerDetail.hpp"

namespace laguerre::core {

using detail::SmallBuffer;

std::string_view to_string(LocalCondition c) {
  switch (c) {
    case LocalCondition::holds: return "holds";
    case LocalCondition::site_outside_cell: return "site_outside_cell";
    case LocalCondition::neighbour_order: return "neighbour_order";
    case LocalCondition::missing_edge: return "missing_edge";
    case LocalCondition::boundary_vertex_inside_disc: return "boundary_vertex_inside_disc";
    case LocalCondition::face_not_convex: return "face_not_convex";
    case LocalCondition::cell_crosses_face: return "cell_crosses_face";
    case LocalCondition::unrepresentable: return "unrepresentable";
  }
  return "unknown";
}

namespace {

// ---------------------------------------------------------------------------------------------
// Directions and angles, exactly.
//
// Directions are d(w) = p(w) − p(v). We split the circle of directions into the "upper" half
// [0, π) = {dy > 0} ∪ {dy = 0, dx > 0} and the "lower" half [π, 2π). Comparing the raw doubles
// y(w) > y(v) decides the sign of the exact difference, so the split is exact.
// ---------------------------------------------------------------------------------------------

// Written once over the coordinate type: C is Circle or Circle128 (binary128 coordinates, compared
// natively and exactly), P the matching point type.
template <class C>
bool upper(const C& v, const C& w) { return w.y > v.y || (w.y == v.y && w.x > v.x); }
bool upper(Point2 a, Point2 b) { return b.y > a.y || (b.y == a.y && b.x > a.x); }
bool upper(Point128 a, Point128 b) { return b.y > a.y || (b.y == a.y && b.x > a.x); }

// angle(p(a) − p(v)) < angle(p(b) − p(v)) with angles in [0, 2π), for non-zero directions. Within
// one half the angles differ by less than π, so the orientation decides; equal angles are not less.
template <class C>
bool angle_less(const C& v, const C& a, const C& b) {
  const bool ua = upper(v, a), ub = upper(v, b);
  if (ua != ub) return ua;
  return orientation(centre(v), centre(a), centre(b)) == Sign::positive;
}

// ---------------------------------------------------------------------------------------------
// LPD at one vertex.
//
// H_i = {x : pow(x, v) ≤ pow(x, w_i)} has outward normal n_i = p(w_i) − p(v); the local cell is
// C = ∩ H_i. The edges of a convex polygon appear counter-clockwise in the angular order of their
// outward normals, so "the cells adjacent to Cell(v) are exactly w1 … wn in this order" says: every
// H_i carries an edge of positive length, and going around ∂C counter-clockwise they come in the
// order w1 … wn. We decide it as follows (all exact).
//
// Interior v (cyclic order, C must be bounded):
//  (1) p(v) ∈ C: pow(p(v), v) ≤ pow(p(v), w_i) for all i.
//  (2) orientation(p(v), p(w_i), p(w_{i+1})) > 0 for every cyclic i: consecutive normals turn left by
//      an angle in (0, π).
//  (3) the normals wind exactly once: with every step in (0, π), a step enters the upper half from
//      the lower half iff it crosses angle 0, so the number of lower→upper transitions is the
//      winding number.
//  (4) q_{i−1,i} = L_{i−1} ∩ L_i (the radical centre of v, w_{i−1}, w_i, which exists by (2)) lies
//      strictly inside H_{i+1}. Along L_i in the counter-clockwise direction t_i = rot90(n_i),
//      pow(·, v) − pow(·, w_{i+1}) increases (t_i·n_{i+1} = n_i × n_{i+1} > 0 by (2)), so (4) says
//      exactly that the corner q_{i,i+1} comes strictly after q_{i−1,i} on L_i: edge i has positive
//      length and the right direction.
//  Sufficiency: by (2)–(4) the closed polygon q_{n,1} q_{1,2} … has edges of positive length whose
//  directions turn strictly left with total turn 2π, hence it is a strictly convex polygon P; each
//  edge lies on L_i with P on the inner side, so P = ∩ H_i = C and all edges are present in order.
//  Necessity: if C is bounded with edges w1 … wn in cyclic order, consecutive normals of a convex
//  polygon turn by (0, π) and wind once, and a corner q_{i−1,i} on the boundary of H_{i+1} would make
//  edge i empty (pow(·, v) − pow(·, w_{i+1}) increases along it), so (2)–(4) hold. An interior vertex
//  whose local cell is unbounded fails (2) or (3): Theorem 5.2.1's gluing needs the corner of every
//  pair of consecutive neighbours (the power vertex of each incident triangle).
//
// Boundary v with chain w1 … wn (outer face between wn and w1):
//  (2) for i = 1 … n−1 only: the corners q_{i,i+1} of the inner triangles must exist.
//  (3) the chain turns by T < 2π in total. With k the number of lower→upper transitions along the
//      chain and θ the angles, T = θ_n − θ_1 + 2πk, so T < 2π ⇔ k = 0, or k = 1 and θ_n < θ_1.
//  (4) for the edges i = 2 … n−1, whose both ends are corners of the chain.
//  Closure: if orientation(p(v), p(wn), p(w1)) > 0 the closing turn c is in (0, π) and T + c is a
//  positive multiple of 2π below 3π, so the normals wind exactly once: C is bounded (the interior
//  case). Then edges 1 and n need (4) against each other (q_{n,1} strictly inside H_2, q_{n−1,n}
//  strictly inside H_1), and the boundary rule: the corner Cell(v) ∩ Cell(w1) ∩ Cell(wn) = q_{n,1}
//  must lie strictly outside the unit disc. Otherwise the closing turn is in [π, 2π), so T ≤ π: the
//  chain q_{1,2} … q_{n−1,n} extended by the rays of L_1 and L_n is a locally convex curve turning by
//  at most π, hence the boundary of the convex unbounded region C, whose first and last edges are
//  disjoint rays: the corner is empty and the boundary rule holds.
//
//  Degree 2 (n = 2): the only corner is q_{1,2}, the power vertex of the inner triangle (v, w1, w2).
//  Read literally, Def. 5.2.2 would put it outside the unit disc, but the proof of Theorem 5.2.1
//  needs exactly that vertex inside (it is the one vertex of e(v, w) in D²), and for an exact packing
//  it is the incentre of the triangle of tangent circles, inside the disc: Theorem 5.2.5 would fail.
//  The definition itself glosses "empty" as "which means that Cell(v) is unbounded": the rule is
//  about the corner on the outer-face side, which for n = 2 does not exist (the closing turn is > π
//  since the chain turn is < π), so a degree-2 boundary vertex needs (1) and (2) only. The general
//  closure test above implements exactly this reading.
//
// Orientation: the thesis accepts the cyclic order up to a global mirror; laguerre's rotation systems
// are counter-clockwise, so a mirrored (clockwise) layout fails with `neighbour_order`.
//
// Perturbation: with `prio` non-null, prio[0] is v's id and prio[1 + i] w_i's; (1) and (4) are then
// decided on the perturbed embedding (PowerDetail.hpp). Orientations do not depend on the weights.
// ---------------------------------------------------------------------------------------------

bool representable(const Circle& c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.r) && c.r >= 0;
}
bool representable(const Circle128& c) {
  return detail::finite128(c.x) && detail::finite128(c.y) && detail::finite128(c.r) && c.r >= 0;
}

template <class C>
LocalCondition lpd_core(const C& v, std::span<const C> w, bool boundary, bool perturbed, std::uint64_t pv,
                        std::span<const std::uint64_t> pw) {
  const std::size_t n = w.size();
  // Non-finite inputs have no exact value: nothing can be decided (and exact arithmetic would abort).
  if (!representable(v)) return LocalCondition::unrepresentable;
  for (const C& c : w)
    if (!representable(c)) return LocalCondition::unrepresentable;
  if (n == 0) return LocalCondition::holds;
  auto prio = [&](std::size_t i) { return perturbed ? pw[i] : std::uint64_t{0}; };
  // (1) p(v) in the closed local cell.
  for (std::size_t i = 0; i < n; ++i)
    if (detail::compare_power_sos(v, w[i], perturbed, pv, prio(i)) == Sign::positive)
      return LocalCondition::site_outside_cell;
  if (boundary && n == 1) return LocalCondition::holds;  // a half-plane: one edge, nothing to order
  const auto pv_ = centre(v);
  // (2) strict left turns between consecutive normals; (3) winding.
  const std::size_t pairs = boundary ? n - 1 : n;
  std::size_t k = 0;
  for (std::size_t i = 0; i < pairs; ++i) {
    const C& a = w[i];
    const C& b = w[(i + 1) % n];
    if (orientation(pv_, centre(a), centre(b)) != Sign::positive) return LocalCondition::neighbour_order;
    if (!upper(v, a) && upper(v, b)) ++k;
  }
  if (boundary) {
    if (!(k == 0 || (k == 1 && angle_less(v, w[n - 1], w[0])))) return LocalCondition::neighbour_order;
  } else if (k != 1) {
    return LocalCondition::neighbour_order;
  }
  // (4) positive length of the edges between two corners of the chain.
  auto side = [&](std::size_t a, std::size_t b, std::size_t t) {
    if (!perturbed) return radical_centre_power_side(v, w[a], w[b], w[t]);
    const std::uint64_t ids[4] = {pv, pw[a], pw[b], pw[t]};
    return detail::power_side_sos(v, w[a], w[b], w[t], ids);
  };
  if (!boundary) {
    // n ≥ 3 here: n = 1 and n = 2 cannot pass (2) cyclically.
    for (std::size_t i = 0; i < n; ++i)
      if (side((i + n - 1) % n, i, (i + 1) % n) != Sign::positive) return LocalCondition::missing_edge;
    return LocalCondition::holds;
  }
  for (std::size_t i = 1; i + 1 < n; ++i)
    if (side(i - 1, i, i + 1) != Sign::positive) return LocalCondition::missing_edge;
  // Closure on the outer-face side (never taken for n = 2: (2) made the opposite turn positive).
  if (orientation(pv_, centre(w[n - 1]), centre(w[0])) == Sign::positive) {
    if (side(n - 1, 0, 1) != Sign::positive) return LocalCondition::missing_edge;
    if (side(n - 2, n - 1, 0) != Sign::positive) return LocalCondition::missing_edge;
    if (radical_centre_outside_unit_disc(v, w[n - 1], w[0]) != Sign::positive)
      return LocalCondition::boundary_vertex_inside_disc;
  }
  return LocalCondition::holds;
}

// Counter-clockwise neighbours of v in g, starting at lpd_first_dart.
template <class Embedding, class Buffer>
void collect_neighbours(const PlanarGraph& g, const Embedding& phi, Vertex v, Buffer& out) {
  const std::uint32_t deg = g.degree(v);
  Dart d = lpd_first_dart(g, v);
  for (std::uint32_t i = 0; i < deg; ++i, d = g.next_ccw(d)) out.push_back(phi[g.head(d)]);
}

// The face walk to the left of d, starting at tail(d): circles and ids.
template <class C>
void collect_face(const PlanarGraph& g, const std::vector<C>& phi, Dart d, SmallBuffer<C>& circles,
                  SmallBuffer<std::uint64_t>& ids) {
  circles.clear();
  ids.clear();
  Dart e = d;
  do {
    circles.push_back(phi[g.tail(e)]);
    ids.push_back(g.id(g.tail(e)));
    e = g.next_in_face(e);
  } while (e != d);
}

bool is_inner_polygon(const PlanarGraph& g, Dart d) {
  const Face f = g.face_of(d);
  return f != g.outer_face() && g.face_size(f) > 3;
}

}  // namespace

LocalCondition check_lpd_at(const Circle& v, std::span<const Circle> ccw_neighbours, bool boundary) {
  return lpd_core(v, ccw_neighbours, boundary, false, 0, {});
}

LocalCondition check_lpd_at(const Circle128& v, std::span<const Circle128> ccw_neighbours, bool boundary) {
  return lpd_core(v, ccw_neighbours, boundary, false, 0, {});
}

LocalCondition check_lpd_at_perturbed(const Circle& v, std::uint64_t v_priority, std::span<const Circle> ccw_neighbours,
                                      std::span<const std::uint64_t> priorities, bool boundary) {
  assert(priorities.size() == ccw_neighbours.size());
  return lpd_core(v, ccw_neighbours, boundary, true, v_priority, priorities);
}

Dart lpd_first_dart(const PlanarGraph& g, Vertex v) {
  const Dart first = g.first_dart(v);
  if (!g.is_boundary(v)) return first;
  // face_of(v→u_i) is the wedge from u_i counter-clockwise to u_{i+1} (faces lie left of darts and
  // next_in_face(u→v) = v→(neighbour before u)), so if v→u_i bounds the outer face, wn = u_i and
  // w1 = u_{i+1}.
  const std::uint32_t deg = g.degree(v);
  for (Dart d = first; d < first + deg; ++d)
    if (g.face_of(d) == g.outer_face()) return g.next_ccw(d);
  return first;  // unreachable for a boundary vertex
}

namespace {
template <class C>
LocalCondition check_lpd_t(const PlanarGraph& g, const std::vector<C>& phi, Vertex v) {
  SmallBuffer<C> nb;
  collect_neighbours(g, phi, v, nb);
  return lpd_core(phi[v], nb.span(), g.is_boundary(v), false, 0, {});
}

template <class C>
bool is_strictly_convex_t(std::span<const C> q) {
  // Every corner a strict left turn (each edge direction turns by (0, π)); then, as in lpd_core, the
  // number of lower→upper transitions of the edge directions is the turning number, which must be 1.
  const std::size_t m = q.size();
  if (m < 3) return false;
  std::size_t k = 0;
  for (std::size_t j = 0; j < m; ++j) {
    const auto a = centre(q[j]), b = centre(q[(j + 1) % m]), c = centre(q[(j + 2) % m]);
    if (orientation(a, b, c) != Sign::positive) return false;
    if (!upper(a, b) && upper(b, c)) ++k;
  }
  return k == 1;
}

template <class C>
LocalCondition check_glpd_t(const PlanarGraph& g, const std::vector<C>& phi, Vertex v) {
  const std::uint32_t deg = g.degree(v);
  if (deg == 0) return LocalCondition::holds;
  const Dart first = g.first_dart(v);
  SmallBuffer<C> fc;
  SmallBuffer<std::uint64_t> fid;
  // 1. The inner faces around v are strictly convex (triangles: counter-clockwise).
  for (Dart d = first; d < first + deg; ++d) {
    if (g.face_of(d) == g.outer_face()) continue;
    collect_face(g, phi, d, fc, fid);
    for (const C& c : fc.span())
      if (!representable(c)) return LocalCondition::unrepresentable;
    if (!is_strictly_convex_t(fc.span())) return LocalCondition::face_not_convex;
  }
  // 2. LPD(v) in G(φ), perturbed. v's neighbours in G(φ): after each dart v→u_i whose left face f is
  //    a non-triangle inner face, the diagonals of f at v, which lie in the wedge (u_i, u_{i+1}) and
  //    come counter-clockwise in face order. With f = (f0 = v, f1 = u_i, …, f_{m−1} = u_{i+1}), the
  //    triangle of the (unique, perturbed) regular triangulation on edge v f_j has apex f_c; v f_c is
  //    a diagonal unless c = m − 1, and the fan continues from it. This is the same triangulation as
  //    `regular_triangulation_diagonals` computes from any starting corner.
  SmallBuffer<C> nb;
  SmallBuffer<std::uint64_t> nid;
  Dart d = lpd_first_dart(g, v);
  for (std::uint32_t i = 0; i < deg; ++i, d = g.next_ccw(d)) {
    nb.push_back(phi[g.head(d)]);
    nid.push_back(g.id(g.head(d)));
    if (!is_inner_polygon(g, d)) continue;
    collect_face(g, phi, d, fc, fid);
    const auto m = static_cast<std::uint32_t>(fc.size());
    for (std::uint32_t j = 1;;) {
      const std::uint32_t c = detail::lower_hull_apex(fc.span(), fid.span(), 0, j, j + 1, m - 1);
      if (c == m - 1) break;
      nb.push_back(fc[c]);
      nid.push_back(fid[c]);
      j = c;
    }
  }
  const LocalCondition lpd = lpd_core(phi[v], nb.span(), g.is_boundary(v), true, g.id(v), nid.span());
  if (lpd != LocalCondition::holds) return lpd;
  // 3. The local cell in G (g-neighbours only, exact, closed) meets no edge [f_i, f_{i+1}],
  //    1 ≤ i ≤ m − 2, of a non-triangle face f = (v, f1 … f_{m−1}): it may cross ∂f only on the two
  //    edges at v. Triangle faces are exempt (thesis, after Theorem 5.2.4).
  SmallBuffer<C> gn;
  for (Dart e = first; e < first + deg; ++e) gn.push_back(phi[g.head(e)]);
  const std::span<const C> others = gn.span();
  for (Dart e = first; e < first + deg; ++e) {
    if (!is_inner_polygon(g, e)) continue;
    collect_face(g, phi, e, fc, fid);
    for (std::size_t j = 1; j + 2 <= fc.size(); ++j)
      if (segment_meets_power_cell(centre(fc[j]), centre(fc[j + 1]), phi[v], others.data(), others.size()))
        return LocalCondition::cell_crosses_face;
  }
  return LocalCondition::holds;
}

template <class C>
LocalCondition check_local_t(const PlanarGraph& g, const std::vector<C>& phi, Vertex v) {
  const bool triangulated =
      g.outer_face() == none ||
      2 * g.num_edges() - g.face_size(g.outer_face()) == 3 * (g.num_faces() - 1);
  return triangulated ? check_lpd_t(g, phi, v) : check_glpd_t(g, phi, v);
}

template <class C>
std::vector<LocalCondition> check_all_t(const PlanarGraph& g, const std::vector<C>& phi) {
  const bool triangulated = g.inner_faces_are_triangles();
  std::vector<LocalCondition> out(g.num_vertices());
  for (Vertex v = 0; v < g.num_vertices(); ++v) out[v] = triangulated ? check_lpd_t(g, phi, v) : check_glpd_t(g, phi, v);
  return out;
}
}  // namespace

LocalCondition check_lpd(const PlanarGraph& g, const CircleEmbedding& phi, Vertex v) { return check_lpd_t(g, phi, v); }
LocalCondition check_lpd(const PlanarGraph& g, const CircleEmbedding128& phi, Vertex v) { return check_lpd_t(g, phi, v); }
bool is_strictly_convex(std::span<const Circle> q) { return is_strictly_convex_t(q); }
bool is_strictly_convex(std::span<const Circle128> q) { return is_strictly_convex_t(q); }
LocalCondition check_glpd(const PlanarGraph& g, const CircleEmbedding& phi, Vertex v) { return check_glpd_t(g, phi, v); }
LocalCondition check_glpd(const PlanarGraph& g, const CircleEmbedding128& phi, Vertex v) { return check_glpd_t(g, phi, v); }
LocalCondition check_local(const PlanarGraph& g, const CircleEmbedding& phi, Vertex v) { return check_local_t(g, phi, v); }
LocalCondition check_local(const PlanarGraph& g, const CircleEmbedding128& phi, Vertex v) { return check_local_t(g, phi, v); }
std::vector<LocalCondition> check_all(const PlanarGraph& g, const CircleEmbedding& phi) { return check_all_t(g, phi); }
std::vector<LocalCondition> check_all(const PlanarGraph& g, const CircleEmbedding128& phi) { return check_all_t(g, phi); }

std::vector<Point2> local_cell_polygon(const PlanarGraph& g, const CircleEmbedding& phi, Vertex v,
                                       double box_half_width) {
  // Sutherland–Hodgman clipping of the box by each H_w: 2 x·(p(w) − p(v)) ≤ z(w) − z(v), in doubles.
  const double h = box_half_width;
  std::vector<Point2> poly{{-h, -h}, {h, -h}, {h, h}, {-h, h}}, next;
  const Circle& c = phi[v];
  const double zv = c.x * c.x + c.y * c.y - c.r * c.r;
  for (Vertex w : g.neighbours(v)) {
    const Circle& o = phi[w];
    const double ax = 2 * (o.x - c.x), ay = 2 * (o.y - c.y);
    const double b = o.x * o.x + o.y * o.y - o.r * o.r - zv;
    auto f = [&](Point2 p) { return ax * p.x + ay * p.y - b; };  // ≤ 0 inside
    next.clear();
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Point2 p = poly[i], q = poly[(i + 1) % poly.size()];
      const double fp = f(p), fq = f(q);
      if (fp <= 0) next.push_back(p);
      if ((fp < 0 && fq > 0) || (fp > 0 && fq < 0)) {
        const double t = fp / (fp - fq);
        next.push_back({p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)});
      }
    }
    poly.swap(next);
    if (poly.empty()) break;
  }
  return poly;
}

}  // namespace laguerre::core
