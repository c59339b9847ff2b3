/// @file
/// The regular complex in R⁵ of the lifted anisotropic sites, through CGAL's dD Regular_triangulation
/// (Epick_d, exact filtered predicates). The only CGAL include of the anisotropic construction.

#include <CGAL/Epick_d.h>
#include <CGAL/Regular_triangulation.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "AnisotropicDetail.hpp"

namespace laguerre::core::detail {

namespace {
using K = CGAL::Epick_d<CGAL::Dimension_tag<5>>;
using Traits = CGAL::Regular_triangulation_traits_adapter<K>;
using Vertex = CGAL::Triangulation_vertex<Traits, SiteIndex>;
using Cell = CGAL::Triangulation_full_cell<Traits>;
using Tds = CGAL::Triangulation_data_structure<CGAL::Dimension_tag<5>, Vertex, Cell>;
using Rt = CGAL::Regular_triangulation<K, Tds>;
}  // namespace

RegularComplex regular_complex(const std::vector<AnisotropicSite>& sites, const std::vector<char>& keep) {
  RegularComplex out;
  out.neighbours.resize(sites.size());
  out.visible.assign(sites.size(), 0);
  // Insert in a row-snake order of the sites (a cheap spatial sort: each point starts its walk near
  // the previous one).
  std::vector<SiteIndex> order;
  for (SiteIndex i = 0; i < sites.size(); ++i)
    if (keep[i]) order.push_back(i);
  if (order.empty()) return out;
  double ymin = sites[order[0]].y, ymax = ymin;
  for (SiteIndex i : order) ymin = std::min(ymin, sites[i].y), ymax = std::max(ymax, sites[i].y);
  const double rows = std::max(1.0, std::floor(std::sqrt(static_cast<double>(order.size()) / 4)));
  auto row_of = [&](SiteIndex i) {
    return ymax > ymin ? std::min(rows - 1, std::floor((sites[i].y - ymin) / (ymax - ymin) * rows)) : 0.0;
  };
  std::sort(order.begin(), order.end(), [&](SiteIndex i, SiteIndex j) {
    const double ri = row_of(i), rj = row_of(j);
    if (ri != rj) return ri < rj;
    const bool odd = static_cast<long>(ri) % 2 == 1;
    if (sites[i].x != sites[j].x) return odd ? sites[i].x > sites[j].x : sites[i].x < sites[j].x;
    return i < j;
  });
  Rt rt(5);
  Rt::Vertex_handle hint;
  for (SiteIndex i : order) {
    const AnisotropicSite& s = sites[i];
    const double mx = s.a * s.x + s.b * s.y, my = s.b * s.x + s.c * s.y;
    const std::array<double, 5> c{mx, my, -s.a / 2, -s.b, -s.c / 2};
    double norm = 0;
    for (double v : c) norm += v * v;
    const double weight = norm - (s.x * mx + s.y * my);
    const Rt::Weighted_point wp(K::Point_d(c.begin(), c.end()), weight);
    const Rt::Vertex_handle v = hint == Rt::Vertex_handle() ? rt.insert(wp) : rt.insert(wp, hint);
    if (v != Rt::Vertex_handle()) v->data() = i, hint = v;
  }
  out.dimension = rt.current_dimension();
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v) out.visible[v->data()] = 1;
  const int d = rt.current_dimension();
  if (d < 1) return out;
  for (auto c = rt.finite_full_cells_begin(); c != rt.finite_full_cells_end(); ++c) {
    std::vector<SiteIndex> ids;
    for (int k = 0; k <= d; ++k) ids.push_back(c->vertex(k)->data());
    std::sort(ids.begin(), ids.end());
    for (std::size_t p = 0; p < ids.size(); ++p)
      for (std::size_t q = p + 1; q < ids.size(); ++q) {
        out.neighbours[ids[p]].push_back(ids[q]);
        out.neighbours[ids[q]].push_back(ids[p]);
        for (std::size_t r = q + 1; r < ids.size(); ++r) out.triangles.push_back({ids[p], ids[q], ids[r]});
      }
  }
  // Faces that only lie on the convex hull also belong to finite cells (every finite simplex of a
  // full-dimensional triangulation is a face of a finite full cell), so nothing is missed.
  std::sort(out.triangles.begin(), out.triangles.end());
  out.triangles.erase(std::unique(out.triangles.begin(), out.triangles.end()), out.triangles.end());
  for (auto& n : out.neighbours) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  return out;
}

}  // namespace laguerre::core::detail
