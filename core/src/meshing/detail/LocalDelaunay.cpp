#include "LocalDelaunay.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>

namespace laguerre::core::detail {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

/// The M-in-circle determinant of t against (p, q, r), in any number type NT built from doubles:
/// rows (u, Q(u)) for u = p − t, q − t, r − t and Q(u) = a·ux² + 2b·ux·uy + c·uy².
template <class NT>
NT in_circle_determinant(const std::array<double, 2>& p, const std::array<double, 2>& q, const std::array<double, 2>& r,
                         const std::array<double, 2>& t, const std::array<double, 3>& m) {
  const NT a(m[0]), b(m[1]), c(m[2]);
  const NT tx(t[0]), ty(t[1]);
  const NT px = NT(p[0]) - tx, py = NT(p[1]) - ty;
  const NT qx = NT(q[0]) - tx, qy = NT(q[1]) - ty;
  const NT rx = NT(r[0]) - tx, ry = NT(r[1]) - ty;
  const auto lift = [&](const NT& x, const NT& y) -> NT { return a * x * x + NT(2) * b * x * y + c * y * y; };
  return NT(lift(px, py) * (qx * ry - qy * rx) - lift(qx, qy) * (px * ry - py * rx) +
            lift(rx, ry) * (px * qy - py * qx));
}

/// The interval and exact stages of the in-circle test (the static filter failed).
[[gnu::noinline]] int in_circle_slow(const std::array<double, 2>& p, const std::array<double, 2>& q,
                                     const std::array<double, 2>& r, const std::array<double, 2>& t,
                                     const std::array<double, 3>& m) {
  {
    CGAL::Protect_FPU_rounding<true> protect;
    const CGAL::Uncertain<CGAL::Sign> s = CGAL::sign(in_circle_determinant<CGAL::Interval_nt<false>>(p, q, r, t, m));
    if (CGAL::is_certain(s)) return static_cast<int>(CGAL::get_certain(s));
  }
  return static_cast<int>(CGAL::sign(in_circle_determinant<CGAL::Exact_rational>(p, q, r, t, m)));
}

/// Sign of the M-in-circle determinant, exactly. Static filter first: the determinant in doubles and
/// the same expression with every term made positive (its "permanent"). Along any path from an input
/// to the result there are at most 9 roundings, so the error is at most γ₉·permanent ≈ 1.0e-15·
/// permanent (Higham, §3.1); 1e-14 leaves a margin for the rounding of the permanent itself. Tiny
/// permanents (underflow) and non-finite values go on to intervals, then exact rationals.
inline int exact_in_circle(const std::array<double, 2>& p, const std::array<double, 2>& q,
                           const std::array<double, 2>& r, const std::array<double, 2>& t,
                           const std::array<double, 3>& m) {
  const double px = p[0] - t[0], py = p[1] - t[1], qx = q[0] - t[0], qy = q[1] - t[1];
  const double rx = r[0] - t[0], ry = r[1] - t[1];
  const double lp = m[0] * px * px + 2 * m[1] * px * py + m[2] * py * py;
  const double lq = m[0] * qx * qx + 2 * m[1] * qx * qy + m[2] * qy * qy;
  const double lr = m[0] * rx * rx + 2 * m[1] * rx * ry + m[2] * ry * ry;
  const double det = lp * (qx * ry - qy * rx) - lq * (px * ry - py * rx) + lr * (px * qy - py * qx);
  const double ab = std::abs(m[1]);
  const double ap = m[0] * px * px + 2 * ab * std::abs(px * py) + m[2] * py * py;  // a, c > 0 (a metric)
  const double aq = m[0] * qx * qx + 2 * ab * std::abs(qx * qy) + m[2] * qy * qy;
  const double ar = m[0] * rx * rx + 2 * ab * std::abs(rx * ry) + m[2] * ry * ry;
  const double permanent = ap * (std::abs(qx * ry) + std::abs(qy * rx)) + aq * (std::abs(px * ry) + std::abs(py * rx)) +
                           ar * (std::abs(px * qy) + std::abs(py * qx));
  if (permanent > 1e-280 && permanent < 1e280 && std::abs(det) > 1e-14 * permanent) return det > 0 ? 1 : -1;
  return in_circle_slow(p, q, r, t, m);
}

/// Epick with the in-circle test of the metric M: the triangulation classes see a Delaunay
/// triangulation of the lifting xᵀMx (a convex paraboloid, so insertion and flips work unchanged).
struct MetricTraits : Kernel {
  struct Side_of_oriented_circle_2 {
    std::array<double, 3> m;
    typedef CGAL::Oriented_side result_type;
    CGAL::Oriented_side operator()(const Point_2& p, const Point_2& q, const Point_2& r, const Point_2& t) const {
      return static_cast<CGAL::Oriented_side>(
          exact_in_circle({p.x(), p.y()}, {q.x(), q.y()}, {r.x(), r.y()}, {t.x(), t.y()}, m));
    }
  };
  std::array<double, 3> metric{1, 0, 1};
  Side_of_oriented_circle_2 side_of_oriented_circle_2_object() const { return {metric}; }
};

using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, MetricTraits>;
using Fb = CGAL::Constrained_triangulation_face_base_2<MetricTraits>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<MetricTraits, Tds,
                                                       CGAL::No_constraint_intersection_requiring_constructions_tag>;

}  // namespace

int metric_in_circle(std::array<double, 2> p, std::array<double, 2> q, std::array<double, 2> r,
                     std::array<double, 2> t, std::array<double, 3> metric) {
  return exact_in_circle(p, q, r, t, metric);
}

namespace {

using DtVb = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, MetricTraits>;
using Dt = CGAL::Delaunay_triangulation_2<MetricTraits, CGAL::Triangulation_data_structure_2<DtVb>>;

/// The fan around the vertex of info `centre` of a built triangulation.
template <class T>
void extract_fan(const T& dt, std::size_t centre, std::vector<std::array<std::size_t, 2>>& fan, bool& on_hull) {
  typename T::Vertex_handle v;
  for (auto it = dt.finite_vertices_begin(); it != dt.finite_vertices_end(); ++it)
    if (it->info() == centre) v = it;
  if (v == typename T::Vertex_handle()) return;  // a duplicate of another point: no fan
  on_hull = false;
  // Start right after an infinite face if there is one, so an open fan comes out in order.
  auto start = dt.incident_faces(v), f = start;
  do {
    if (dt.is_infinite(f)) {
      on_hull = true;
      break;
    }
  } while (++f != start);
  if (on_hull) ++f;  // first face after the infinite one, counter-clockwise
  const auto first = f;
  do {
    if (!dt.is_infinite(f)) {
      const int i = f->index(v);
      fan.push_back({f->vertex(T::ccw(i))->info(), f->vertex(T::cw(i))->info()});
    }
  } while (++f != first);
}

}  // namespace

void delaunay_fan(const std::vector<std::array<double, 2>>& points, std::size_t centre, std::array<double, 3> metric,
                  const std::vector<std::array<std::size_t, 2>>& constraints,
                  std::vector<std::array<std::size_t, 2>>& fan, bool& on_hull) {
  fan.clear();
  on_hull = true;
  MetricTraits traits;
  traits.metric = metric;
  std::vector<std::pair<Kernel::Point_2, std::size_t>> input;
  input.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) input.emplace_back(Kernel::Point_2(points[i][0], points[i][1]), i);
  {
    // The common case: every constraint is already a Delaunay edge (subsegments are kept
    // unencroached on Ω's side), and the constrained Delaunay triangulation is the Delaunay one.
    Dt dt(traits);
    dt.insert(input.begin(), input.end());
    if (dt.dimension() < 2) return;
    bool conforming = true;
    if (!constraints.empty()) {
      std::vector<Dt::Vertex_handle> handle(points.size());
      for (auto it = dt.finite_vertices_begin(); it != dt.finite_vertices_end(); ++it) handle[it->info()] = it;
      for (const auto& [i, j] : constraints)
        conforming = conforming && (handle[i] == Dt::Vertex_handle() || handle[j] == Dt::Vertex_handle() ||
                                    handle[i] == handle[j] || dt.is_edge(handle[i], handle[j]));
    }
    if (conforming) {
      extract_fan(dt, centre, fan, on_hull);
      return;
    }
  }
  Cdt dt(traits);
  dt.insert(input.begin(), input.end());
  if (dt.dimension() < 2) return;
  std::vector<Cdt::Vertex_handle> handle(points.size());
  for (auto it = dt.finite_vertices_begin(); it != dt.finite_vertices_end(); ++it) handle[it->info()] = it;
  for (const auto& [i, j] : constraints)
    if (handle[i] != Cdt::Vertex_handle() && handle[j] != Cdt::Vertex_handle() && handle[i] != handle[j])
      dt.insert_constraint(handle[i], handle[j]);
  extract_fan(dt, centre, fan, on_hull);
}

}  // namespace laguerre::core::detail
