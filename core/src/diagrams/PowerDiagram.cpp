#include "laguerre/core/diagrams/PowerDiagram.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>
#include <stdexcept>

#include "detail/AffineCells.hpp"
#include "detail/Validity.hpp"
#include "laguerre/core/Error.hpp"

namespace laguerre::core {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Regular_triangulation_vertex_base_2<K>;
using Vbi = CGAL::Triangulation_vertex_base_with_info_2<SiteIndex, K, Vb>;
using Fb = CGAL::Regular_triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vbi, Fb>;
using RT = CGAL::Regular_triangulation_2<K, Tds>;
using WP = RT::Weighted_point;
}  // namespace

struct PowerDiagram::Impl {
  std::vector<WeightedPoint> sites;
  Box box;
  RT rt;
  std::vector<bool> hidden;
  std::vector<DiagramVertex> vertices;
  detail::AffineCells cells;
};

PowerDiagram::PowerDiagram(std::vector<WeightedPoint> sites, const Box& box) : impl_(std::make_unique<Impl>()) {
  if (!box.valid()) throw InputError("power diagram: the box must satisfy xmin < xmax and ymin < ymax");
  for (std::size_t i = 0; i < sites.size(); ++i)
    if (!std::isfinite(sites[i].x) || !std::isfinite(sites[i].y) || !std::isfinite(sites[i].w))
      throw InputError("power diagram: site " + std::to_string(i) + " has a non-finite coordinate or weight");
  Impl& m = *impl_;
  m.sites = std::move(sites);
  m.box = box;
  std::vector<std::pair<WP, SiteIndex>> input;
  input.reserve(m.sites.size());
  for (SiteIndex i = 0; i < m.sites.size(); ++i)
    input.emplace_back(WP(K::Point_2(m.sites[i].x, m.sites[i].y), m.sites[i].w), i);
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
      const K::Point_2 c = m.rt.weighted_circumcenter(f);
      m.vertices.push_back({{c.x(), c.y()}, {f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}});
    }
  m.cells = detail::build_affine_cells(m.sites, m.hidden, neighbours, box);
}

PowerDiagram::~PowerDiagram() = default;
PowerDiagram::PowerDiagram(PowerDiagram&&) noexcept = default;
PowerDiagram& PowerDiagram::operator=(PowerDiagram&&) noexcept = default;

const std::vector<WeightedPoint>& PowerDiagram::sites() const { return impl_->sites; }
const Box& PowerDiagram::box() const { return impl_->box; }
int PowerDiagram::dimension() const { return impl_->rt.dimension(); }
bool PowerDiagram::is_hidden(SiteIndex i) const { return impl_->hidden.at(i); }
std::vector<SiteIndex> PowerDiagram::hidden_sites() const {
  std::vector<SiteIndex> out;
  for (SiteIndex i = 0; i < impl_->hidden.size(); ++i)
    if (impl_->hidden[i]) out.push_back(i);
  return out;
}
const std::vector<std::pair<SiteIndex, SiteIndex>>& PowerDiagram::dual_edges() const { return impl_->cells.dual; }
const std::vector<DiagramVertex>& PowerDiagram::vertices() const { return impl_->vertices; }
const Polygon& PowerDiagram::cell(SiteIndex i) const { return impl_->cells.cells.at(i); }
const std::vector<StraightEdge>& PowerDiagram::edges() const { return impl_->cells.edges; }

SiteIndex PowerDiagram::locate(Point2 q) const {
  if (impl_->rt.number_of_vertices() == 0) return no_site;
  return impl_->rt.nearest_power_vertex(K::Point_2(q.x, q.y))->info();
}

bool PowerDiagram::is_valid(bool verbose) const {
  const Impl& m = *impl_;
  const std::string violation = [&]() -> std::string {
  if (!m.rt.is_valid()) return "CGAL's regular triangulation is not valid";
  std::size_t visible = 0;
  for (bool h : m.hidden) visible += h ? 0 : 1;
  if (visible != m.rt.number_of_vertices())
    return "the triangulation has " + std::to_string(m.rt.number_of_vertices()) + " vertices but " +
                       std::to_string(visible) + " sites are reported visible";
  // A hidden site is hidden for a reason: its power at its own point is not smaller than the located
  // site's (for an exact duplicate, equal).
  for (SiteIndex i = 0; i < m.sites.size(); ++i) {
    if (!m.hidden[i]) continue;
    const Point2 p{m.sites[i].x, m.sites[i].y};
    const SiteIndex l = locate(p);
    if (l == no_site || power_distance(p, m.sites[l]) > power_distance(p, m.sites[i]) + 1e-9 * (1 + std::fabs(m.sites[i].w)))
      return "hidden site " + std::to_string(i) + " is closer to its own point than any visible site";
  }
  return detail::check_affine_cells(m.sites, m.hidden, m.cells, m.vertices, m.box, [this](Point2 q) { return locate(q); });
  }();
  return detail::report_validity(violation, verbose);
}

}  // namespace laguerre::core
