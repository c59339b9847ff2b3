#include "laguerre/core/meshing/MeshQuality.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace laguerre::core {

namespace {

/// Radius–edge ratio and smallest angle (degrees) of triangle (p, q, r) after mapping by f.
std::pair<double, double> shape_in(const Matrix2& f, const std::array<double, 2>& p, const std::array<double, 2>& q,
                                   const std::array<double, 2>& r) {
  auto map = [&](const std::array<double, 2>& a) {
    return std::array<double, 2>{f.m00 * a[0] + f.m01 * a[1], f.m10 * a[0] + f.m11 * a[1]};
  };
  const auto a = map(p), b = map(q), c = map(r);
  const double la = std::hypot(b[0] - c[0], b[1] - c[1]);  // opposite a
  const double lb = std::hypot(c[0] - a[0], c[1] - a[1]);
  const double lc = std::hypot(a[0] - b[0], a[1] - b[1]);
  const double twice_area = std::abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
  const double radius = la * lb * lc / (2 * twice_area);
  const double shortest = std::min({la, lb, lc});
  // The smallest angle is opposite the shortest side: sin θ = shortest / (2R).
  const double angle = std::asin(std::min(1.0, shortest / (2 * radius))) * 180 / M_PI;
  return {radius / shortest, angle};
}

}  // namespace

QualitySummary summarize(std::vector<double> values, double lo, double hi, std::size_t bins) {
  QualitySummary s;
  s.count = values.size();
  s.bin_start = lo;
  s.bin_width = (hi - lo) / static_cast<double>(bins);
  s.histogram.assign(bins, 0);
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  s.min = values.front();
  s.max = values.back();
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
  auto rank = [&](double q) {
    const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
    return values[std::clamp<std::size_t>(k, 1, values.size()) - 1];
  };
  s.p5 = rank(0.05);
  s.p95 = rank(0.95);
  for (double v : values) {
    const double t = (v - lo) / s.bin_width;
    const auto bin = t <= 0 ? 0 : std::min(bins - 1, static_cast<std::size_t>(t));
    ++s.histogram[bin];
  }
  return s;
}

namespace {

/// Fills q's edge lengths (each edge a < b measured in the metric of a, then of b, by `length(v, a, b)`)
/// and summaries: smallest angles over [0, max_angle] in `angle_bins` bins, sliverity when `slivers`.
template <class Length>
void summarize_quality(MeshQuality& q, const std::map<std::pair<std::size_t, std::size_t>, bool>& edges, Length length,
                       double max_angle, std::size_t angle_bins, bool slivers) {
  for (const auto& [e, unused] : edges) {
    q.edge_lengths.push_back(length(e.first, e.first, e.second));
    q.edge_lengths.push_back(length(e.second, e.first, e.second));
  }
  std::vector<double> ratios, angles, gammas, sliverity;
  for (const auto& e : q.elements) {
    ratios.push_back(e.radius_edge);
    angles.push_back(e.smallest_angle);
    gammas.push_back(e.distortion);
    sliverity.push_back(e.sliverity);
  }
  q.radius_edge = summarize(ratios, 0.5, 3.0, 10);
  q.smallest_angle = summarize(angles, 0, max_angle, angle_bins);
  q.distortion = summarize(gammas, 1, 2, 10);
  q.edge_length = summarize(q.edge_lengths, 0, 3, 12);
  if (slivers) q.sliverity = summarize(sliverity, 0, 0.12, 12);
}

}  // namespace

MeshQuality measure_quality(const TriangleMesh& mesh, const std::vector<Metric>& metrics) {
  MeshQuality q;
  std::vector<Matrix2> roots;
  roots.reserve(metrics.size());
  for (const Metric& m : metrics) roots.push_back(square_root(m));
  std::map<std::pair<std::size_t, std::size_t>, bool> edges;
  for (const auto& t : mesh.triangles) {
    ElementQuality e{0, 180, 0, 1};
    for (std::size_t k = 0; k < 3; ++k) {
      const auto [ratio, angle] = shape_in(roots[t[k]], mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
      e.radius_edge = std::max(e.radius_edge, ratio);
      e.smallest_angle = std::min(e.smallest_angle, angle);
      e.distortion = std::max(e.distortion, distortion(metrics[t[k]], metrics[t[(k + 1) % 3]]));
      edges.emplace(std::minmax(t[k], t[(k + 1) % 3]), true);
    }
    q.elements.push_back(e);
  }
  summarize_quality(q, edges, [&](std::size_t v, std::size_t a, std::size_t b) {
    return metric_length(metrics[v], mesh.points[b][0] - mesh.points[a][0], mesh.points[b][1] - mesh.points[a][1]);
  }, 60, 12, false);
  return q;
}

namespace {

using P3 = std::array<double, 3>;
P3 minus(const P3& a, const P3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot3(const P3& a, const P3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
P3 cross3(const P3& a, const P3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }

struct TetShape {
  double radius_edge, smallest_dihedral, sliverity;
};

/// Shape of the tetrahedron (p[0..3]) after mapping by f.
TetShape tet_shape(const Matrix3& f, const std::array<P3, 4>& q) {
  std::array<P3, 4> p;
  for (std::size_t i = 0; i < 4; ++i) p[i] = multiply(f, q[i]);
  const P3 a = minus(p[1], p[0]), b = minus(p[2], p[0]), c = minus(p[3], p[0]);
  const double six_volume = std::abs(dot3(a, cross3(b, c)));
  // Circumcentre relative to p[0].
  const P3 bc = cross3(b, c), ca = cross3(c, a), ab = cross3(a, b);
  const double d = 2 * dot3(a, bc);
  P3 o{};
  for (std::size_t k = 0; k < 3; ++k) o[k] = (dot3(a, a) * bc[k] + dot3(b, b) * ca[k] + dot3(c, c) * ab[k]) / d;
  const double radius = std::sqrt(dot3(o, o));
  double shortest = INFINITY, smallest = 180;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i + 1; j < 4; ++j) {
      const P3 e = minus(p[j], p[i]);
      shortest = std::min(shortest, std::sqrt(dot3(e, e)));
      // The dihedral angle at edge ij: between the other two vertices seen perpendicular to the edge.
      std::size_t k = 0;
      while (k == i || k == j) ++k;
      std::size_t l = 6 - i - j - k;
      const P3 u = cross3(e, minus(p[k], p[i])), w = cross3(e, minus(p[l], p[i]));
      const double angle = std::atan2(std::sqrt(dot3(cross3(u, w), cross3(u, w))), dot3(u, w)) * 180 / M_PI;
      smallest = std::min(smallest, angle);
    }
  return {radius / shortest, smallest, six_volume / 6 / (shortest * shortest * shortest)};
}

}  // namespace

MeshQuality measure_quality(const TetMesh& mesh, const std::vector<Metric3>& metrics, double sliver_bound) {
  MeshQuality q;
  q.sliver_bound = sliver_bound;
  std::vector<Matrix3> roots;
  roots.reserve(metrics.size());
  for (const Metric3& m : metrics) roots.push_back(square_root(m));
  std::map<std::pair<std::size_t, std::size_t>, bool> edges;
  for (const auto& t : mesh.tetrahedra) {
    const std::array<P3, 4> p{mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]], mesh.points[t[3]]};
    ElementQuality e{0, 180, INFINITY, 1};
    for (std::size_t k = 0; k < 4; ++k) {
      const TetShape s = tet_shape(roots[t[k]], p);
      e.radius_edge = std::max(e.radius_edge, s.radius_edge);
      e.smallest_angle = std::min(e.smallest_angle, s.smallest_dihedral);
      e.sliverity = std::min(e.sliverity, s.sliverity);
      for (std::size_t l = k + 1; l < 4; ++l) {
        e.distortion = std::max(e.distortion, distortion(metrics[t[k]], metrics[t[l]]));
        edges.emplace(std::minmax(t[k], t[l]), true);
      }
    }
    if (e.sliverity < sliver_bound) ++q.slivers;
    q.elements.push_back(e);
  }
  summarize_quality(q, edges, [&](std::size_t v, std::size_t a, std::size_t b) {
    return metric_length(metrics[v], minus(mesh.points[b], mesh.points[a]));
  }, 90, 18, true);
  return q;
}

}  // namespace laguerre::core
