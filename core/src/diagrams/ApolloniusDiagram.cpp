/// @file
/// Apollonius diagrams: distances, brute-force nearest site, sampled hyperbola arcs, the sites reader.

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "laguerre/core/diagrams/ApolloniusDiagram.hpp"
#include "laguerre/core/diagrams/SitesFile.hpp"
#include "ApolloniusDetail.hpp"
#include "detail/Validity.hpp"

namespace laguerre::core {

double apollonius_distance(Point2 q, const ApolloniusSite& s) { return std::hypot(q.x - s.x, q.y - s.y) - s.w; }

SiteIndex apollonius_nearest(const std::vector<ApolloniusSite>& sites, Point2 q) {
  return detail::nearest_site(sites.size(), [&](SiteIndex i) { return apollonius_distance(q, sites[i]); });
}

std::vector<SampledEdge> apollonius_edges(const ApolloniusDiagram& diagram, const Box& box, int samples) {
  std::map<SiteIndex, std::set<SiteIndex>> neighbours;
  for (const auto& [a, b] : diagram.dual_edges) neighbours[a].insert(b), neighbours[b].insert(a);
  const double reach = std::hypot(box.width(), box.height());
  const Point2 box_centre{(box.xmin + box.xmax) / 2, (box.ymin + box.ymax) / 2};
  std::vector<SampledEdge> out;
  for (const auto& [a, b] : diagram.dual_edges) {
    const ApolloniusSite &sa = diagram.sites[a], &sb = diagram.sites[b];
    // Branch |x − p_a| − |x − p_b| = w_a − w_b = 2α with foci p_a = m − c·u, p_b = m + c·u:
    // x(s) = m + α·√(1 + s²)·u + β·s·v, β = √(c² − α²), s = sinh t (even spacing far away).
    const double c = std::hypot(sb.x - sa.x, sb.y - sa.y) / 2, alpha = (sa.w - sb.w) / 2;
    if (!(c > std::abs(alpha))) continue;
    const double beta = std::sqrt(c * c - alpha * alpha);
    const Point2 m{(sa.x + sb.x) / 2, (sa.y + sb.y) / 2}, u{(sb.x - sa.x) / (2 * c), (sb.y - sa.y) / (2 * c)},
        v{-u.y, u.x};
    const double span = (reach + std::hypot(m.x - box_centre.x, m.y - box_centre.y)) / beta;
    std::vector<SiteIndex> others;
    for (SiteIndex k : neighbours[a]) others.push_back(k);
    for (SiteIndex k : neighbours[b]) others.push_back(k);
    SampledEdge edge{a, b, {}};
    std::vector<Point2> run;
    const int n = std::max(samples, 2);
    for (int i = 0; i <= n; ++i) {
      // Quadratic spacing in s concentrates samples near the vertex of the branch.
      const double r = -1.0 + 2.0 * i / n, s = span * r * std::abs(r);
      const double ch = std::sqrt(1 + s * s);
      const Point2 x{m.x + alpha * ch * u.x + beta * s * v.x, m.y + alpha * ch * u.y + beta * s * v.y};
      bool ok = box.contains(x);
      if (ok) {
        const double da = apollonius_distance(x, sa), tol = 1e-12 * (1 + std::abs(da) + reach);
        for (SiteIndex k : others)
          if (k != a && k != b && apollonius_distance(x, diagram.sites[k]) < da - tol) {
            ok = false;
            break;
          }
      }
      if (ok) {
        run.push_back(x);
      } else {
        if (run.size() >= 2) edge.polylines.push_back(std::move(run));
        run.clear();
      }
    }
    if (run.size() >= 2) edge.polylines.push_back(std::move(run));
    if (!edge.polylines.empty()) out.push_back(std::move(edge));
  }
  return out;
}

bool ApolloniusDiagram::is_valid(bool verbose) const {
  const std::string violation = [&]() -> std::string {
    const std::size_t n = sites.size();
    std::vector<char> is_hidden(n, 0);
    for (std::size_t k = 0; k < hidden.size(); ++k) {
      if (hidden[k] >= n || (k > 0 && hidden[k] <= hidden[k - 1]))
        return "the hidden sites are not increasing indices below " + std::to_string(n);
      is_hidden[hidden[k]] = 1;
    }
    for (SiteIndex i = 0; i < n; ++i) {
      const Point2 p{sites[i].x, sites[i].y};
      const double own = apollonius_distance(p, sites[i]), tol = 1e-8 * (1 + std::abs(own));
      bool beaten = false;  // some other site at most as far from p as site i
      for (SiteIndex j = 0; j < n; ++j)
        if (j != i && apollonius_distance(p, sites[j]) <= own + tol) {
          if (!is_hidden[i] && apollonius_distance(p, sites[j]) < own - tol)
            return "the centre of visible site " + std::to_string(i) + " is strictly closer to site " + std::to_string(j);
          beaten = true;
        }
      if (is_hidden[i] && !beaten) return "hidden site " + std::to_string(i) + " lies in no other site's disc";
    }
    for (std::size_t k = 0; k < dual_edges.size(); ++k) {
      const auto [a, b] = dual_edges[k];
      if (!(a < b && b < n) || is_hidden[a] || is_hidden[b] || (k > 0 && !(dual_edges[k - 1] < dual_edges[k])))
        return "dual edge (" + std::to_string(a) + ", " + std::to_string(b) + ") is malformed, unsorted or touches a hidden site";
    }
    for (std::size_t k = 0; k < vertices.size(); ++k) {
      const ApolloniusVertex& v = vertices[k];
      const std::string name = "vertex " + std::to_string(k);
      if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y)) return name + " is not finite";
      if (!(v.sites[0] < v.sites[1] && v.sites[1] < v.sites[2] && v.sites[2] < n))
        return name + " is not labelled by three increasing site indices";
      double scale = 1 + std::abs(v.distance);
      for (SiteIndex s : v.sites) {
        if (is_hidden[s]) return name + " is labelled by hidden site " + std::to_string(s);
        scale += std::abs(sites[s].w) + std::hypot(v.position.x - sites[s].x, v.position.y - sites[s].y);
      }
      const double tol = 1e-8 * scale;
      for (SiteIndex s : v.sites)
        if (std::abs(apollonius_distance(v.position, sites[s]) - v.distance) > tol)
          return name + " is not at distance " + std::to_string(v.distance) + " from its site " + std::to_string(s);
      for (SiteIndex j = 0; j < n; ++j)
        if (apollonius_distance(v.position, sites[j]) < v.distance - tol)
          return name + " is strictly closer to site " + std::to_string(j) + " than to its three sites";
      for (const auto& pair : {std::pair{v.sites[0], v.sites[1]}, std::pair{v.sites[1], v.sites[2]}, std::pair{v.sites[0], v.sites[2]}})
        if (!std::binary_search(dual_edges.begin(), dual_edges.end(), pair))
          return name + ": its sites " + std::to_string(pair.first) + " and " + std::to_string(pair.second) + " are not a dual edge";
    }
    return "";
  }();
  return detail::report_validity(violation, verbose);
}

std::vector<ApolloniusSite> read_apollonius_sites(const std::string& path) {
  std::vector<ApolloniusSite> sites;
  for (const SiteRow& r : read_site_rows(path, apollonius_columns, "Apollonius diagram")) sites.push_back({r.values[0], r.values[1], r.values[2]});
  return sites;
}

}  // namespace laguerre::core
