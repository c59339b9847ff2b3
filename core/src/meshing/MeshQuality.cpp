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

MeshQuality measure_quality(const TriangleMesh& mesh, const std::vector<Metric>& metrics) {
  MeshQuality q;
  std::vector<Matrix2> roots;
  roots.reserve(metrics.size());
  for (const Metric& m : metrics) roots.push_back(square_root(m));
  std::map<std::pair<std::size_t, std::size_t>, bool> edges;
  for (const auto& t : mesh.triangles) {
    ElementQuality e{0, 180, 1};
    for (std::size_t k = 0; k < 3; ++k) {
      const auto [ratio, angle] = shape_in(roots[t[k]], mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
      e.radius_edge = std::max(e.radius_edge, ratio);
      e.smallest_angle = std::min(e.smallest_angle, angle);
      e.distortion = std::max(e.distortion, distortion(metrics[t[k]], metrics[t[(k + 1) % 3]]));
      edges.emplace(std::minmax(t[k], t[(k + 1) % 3]), true);
    }
    q.elements.push_back(e);
  }
  for (const auto& [e, unused] : edges) {
    const double dx = mesh.points[e.second][0] - mesh.points[e.first][0];
    const double dy = mesh.points[e.second][1] - mesh.points[e.first][1];
    q.edge_lengths.push_back(metric_length(metrics[e.first], dx, dy));
    q.edge_lengths.push_back(metric_length(metrics[e.second], dx, dy));
  }
  std::vector<double> ratios, angles, gammas;
  for (const auto& e : q.elements) {
    ratios.push_back(e.radius_edge);
    angles.push_back(e.smallest_angle);
    gammas.push_back(e.distortion);
  }
  q.radius_edge = summarize(ratios, 0.5, 3.0, 10);
  q.smallest_angle = summarize(angles, 0, 60, 12);
  q.distortion = summarize(gammas, 1, 2, 10);
  q.edge_length = summarize(q.edge_lengths, 0, 3, 12);
  return q;
}

}  // namespace laguerre::core
