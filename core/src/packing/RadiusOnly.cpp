#include "laguerre/core/packing/RadiusOnly.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace laguerre::core {

bool radius_only_holds(double h_v, const StarView& star, bool boundary, double angle_gap) {
  if (boundary || star.neighbour_h.empty()) return true;
  return std::abs(star_angle_sum(h_v, star) - 2 * std::numbers::pi) <= angle_gap;  // NaN: false
}

bool radius_only_everywhere(const PackingComplex& k, const Radii& h, double angle_gap) {
  // The star as PackingAgent holds it: neighbours from the first dart, K's cosines unless tangent-only.
  const PlanarGraph& g = k.graph;
  std::vector<double> nh, spoke, rim;
  for (Vertex v = 0; v < g.num_vertices(); ++v) {
    if (g.is_boundary(v)) continue;
    nh.clear();
    spoke.clear();
    rim.clear();
    const Dart first = g.first_dart(v);
    for (Dart d = first; d < first + g.degree(v); ++d) {
      nh.push_back(h[g.head(d)]);
      if (!k.tangent_only[v]) {
        spoke.push_back(k.cos_angle[d]);
        rim.push_back(k.cos_angle[g.next_in_face(d)]);
      }
    }
    if (!radius_only_holds(h[v], StarView{nh, spoke, rim}, false, angle_gap)) return false;
  }
  return true;
}

std::uint32_t radius_flood_depth(const Layout& layout) {
  std::uint32_t height = 0;
  for (std::uint32_t w : layout.wave) height = std::max(height, w);
  return radius_flood_depth(height);
}

std::uint32_t radius_flood_depth(std::uint32_t height) { return 2 * height + 2; }

int radius_flood_period(int depth, int steps_per_check) {
  const long long per = 63LL * steps_per_check;
  return static_cast<int>(std::max(1LL, (depth + per - 1) / per));
}

bool radius_flood_tested(long long t, int steps_per_check, int period) {
  return t % steps_per_check == 0 && (t / steps_per_check) % period == 0;
}

}  // namespace laguerre::core
