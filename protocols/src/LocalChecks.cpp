#include "laguerre/protocols/LocalChecks.hpp"

#include <cmath>
#include <vector>

#include "laguerre/core/geometry/Predicates.hpp"

namespace laguerre::protocols {

namespace {
bool representable(const core::Circle& c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.r) && c.r >= 0;
}
bool polygon(const GlpdWedge& w) { return !w.outer && w.circles.size() > 3; }
}  // namespace

core::LocalCondition check_glpd_local(const core::Circle& v, std::uint64_t v_id, std::span<const core::Circle> neighbours,
                                      std::span<const std::uint64_t> neighbour_ids, bool boundary,
                                      std::uint32_t outer_gap, std::span<const GlpdWedge> wedges) {
  using core::LocalCondition;
  const std::size_t deg = neighbours.size();
  if (deg == 0) return LocalCondition::holds;
  // 1. Inner faces strictly convex, in wedge order; a face with a non-representable circle is reported
  //    as such before its convexity is asked (as core does, face by face).
  for (const GlpdWedge& w : wedges) {
    if (w.outer) continue;
    for (const core::Circle& c : w.circles)
      if (!representable(c)) return LocalCondition::unrepresentable;
    if (!core::is_strictly_convex(w.circles)) return LocalCondition::face_not_convex;
  }
  // 2. Perturbed LPD in G(φ): neighbours from w1 (after the outer wedge for a boundary node), each
  //    followed by the diagonals at v of the polygon in its wedge.
  std::vector<core::Circle> nb;
  std::vector<std::uint64_t> nid;
  const std::size_t start = boundary ? (outer_gap + 1) % deg : 0;
  for (std::size_t s = 0; s < deg; ++s) {
    const std::size_t i = (start + s) % deg;
    nb.push_back(neighbours[i]);
    nid.push_back(neighbour_ids[i]);
    if (!polygon(wedges[i])) continue;
    for (const auto& [a, c] : core::regular_triangulation_diagonals(wedges[i].circles, wedges[i].ids)) {
      if (a != 0) break;  // sorted: the diagonals at corner 0 come first, by increasing c
      nb.push_back(wedges[i].circles[c]);
      nid.push_back(wedges[i].ids[c]);
    }
  }
  const LocalCondition lpd = core::check_lpd_at_perturbed(v, v_id, nb, nid, boundary);
  if (lpd != LocalCondition::holds) return lpd;
  // 3. The local cell in G meets no edge [f_j, f_j+1], 1 ≤ j ≤ m − 2, of a polygon face.
  for (const GlpdWedge& w : wedges) {
    if (!polygon(w)) continue;
    for (std::size_t j = 1; j + 2 <= w.circles.size(); ++j)
      if (core::segment_meets_power_cell(core::centre(w.circles[j]), core::centre(w.circles[j + 1]), v,
                                         neighbours.data(), neighbours.size()))
        return LocalCondition::cell_crosses_face;
  }
  return LocalCondition::holds;
}

}  // namespace laguerre::protocols
