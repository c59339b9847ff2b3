// How much a 3D metric field varies over one element: the thesis's hypothesis on the field (the
// distortion between the metrics of two neighbouring vertices is bounded, and close to 1 at the scale
// of the elements; Rouxel-Labbé, chapter 3) measured on a field and a domain, per element size.
//
//   build/release/tools/bench/field_distortion DOMAIN.off FIELD [--grid N] [--lengths L1,L2,…] [--gamma G]
//
// For the points p of an N×N×N grid of cell centres of the domain's bounding box that are inside the
// domain (exact location), and 64 directions u (a Fibonacci sphere), q = p + L·F_p⁻¹u is the point at
// distance L from p in p's own metric M_p (F_p = M_p^{1/2}): an edge of length L in the metric, which
// is what the mesher's elements are (size bound S = 1: circumradius ≤ 1, edges up to 2). Pairs with q
// outside the domain are skipped. Per L it prints, over all pairs: the relative distortion
// γ(M_p, M_q) (core::distortion: the quantity rule 2 bounds by γ₀) at the median, 95th percentile and
// maximum, the share of pairs with γ ≥ G (γ₀, default 1.5), and, where both metrics are anisotropic
// (largest size / smallest size ≥ 1.5, so that the strongest direction is well defined), the angle in
// radians between the strongest directions (eigenvector of the largest eigenvalue) of M_p and M_q.
// A field meets the hypothesis at the scale of the elements when γ stays well below γ₀ at L ≈ 1–2.
// The fields are parsed by core (parse_metric_field3: muparser expressions, background meshes), so
// this is C++ rather than Python: there is one implementation of each field.
#include "laguerre/core/meshing/Domain3.hpp"
#include "laguerre/core/meshing/Metric3.hpp"
#include "laguerre/core/meshing/MetricField.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace laguerre::core;
using P3 = std::array<double, 3>;

/// The unit eigenvector of the largest eigenvalue of m, and largest size / smallest size.
std::pair<Eigen::Vector3d, double> strongest(const Metric3& m) {
  Eigen::Matrix3d a;
  a << m.xx, m.xy, m.xz, m.xy, m.yy, m.yz, m.xz, m.yz, m.zz;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> e(a);
  return {e.eigenvectors().col(2), std::sqrt(e.eigenvalues()(2) / e.eigenvalues()(0))};
}

double quantile(std::vector<double>& v, double q) {
  if (v.empty()) return NAN;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

[[noreturn]] void usage(const std::string& why) {
  std::fprintf(stderr, "field_distortion: %s\nusage: field_distortion DOMAIN.off FIELD [--grid N] [--lengths L1,L2,...] [--gamma G]\n",
               why.c_str());
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) usage("expected a domain and a field");
  const std::string domain_path = argv[1], spec = argv[2];
  int grid = 16;
  double gamma0 = 1.5;
  std::vector<double> lengths{0.25, 0.5, 1, 1.633, 2};
  for (int i = 3; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) usage("option '" + a + "' needs a value");
    const std::string value = argv[++i];
    char* end = nullptr;
    if (a == "--grid") {
      grid = static_cast<int>(std::strtol(value.c_str(), &end, 10));
      if (*end || grid < 1 || grid > 200) usage("--grid: expected an integer in [1, 200], got '" + value + "'");
    } else if (a == "--gamma") {
      gamma0 = std::strtod(value.c_str(), &end);
      if (*end || !(gamma0 >= 1)) usage("--gamma: expected a number >= 1, got '" + value + "'");
    } else if (a == "--lengths") {
      lengths.clear();
      std::stringstream in(value);
      for (std::string w; std::getline(in, w, ',');) {
        const double l = std::strtod(w.c_str(), &end);
        if (*end || !(l > 0) || !std::isfinite(l)) usage("--lengths: expected positive numbers, got '" + w + "'");
        lengths.push_back(l);
      }
    } else {
      usage("unknown option '" + a + "'");
    }
  }
  try {
    const PolyhedralDomain domain = read_polyhedral_domain(domain_path);
    const auto field = parse_metric_field3(spec);
    const auto box = domain.bounding_box();
    std::vector<P3> points;
    for (int i = 0; i < grid; ++i)
      for (int j = 0; j < grid; ++j)
        for (int k = 0; k < grid; ++k) {
          const P3 p{box[0] + (i + 0.5) / grid * (box[3] - box[0]), box[1] + (j + 0.5) / grid * (box[4] - box[1]),
                     box[2] + (k + 0.5) / grid * (box[5] - box[2])};
          if (domain.locate(p) == DomainSide::inside) points.push_back(p);
        }
    constexpr int kDirections = 64;
    std::vector<P3> directions;
    const double golden = M_PI * (3 - std::sqrt(5.0));
    for (int k = 0; k < kDirections; ++k) {
      const double z = 1 - (k + 0.5) * 2 / kDirections, r = std::sqrt(1 - z * z);
      directions.push_back({r * std::cos(golden * k), r * std::sin(golden * k), z});
    }
    std::printf("field %s on %s: %zu grid points inside (grid %d^3) x %d directions, gamma0 = %g\n",
                field->describe().c_str(), domain_path.c_str(), points.size(), grid, kDirections, gamma0);
    std::printf("%8s %8s %9s %9s %9s %9s %8s %9s %9s %9s\n", "L_metric", "pairs", "gamma_p50", "gamma_p95",
                "gamma_max", ">=gamma0", "aniso", "rot_p50", "rot_p95", "rot_max");
    for (const double length : lengths) {
      std::vector<double> gammas, rotations;
      std::size_t over = 0;
      for (const P3& p : points) {
        const Metric3 mp = field->at(p[0], p[1], p[2]);
        const Matrix3 f = square_root(mp);
        const auto [vp, ap] = strongest(mp);
        for (const P3& u : directions) {
          const P3 d = solve(f, {length * u[0], length * u[1], length * u[2]});
          const P3 q{p[0] + d[0], p[1] + d[1], p[2] + d[2]};
          if (domain.locate(q) != DomainSide::inside) continue;
          const Metric3 mq = field->at(q[0], q[1], q[2]);
          const double g = distortion(mp, mq);
          gammas.push_back(g);
          over += g >= gamma0;
          const auto [vq, aq] = strongest(mq);
          if (ap >= 1.5 && aq >= 1.5) rotations.push_back(std::acos(std::min(1.0, std::abs(vp.dot(vq)))));
        }
      }
      const std::size_t n = gammas.size(), nr = rotations.size();
      std::printf("%8.3f %8zu %9.3f %9.3f %9.3f %8.1f%% %7.0f%% %9.3f %9.3f %9.3f\n", length, n, quantile(gammas, 0.5),
                  quantile(gammas, 0.95), n ? *std::max_element(gammas.begin(), gammas.end()) : NAN,
                  n ? 100.0 * static_cast<double>(over) / static_cast<double>(n) : NAN,
                  n ? 100.0 * static_cast<double>(nr) / static_cast<double>(n) : NAN, quantile(rotations, 0.5),
                  quantile(rotations, 0.95), nr ? *std::max_element(rotations.begin(), rotations.end()) : NAN);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "field_distortion: %s\n", e.what());
    return 2;
  }
  return 0;
}
