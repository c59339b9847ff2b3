#include "LocalDelaunay3.hpp"


#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/determinant.h>

#include <cmath>

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

int exact_in_sphere(const P3& p, const P3& q, const P3& r, const P3& s, const P3& t, const std::array<double, 6>& m) {
  {
    CGAL::Protect_FPU_rounding<true> protect;
    const CGAL::Uncertain<CGAL::Sign> sign = CGAL::sign(in_sphere_determinant<CGAL::Interval_nt<false>>(p, q, r, s, t, m));
    if (CGAL::is_certain(sign)) return static_cast<int>(CGAL::get_certain(sign));
  }
  return static_cast<int>(CGAL::sign(in_sphere_determinant<CGAL::Exact_rational>(p, q, r, s, t, m)));
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
