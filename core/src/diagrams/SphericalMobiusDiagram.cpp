#include "laguerre/core/diagrams/SphericalMobiusDiagram.hpp"
#include "laguerre/core/Error.hpp"

#include <cmath>
#include <stdexcept>

namespace laguerre::core {

namespace {
std::vector<MobiusSite> project_all(const std::vector<SphereMobiusSite>& sites) {
  std::vector<MobiusSite> out;
  out.reserve(sites.size());
  for (const auto& s : sites) out.push_back(stereographic_site(s));
  return out;
}
}  // namespace

double sphere_mobius_distance(const Point3& x, const SphereMobiusSite& s) {
  const double dx = x[0] - s.p[0], dy = x[1] - s.p[1], dz = x[2] - s.p[2];
  return s.lambda * (dx * dx + dy * dy + dz * dz) - s.mu;
}

Point2 stereographic(const Point3& x) { return {x[0] / (1 - x[2]), x[1] / (1 - x[2])}; }

Point3 inverse_stereographic(Point2 x) {
  const double r2 = x.x * x.x + x.y * x.y;
  return {2 * x.x / (r2 + 1), 2 * x.y / (r2 + 1), (r2 - 1) / (r2 + 1)};
}

MobiusSite stereographic_site(const SphereMobiusSite& s) {
  const double l = s.lambda;
  const double pn = s.p[0] * s.p[0] + s.p[1] * s.p[1] + (s.p[2] - 1) * (s.p[2] - 1);
  const double pp = s.p[0] * s.p[0] + s.p[1] * s.p[1] + (s.p[2] + 1) * (s.p[2] + 1);
  const double a = l * pn - s.mu, c = l * pp - s.mu;
  if (a == 0 || !std::isfinite(a) || !std::isfinite(c))
    throw InputError("spherical Möbius diagram: a site's projected λ' = λ|P − N|² − μ is zero or not finite");
  const double bx = 2 * l * s.p[0], by = 2 * l * s.p[1];
  return {bx / a, by / a, a, (bx * bx + by * by) / a - c};
}

SphericalMobiusDiagram::SphericalMobiusDiagram(std::vector<SphereMobiusSite> sites, double window)
    : sites_(std::move(sites)), planar_(project_all(sites_), Box{-window, -window, window, window}) {}

SiteIndex SphericalMobiusDiagram::locate(const Point3& x) const { return planar_.locate(stereographic(x)); }

std::vector<Point3> SphericalMobiusDiagram::vertices() const {
  std::vector<Point3> out;
  for (const auto& v : planar_.vertices()) out.push_back(inverse_stereographic(v.point));
  return out;
}

std::vector<std::vector<Point3>> SphericalMobiusDiagram::edge_polylines(double step, int segment_points) const {
  std::vector<std::vector<Point3>> out;
  for (const auto& e : planar_.edges()) {
    std::vector<Point3> line;
    if (e.curve.is_arc) {
      for (Point2 p : e.curve.sample(step)) line.push_back(inverse_stereographic(p));
    } else {
      const int n = std::max(segment_points, 2);
      for (int k = 0; k < n; ++k) {
        const double t = static_cast<double>(k) / (n - 1);
        line.push_back(inverse_stereographic({e.curve.from.x + t * (e.curve.to.x - e.curve.from.x),
                                              e.curve.from.y + t * (e.curve.to.y - e.curve.from.y)}));
      }
    }
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace laguerre::core
