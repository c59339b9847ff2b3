#include "LocalDelaunay3.hpp"

#include "laguerre/core/meshing/Metric3.hpp"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/determinant.h>

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

using EuclideanVb = CGAL::Triangulation_vertex_base_with_info_3<std::size_t, Kernel>;
using EuclideanDt = CGAL::Delaunay_triangulation_3<Kernel, CGAL::Triangulation_data_structure_3<EuclideanVb>>;

}  // namespace

bool delaunay_star3(const std::vector<P3>& points, std::size_t centre, const std::array<double, 6>& metric,
                    std::vector<std::array<std::size_t, 3>>& star, bool& on_hull) {
  star.clear();
  on_hull = false;
  // The Euclidean Delaunay triangulation of the stretched points F·p (F = M^{1/2}, rounded), whose
  // combinatorics is the M-Delaunay one up to the rounding of F·p; see the header for why not the
  // metric in-sphere on the input points.
  const Matrix3 f = square_root(Metric3{metric[0], metric[1], metric[2], metric[3], metric[4], metric[5]});
  std::vector<std::pair<Kernel::Point_3, std::size_t>> input;
  input.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const P3 q = multiply(f, points[i]);
    input.emplace_back(Kernel::Point_3(q[0], q[1], q[2]), i);
  }
  EuclideanDt dt(input.begin(), input.end());
  if (dt.dimension() < 3) return false;
  EuclideanDt::Vertex_handle v;
  for (auto it = dt.finite_vertices_begin(); it != dt.finite_vertices_end(); ++it)
    if (it->info() == centre) v = it;
  if (v == EuclideanDt::Vertex_handle()) return false;
  std::vector<EuclideanDt::Cell_handle> cells;
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
