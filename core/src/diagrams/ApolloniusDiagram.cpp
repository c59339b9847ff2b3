/// @file
/// Apollonius diagrams: distances, brute-force nearest site, sampled hyperbola arcs, the sites reader.

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "laguerre/core/diagrams/ApolloniusDiagram.hpp"

namespace laguerre::core {

double apollonius_distance(Point2 q, const ApolloniusSite& s) { return std::hypot(q.x - s.x, q.y - s.y) - s.w; }

SiteIndex apollonius_nearest(const std::vector<ApolloniusSite>& sites, Point2 q) {
  SiteIndex best = no_site;
  double best_d = 0;
  for (SiteIndex i = 0; i < sites.size(); ++i) {
    const double d = apollonius_distance(q, sites[i]);
    if (best == no_site || d < best_d) best = i, best_d = d;
  }
  return best;
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

std::vector<ApolloniusSite> read_apollonius_sites(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the Apollonius sites file.");
  std::vector<ApolloniusSite> sites;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream tokens(line);
    std::vector<std::string> words;
    for (std::string w; tokens >> w;) words.push_back(w);
    if (words.empty()) continue;
    const std::string where = path + ":" + std::to_string(number) + ": ";
    if (words.size() != 3)
      throw std::runtime_error(where + "found " + std::to_string(words.size()) +
                               " fields; expected 3 numbers `x y w` (centre and additive weight).");
    double value[3];
    for (int k = 0; k < 3; ++k) {
      std::size_t used = 0;
      try {
        value[k] = std::stod(words[static_cast<std::size_t>(k)], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != words[static_cast<std::size_t>(k)].size() || !std::isfinite(value[k]))
        throw std::runtime_error(where + "found `" + words[static_cast<std::size_t>(k)] + "` in field " +
                                 std::to_string(k + 1) + "; expected a finite number.");
    }
    sites.push_back({value[0], value[1], value[2]});
  }
  return sites;
}

}  // namespace laguerre::core
