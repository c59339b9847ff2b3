#include "LocalDelaunay.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

namespace laguerre::core::detail {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
}  // namespace

void delaunay_fan(const std::vector<std::array<double, 2>>& points, std::size_t centre,
                  std::vector<std::array<std::size_t, 2>>& fan, bool& on_hull) {
  fan.clear();
  on_hull = true;
  std::vector<std::pair<Kernel::Point_2, std::size_t>> input;
  input.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) input.emplace_back(Kernel::Point_2(points[i][0], points[i][1]), i);
  Delaunay dt(input.begin(), input.end());
  if (dt.dimension() < 2) return;
  Delaunay::Vertex_handle v;
  for (auto it = dt.finite_vertices_begin(); it != dt.finite_vertices_end(); ++it)
    if (it->info() == centre) v = it;
  if (v == Delaunay::Vertex_handle()) return;  // a duplicate of another point: no fan
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
      fan.push_back({f->vertex(Delaunay::ccw(i))->info(), f->vertex(Delaunay::cw(i))->info()});
    }
  } while (++f != first);
}

}  // namespace laguerre::core::detail
