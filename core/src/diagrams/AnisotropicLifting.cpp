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

/// The sphere σ_s of R⁵ as a weighted point (AnisotropicDiagram.hpp).
Rt::Weighted_point lifted(const AnisotropicSite& s) {
  const double mx = s.a * s.x + s.b * s.y, my = s.b * s.x + s.c * s.y;
  const std::array<double, 5> c{mx, my, -s.a / 2, -s.b, -s.c / 2};
  double norm = 0;
  for (double v : c) norm += v * v;
  const double weight = norm - (s.x * mx + s.y * my);
  return Rt::Weighted_point(K::Point_d(c.begin(), c.end()), weight);
}

/// Sorts `order` in a row-snake order of the sites (a cheap spatial sort: each point starts its walk near
/// the previous one).
void snake_sort(const std::vector<AnisotropicSite>& sites, std::vector<SiteIndex>& order) {
  if (order.empty()) return;
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
}
}  // namespace

RegularComplex regular_complex(const std::vector<AnisotropicSite>& sites, const std::vector<char>& keep) {
  RegularComplex out;
  out.neighbours.resize(sites.size());
  out.visible.assign(sites.size(), 0);
  std::vector<SiteIndex> order;
  for (SiteIndex i = 0; i < sites.size(); ++i)
    if (keep[i]) order.push_back(i);
  if (order.empty()) return out;
  snake_sort(sites, order);
  Rt rt(5);
  Rt::Vertex_handle hint;
  for (SiteIndex i : order) {
    const Rt::Weighted_point wp = lifted(sites[i]);
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

struct LiftedTriangulation::Impl {
  Rt rt{5};
  std::vector<Rt::Vertex_handle> vertex;  ///< per site, its vertex (default handle: none)
  std::size_t inserted = 0;               ///< sites inserted so far (vertices or hidden)

  /// Appends the finite vertices of the finite full cells around v, v included.
  void star(Rt::Vertex_handle v, std::vector<SiteIndex>& out) const {
    std::vector<Rt::Full_cell_handle> cells;
    rt.incident_full_cells(v, std::back_inserter(cells));
    for (Rt::Full_cell_handle c : cells) {
      if (rt.is_infinite(c)) continue;
      for (int k = 0; k <= rt.current_dimension(); ++k) out.push_back(c->vertex(k)->data());
    }
  }

  std::vector<Rt::Full_cell_handle> finite_cells(SiteIndex s) const {
    std::vector<Rt::Full_cell_handle> cells, finite;
    if (s >= vertex.size() || vertex[s] == Rt::Vertex_handle() || rt.current_dimension() < 1) return finite;
    rt.incident_full_cells(vertex[s], std::back_inserter(cells));
    for (Rt::Full_cell_handle c : cells)
      if (!rt.is_infinite(c)) finite.push_back(c);
    return finite;
  }
};

LiftedTriangulation::LiftedTriangulation() : impl_(std::make_unique<Impl>()) {}
LiftedTriangulation::~LiftedTriangulation() = default;

int LiftedTriangulation::dimension() const { return impl_->rt.current_dimension(); }

std::vector<SiteIndex> LiftedTriangulation::insert(const std::vector<AnisotropicSite>& sites,
                                                   const std::vector<SiteIndex>& added, bool& all) {
  Impl& m = *impl_;
  std::vector<SiteIndex> order = added;
  snake_sort(sites, order);
  if (m.vertex.size() < sites.size()) m.vertex.resize(sites.size());
  const int dimension = m.rt.current_dimension();
  const std::size_t before = m.rt.number_of_vertices();
  std::size_t created = 0;
  std::vector<SiteIndex> changed;
  Rt::Vertex_handle hint;
  for (SiteIndex i : order) {
    const Rt::Weighted_point wp = lifted(sites[i]);
    const Rt::Vertex_handle v = hint == Rt::Vertex_handle() ? m.rt.insert(wp) : m.rt.insert(wp, hint);
    ++m.inserted;
    if (v == Rt::Vertex_handle()) continue;
    v->data() = i, hint = v, m.vertex[i] = v, ++created;
    // Every cell destroyed by this insertion had its vertices on the boundary of the conflict zone,
    // hence in a new cell around v (or hidden, which the vertex count below catches); every new edge
    // has v as an end: the sites whose neighbourhood changed are the vertices of v's star.
    if (m.rt.current_dimension() >= 1) m.star(v, changed);
  }
  all = m.rt.current_dimension() != dimension || m.rt.number_of_vertices() != before + created;
  if (all) {
    // A vertex became hidden (its handle is gone) or the dimension grew (every cell changed): renumber.
    std::fill(m.vertex.begin(), m.vertex.end(), Rt::Vertex_handle());
    changed.clear();
    for (Rt::Vertex_handle v = m.rt.vertices_begin(); v != m.rt.vertices_end(); ++v) {
      if (m.rt.is_infinite(v)) continue;
      m.vertex[v->data()] = v;
      changed.push_back(v->data());
    }
  }
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  return changed;
}

std::vector<SiteIndex> LiftedTriangulation::neighbours(SiteIndex s) const {
  std::vector<SiteIndex> out;
  const int d = impl_->rt.current_dimension();
  for (Rt::Full_cell_handle c : impl_->finite_cells(s))
    for (int k = 0; k <= d; ++k)
      if (c->vertex(k)->data() != s) out.push_back(c->vertex(k)->data());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void LiftedTriangulation::triangles_of(SiteIndex s, std::vector<std::array<SiteIndex, 3>>& out) const {
  const int d = impl_->rt.current_dimension();
  if (d < 2) return;
  std::vector<SiteIndex> others;
  for (Rt::Full_cell_handle c : impl_->finite_cells(s)) {
    others.clear();
    for (int k = 0; k <= d; ++k)
      if (c->vertex(k)->data() != s) others.push_back(c->vertex(k)->data());
    for (std::size_t p = 0; p < others.size(); ++p)
      for (std::size_t q = p + 1; q < others.size(); ++q) {
        std::array<SiteIndex, 3> t{s, others[p], others[q]};
        std::sort(t.begin(), t.end());
        out.push_back(t);
      }
  }
}

}  // namespace laguerre::core::detail
