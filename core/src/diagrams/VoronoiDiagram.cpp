#include "laguerre/core/diagrams/VoronoiDiagram.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>
#include <stdexcept>

#include "detail/AffineCells.hpp"
#include "detail/Validity.hpp"
#include "laguerre/core/Error.hpp"

namespace laguerre::core {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vbi = CGAL::Triangulation_vertex_base_with_info_2<SiteIndex, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vbi>;
using RT = CGAL::Delaunay_triangulation_2<K, Tds>;
}  // namespace

struct VoronoiDiagram::Impl {
  std::vector<Point2> sites;
  std::vector<WeightedPoint> weighted;  // the same with weight 0, for the shared cell code
  Box box;
  RT rt;
  std::vector<bool> hidden;
  std::vector<DiagramVertex> vertices;
  detail::AffineCells cells;
};

VoronoiDiagram::VoronoiDiagram(std::vector<Point2> sites, const Box& box) : impl_(std::make_unique<Impl>()) {
  if (!box.valid()) throw InputError("Voronoi diagram: the box must satisfy xmin < xmax and ymin < ymax");
  for (std::size_t i = 0; i < sites.size(); ++i)
    if (!std::isfinite(sites[i].x) || !std::isfinite(sites[i].y))
      throw InputError("Voronoi diagram: site " + std::to_string(i) + " has a non-finite coordinate");
  Impl& m = *impl_;
  m.sites = std::move(sites);
  m.box = box;
  std::vector<std::pair<K::Point_2, SiteIndex>> input;
  input.reserve(m.sites.size());
  for (SiteIndex i = 0; i < m.sites.size(); ++i) {
    input.emplace_back(K::Point_2(m.sites[i].x, m.sites[i].y), i);
    m.weighted.push_back({m.sites[i].x, m.sites[i].y, 0.0});
  }
  m.rt.insert(input.begin(), input.end());

  const std::size_t n = m.sites.size();
  m.hidden.assign(n, true);
  for (auto v = m.rt.finite_vertices_begin(); v != m.rt.finite_vertices_end(); ++v) m.hidden[v->info()] = false;
  std::vector<std::vector<SiteIndex>> neighbours(n);
  for (auto e = m.rt.finite_edges_begin(); e != m.rt.finite_edges_end(); ++e) {
    const SiteIndex a = e->first->vertex(RT::cw(e->second))->info();
    const SiteIndex b = e->first->vertex(RT::ccw(e->second))->info();
    neighbours[a].push_back(b), neighbours[b].push_back(a);
  }
  if (m.rt.dimension() == 2)
    for (auto f = m.rt.finite_faces_begin(); f != m.rt.finite_faces_end(); ++f) {
      const K::Point_2 c = m.rt.circumcenter(f);
      m.vertices.push_back({{c.x(), c.y()}, {f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}});
    }
  m.cells = detail::build_affine_cells(m.weighted, m.hidden, neighbours, box);
}

VoronoiDiagram::~VoronoiDiagram() = default;
VoronoiDiagram::VoronoiDiagram(VoronoiDiagram&&) noexcept = default;
VoronoiDiagram& VoronoiDiagram::operator=(VoronoiDiagram&&) noexcept = default;

const std::vector<Point2>& VoronoiDiagram::sites() const { return impl_->sites; }
const Box& VoronoiDiagram::box() const { return impl_->box; }
int VoronoiDiagram::dimension() const { return impl_->rt.dimension(); }
bool VoronoiDiagram::is_hidden(SiteIndex i) const { return impl_->hidden.at(i); }
std::vector<SiteIndex> VoronoiDiagram::hidden_sites() const {
  std::vector<SiteIndex> out;
  for (SiteIndex i = 0; i < impl_->hidden.size(); ++i)
    if (impl_->hidden[i]) out.push_back(i);
  return out;
}
const std::vector<std::pair<SiteIndex, SiteIndex>>& VoronoiDiagram::dual_edges() const { return impl_->cells.dual; }
const std::vector<DiagramVertex>& VoronoiDiagram::vertices() const { return impl_->vertices; }
const Polygon& VoronoiDiagram::cell(SiteIndex i) const { return impl_->cells.cells.at(i); }
const std::vector<StraightEdge>& VoronoiDiagram::edges() const { return impl_->cells.edges; }

SiteIndex VoronoiDiagram::locate(Point2 q) const {
  if (impl_->rt.number_of_vertices() == 0) return no_site;
  return impl_->rt.nearest_vertex(K::Point_2(q.x, q.y))->info();
}

bool VoronoiDiagram::is_valid(bool verbose) const {
  const Impl& m = *impl_;
  const std::string violation = [&]() -> std::string {
  if (!m.rt.is_valid()) return "CGAL's Delaunay triangulation is not valid";
  std::size_t visible = 0;
  for (bool h : m.hidden) visible += h ? 0 : 1;
  if (visible != m.rt.number_of_vertices())
    return "the triangulation has " + std::to_string(m.rt.number_of_vertices()) + " vertices but " +
                       std::to_string(visible) + " sites are reported visible";
  // A hidden site is an exact duplicate of the visible site located at its point.
  for (SiteIndex i = 0; i < m.sites.size(); ++i) {
    if (!m.hidden[i]) continue;
    const SiteIndex l = locate(m.sites[i]);
    if (l == no_site || m.sites[l].x != m.sites[i].x || m.sites[l].y != m.sites[i].y)
      return "hidden site " + std::to_string(i) + " is not a duplicate of a visible site";
  }
  return detail::check_affine_cells(m.weighted, m.hidden, m.cells, m.vertices, m.box, [this](Point2 q) { return locate(q); });
  }();
  return detail::report_validity(violation, verbose);
}

}  // namespace laguerre::core
