#include "LocalDelaunay3.hpp"


#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/determinant.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace laguerre::core::detail {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using P3 = std::array<double, 3>;

/// The M-in-sphere determinant of t against (p, q, r, s), in NT: rows (u, uᵀMu) for u = p − t,
/// r − t, q − t, s − t (CGAL's row order for side_of_oriented_sphere: positive inside).
template <class NT>
NT in_sphere_determinant(const P3& p, const P3& q, const P3& r, const P3& s, const P3& t, const std::array<double, 6>& m) {
  const NT xx(m[0]), xy(m[1]), xz(m[2]), yy(m[3]), yz(m[4]), zz(m[5]);
  const auto row = [&](const P3& a, NT& x, NT& y, NT& z, NT& l) {
    x = NT(a[0]) - NT(t[0]), y = NT(a[1]) - NT(t[1]), z = NT(a[2]) - NT(t[2]);
    l = xx * x * x + yy * y * y + zz * z * z + NT(2) * (xy * x * y + xz * x * z + yz * y * z);
  };
  NT px, py, pz, pl, qx, qy, qz, ql, rx, ry, rz, rl, sx, sy, sz, sl;
  row(p, px, py, pz, pl);
  row(q, qx, qy, qz, ql);
  row(r, rx, ry, rz, rl);
  row(s, sx, sy, sz, sl);
  return CGAL::determinant(px, py, pz, pl, rx, ry, rz, rl, qx, qy, qz, ql, sx, sy, sz, sl);
}

/// The power of two 2^k with a·2^k ∈ [0.5, 1), for a normal positive a; 0 when a is subnormal or so
/// large that 2^k would be subnormal (multiplying by it is then exact unless the product underflows).
double inverse_power_of_two(double a) {
  const auto biased = static_cast<int>((std::bit_cast<std::uint64_t>(a) >> 52) & 0x7ff);  // a ∈ [2^(b−1023), 2^(b−1022))
  const int k = 1022 - biased;
  if (biased == 0 || k + 1023 < 1) return 0;
  return std::bit_cast<double>(static_cast<std::uint64_t>(k + 1023) << 52);
}

}  // namespace

int metric_in_sphere_filter(const P3& p, const P3& q, const P3& r, const P3& s, const P3& t,
                            const std::array<double, 6>& metric) {
  // Rows (x, y, z, l) for the points in CGAL's row order p, r, q, s, relative to t. The differences
  // are rounded once each (relative error ≤ u), then multiplied by one power of two so that the
  // largest is in [0.5, 1), and the metric by another likewise: both exact (checked: no scaled value
  // falls into the subnormal range), and the sign of D is unchanged (D is homogeneous of degree 5 in the
  // differences and 1 in the metric).
  const P3* rows[4] = {&p, &r, &q, &s};
  double d[4][3];
  double largest = 0;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      d[i][k] = (*rows[i])[k] - t[k];
      largest = std::max(largest, std::abs(d[i][k]));
    }
  double largest_m = 0;
  for (double e : metric) largest_m = std::max(largest_m, std::abs(e));
  if (!(largest > 0) || !(largest_m > 0) || !std::isfinite(largest) || !std::isfinite(largest_m)) return kUndecided;
  // Fast path: the same determinant unscaled, against the static bound below scaled back,
  // 2⁻⁴⁰·L⁵·L_M (L, L_M the largest difference and metric entry; 2⁻⁴⁰ also covers the rounding of
  // L⁵·L_M), when L ∈ [2⁻¹⁰⁰, 2¹⁰⁰] and L_M ∈ [2⁻²⁰⁰, 2²⁰⁰]: no overflow (|D| < 2⁸·L⁵·L_M ≤ 2⁷⁰⁸),
  // and an underflowed intermediate (≤ 2⁻¹⁰⁷⁵, amplified by at most 2⁴·L_M·L³ by the later products,
  // ~100 of them) stays below 2⁻¹⁰⁶⁰·L_M·L³, far below 2⁻⁴¹·L⁵·L_M since L² ≥ 2⁻²⁰⁰.
  if (largest >= 0x1p-100 && largest <= 0x1p100 && largest_m >= 0x1p-200 && largest_m <= 0x1p200) {
    double l[4];
    for (int i = 0; i < 4; ++i) {
      const double x = d[i][0], y = d[i][1], z = d[i][2];
      l[i] = (metric[0] * (x * x) + metric[3] * (y * y)) + metric[5] * (z * z) +
             2 * ((metric[1] * (x * y) + metric[2] * (x * z)) + metric[4] * (y * z));
    }
    double e2[4][4];
    for (int j = 0; j < 4; ++j)
      for (int k = j + 1; k < 4; ++k) e2[j][k] = d[j][0] * d[k][1] - d[k][0] * d[j][1];
    const auto minor3 = [&](int a, int b, int c) {
      return (d[a][2] * e2[b][c] - d[b][2] * e2[a][c]) + d[c][2] * e2[a][b];
    };
    const double det =
        (l[1] * minor3(0, 2, 3) - l[0] * minor3(1, 2, 3)) + (l[3] * minor3(0, 1, 2) - l[2] * minor3(0, 1, 3));
    const double l2 = largest * largest, bound = 0x1p-40 * (l2 * l2 * largest * largest_m);
    if (det > bound) return 1;
    if (det < -bound) return -1;
  }
  const double scale = inverse_power_of_two(largest), scale_m = inverse_power_of_two(largest_m);
  if (scale == 0 || scale_m == 0) return kUndecided;
  constexpr double kTiny = 0x1p-900;  // scaled nonzero values below this: let the exact path decide
  double x[4], y[4], z[4], l[4], mm[6];
  for (int k = 0; k < 6; ++k) {
    mm[k] = metric[k] * scale_m;
    if (mm[k] != 0 && std::abs(mm[k]) < kTiny) return kUndecided;
  }
  for (int i = 0; i < 4; ++i) {
    x[i] = d[i][0] * scale, y[i] = d[i][1] * scale, z[i] = d[i][2] * scale;
    for (const double c : {x[i], y[i], z[i]})
      if (c != 0 && std::abs(c) < kTiny) return kUndecided;
    l[i] = (mm[0] * (x[i] * x[i]) + mm[3] * (y[i] * y[i])) + mm[5] * (z[i] * z[i]) +
           2 * ((mm[1] * (x[i] * y[i]) + mm[2] * (x[i] * z[i])) + mm[4] * (y[i] * z[i]));
  }
  // D = −l₀·M₀ + l₁·M₁ − l₂·M₂ + l₃·M₃ (expansion along the l column), M_i the 3×3 determinant of the
  // coordinates of the other three rows, each along its z column from the 2×2 minors e_jk of (x, y).
  double e2[4][4];
  for (int j = 0; j < 4; ++j)
    for (int k = j + 1; k < 4; ++k) e2[j][k] = x[j] * y[k] - x[k] * y[j];
  const auto minor3 = [&](int a, int b, int c) { return (z[a] * e2[b][c] - z[b] * e2[a][c]) + z[c] * e2[a][b]; };
  const double det = (l[1] * minor3(0, 2, 3) - l[0] * minor3(1, 2, 3)) + (l[3] * minor3(0, 1, 2) - l[2] * minor3(0, 1, 3));
  if (!std::isfinite(det)) return kUndecided;
  // The error. Each monomial of D carries at most 18 rounding factors (1+δ), |δ| ≤ u = 2⁻⁵³: 7 in its
  // lifted entry l (its two differences, two products, three additions), 8 in its 3×3 minor (the three
  // coordinate differences, the 2×2 minor's product and subtraction, the product by z, two
  // additions), then one product and two additions. So |fl(D) − D| ≤ γ₁₈·P, P the same expansion of
  // the exact differences in absolute values (every subtraction an addition), γ₁₈ < 18.001u.
  // Underflow: scaled magnitudes are below 2⁸ (|x|, |y|, |z| < 1, |metric entries| < 1, so l < 9,
  // |e_jk| < 2, |M_i| < 6, |D| < 216), and an underflowed intermediate (error ≤ 2⁻¹⁰⁷⁵) meets at most
  // three more products by values below 2⁴ among ~100 operations: less than 2⁻¹⁰⁵⁰ in all, covered
  // by the absolute 2⁻¹⁰⁰⁰.
  // Static stage: P ≤ 216·(1 − u)⁻⁵ < 217 (|a − t| ≤ |fl(a − t)|/(1 − u)), so the error is below
  // 18.001u·217 < 2⁻⁴¹: the bound 2⁻⁴⁰ decides well-shaped configurations without computing P.
  if (det > 0x1p-40) return 1;
  if (det < -0x1p-40) return -1;
  // Dynamic stage: fl(P) ≥ P·(1 − u)¹⁸·(1 − u)⁵ (products and additions of nonnegative terms, and the
  // differences' rounding), so γ₁₈·P < 2⁻⁴⁸·fl(P) = 32u·fl(P).
  double al[4], pe2[4][4];
  for (int i = 0; i < 4; ++i) {
    const double ax = std::abs(x[i]), ay = std::abs(y[i]), az = std::abs(z[i]);
    al[i] = (std::abs(mm[0]) * (ax * ax) + std::abs(mm[3]) * (ay * ay)) + std::abs(mm[5]) * (az * az) +
            2 * ((std::abs(mm[1]) * (ax * ay) + std::abs(mm[2]) * (ax * az)) + std::abs(mm[4]) * (ay * az));
  }
  for (int j = 0; j < 4; ++j)
    for (int k = j + 1; k < 4; ++k) pe2[j][k] = std::abs(x[j]) * std::abs(y[k]) + std::abs(x[k]) * std::abs(y[j]);
  const auto perm3 = [&](int a, int b, int c) {
    return (std::abs(z[a]) * pe2[b][c] + std::abs(z[b]) * pe2[a][c]) + std::abs(z[c]) * pe2[a][b];
  };
  const double perm =
      (al[1] * perm3(0, 2, 3) + al[0] * perm3(1, 2, 3)) + (al[3] * perm3(0, 1, 2) + al[2] * perm3(0, 1, 3));
  const double bound = 0x1p-48 * perm + 0x1p-1000;
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return kUndecided;
}

namespace {

int unfiltered_in_sphere(const P3& p, const P3& q, const P3& r, const P3& s, const P3& t, const std::array<double, 6>& m) {
  {
    CGAL::Protect_FPU_rounding<true> protect;
    const CGAL::Uncertain<CGAL::Sign> sign = CGAL::sign(in_sphere_determinant<CGAL::Interval_nt<false>>(p, q, r, s, t, m));
    if (CGAL::is_certain(sign)) return static_cast<int>(CGAL::get_certain(sign));
  }
  return static_cast<int>(CGAL::sign(in_sphere_determinant<CGAL::Exact_rational>(p, q, r, s, t, m)));
}

int exact_in_sphere(const P3& p, const P3& q, const P3& r, const P3& s, const P3& t, const std::array<double, 6>& m) {
  if (const int sign = metric_in_sphere_filter(p, q, r, s, t, m); sign != kUndecided) return sign;
  return unfiltered_in_sphere(p, q, r, s, t, m);
}

/// CGAL's 3D Delaunay traits with the M-lifting x ↦ xᵀMx in place of |x|²: the two predicates
/// Delaunay_triangulation_3 decides conflicts with (side_of_oriented_sphere_3 in dimension 3, and
/// coplanar_side_of_bounded_circle_3 for a point coplanar with a hull facet, which the planar faces of
/// a domain make the rule, not the exception) are exact in M on the input points; orientations,
/// lexicographic order and hence CGAL's symbolic perturbation (which only needs orientations) are
/// the kernel's, metric-independent. (A former attempt that replaced only the first predicate hung in
/// the walk: the Euclidean coplanar test then disagreed with the metric one and broke the triangulation.)
struct MetricDelaunayTraits : Kernel {
  std::array<double, 6> metric{1, 0, 0, 1, 0, 1};

  struct Side_of_oriented_sphere_3 {
    std::array<double, 6> m;
    CGAL::Oriented_side operator()(const Point_3& p, const Point_3& q, const Point_3& r, const Point_3& s,
                                   const Point_3& t) const {
      return CGAL::Oriented_side(exact_in_sphere(array(p), array(q), array(r), array(s), array(t), m));
    }
  };
  /// t (coplanar with p, q, r) against the M-circle through p, q, r in their plane: that circle is the
  /// plane's section of every M-sphere through p, q, r, so the test is the in-sphere against (p, q, r, s)
  /// for any s off the plane (exactly checked), signed by the orientation of (p, q, r, s).
  struct Coplanar_side_of_bounded_circle_3 {
    std::array<double, 6> m;
    CGAL::Bounded_side operator()(const Point_3& p, const Point_3& q, const Point_3& r, const Point_3& t) const {
      const P3 a = array(p);
      for (int axis = 0; axis < 3; ++axis) {
        P3 s = a;
        s[axis] += 1.0 + 2.0 * std::abs(a[axis]);
        const int o = orientation3(a, array(q), array(r), s);
        if (o == 0) continue;
        const int side = o > 0 ? exact_in_sphere(a, array(q), array(r), s, array(t), m)
                               : exact_in_sphere(a, array(r), array(q), s, array(t), m);
        return CGAL::Bounded_side(side);  // ON_BOUNDED_SIDE = 1 = inside
      }
      return CGAL::ON_BOUNDARY;  // p, q, r collinear: CGAL's precondition excludes it
    }
  };
  Side_of_oriented_sphere_3 side_of_oriented_sphere_3_object() const { return {metric}; }
  Coplanar_side_of_bounded_circle_3 coplanar_side_of_bounded_circle_3_object() const { return {metric}; }

  static P3 array(const Point_3& p) { return {p.x(), p.y(), p.z()}; }
};

using MetricVb = CGAL::Triangulation_vertex_base_with_info_3<std::size_t, MetricDelaunayTraits>;
using MetricCb = CGAL::Delaunay_triangulation_cell_base_3<MetricDelaunayTraits>;
using MetricDt =
    CGAL::Delaunay_triangulation_3<MetricDelaunayTraits, CGAL::Triangulation_data_structure_3<MetricVb, MetricCb>>;

}  // namespace

bool delaunay_star3(const std::vector<P3>& points, std::size_t centre, const std::array<double, 6>& metric,
                    std::vector<std::array<std::size_t, 3>>& star, bool& on_hull) {
  star.clear();
  on_hull = false;
  // The M-Delaunay triangulation of the input points themselves (exact predicates in M, see
  // MetricDelaunayTraits): no stretched or rounded coordinates.
  MetricDelaunayTraits traits;
  traits.metric = metric;
  std::vector<std::pair<Kernel::Point_3, std::size_t>> input;
  input.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    input.emplace_back(Kernel::Point_3(points[i][0], points[i][1], points[i][2]), i);
  MetricDt dt(traits);
  dt.insert(input.begin(), input.end());
  if (dt.dimension() < 3) return false;
  MetricDt::Vertex_handle v;
  for (auto it = dt.finite_vertices_begin(); it != dt.finite_vertices_end(); ++it)
    if (it->info() == centre) v = it;
  if (v == MetricDt::Vertex_handle()) return false;
  std::vector<MetricDt::Cell_handle> cells;
  dt.incident_cells(v, std::back_inserter(cells));
  for (const auto& c : cells) {
    if (dt.is_infinite(c)) {
      on_hull = true;
      continue;
    }
    const int i = c->index(v);
    std::array<std::size_t, 3> others{};
    std::size_t k = 0;
    for (int j = 0; j < 4; ++j)
      if (j != i) others[k++] = c->vertex(j)->info();
    // The cell's order (0..3) is positive; moving v to the front is i transpositions.
    if (i % 2 == 1) std::swap(others[1], others[2]);
    star.push_back(others);
  }
  return true;
}

int metric_in_sphere(const P3& p, const P3& q, const P3& r, const P3& s, const P3& t, const std::array<double, 6>& metric) {
  return exact_in_sphere(p, q, r, s, t, metric);
}

int metric_in_sphere_unfiltered(const P3& p, const P3& q, const P3& r, const P3& s, const P3& t,
                                const std::array<double, 6>& metric) {
  return unfiltered_in_sphere(p, q, r, s, t, metric);
}

int orientation3(const P3& a, const P3& b, const P3& c, const P3& d) {
  return static_cast<int>(CGAL::orientation(Kernel::Point_3(a[0], a[1], a[2]), Kernel::Point_3(b[0], b[1], b[2]),
                                            Kernel::Point_3(c[0], c[1], c[2]), Kernel::Point_3(d[0], d[1], d[2])));
}

bool segment_meets_triangle(const P3& p, const P3& q, const P3& a, const P3& b, const P3& c) {
  const Kernel::Point_3 pp(p[0], p[1], p[2]), qq(q[0], q[1], q[2]);
  if (pp == qq) return false;
  return CGAL::do_intersect(Kernel::Segment_3(pp, qq),
                            Kernel::Triangle_3(Kernel::Point_3(a[0], a[1], a[2]), Kernel::Point_3(b[0], b[1], b[2]),
                                               Kernel::Point_3(c[0], c[1], c[2])));
}

}  // namespace laguerre::core::detail
