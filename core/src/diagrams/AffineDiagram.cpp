// The two affine diagrams (Voronoi: Point2 sites, Delaunay triangulation; power: WeightedPoint sites,
// regular triangulation) share everything but the CGAL triangulation, which Traits<Site> supplies:
// its type, how a site is inserted, the (weighted) circumcentre, the nearest-site query and what makes
// a hidden site legitimate. Cells, edges and most checks are the CGAL-free detail::AffineCells.
#include "laguerre/core/diagrams/PowerDiagram.hpp"
#include "laguerre/core/diagrams/VoronoiDiagram.hpp"

#include <CGAL/Cartesian_converter.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>

#include "detail/AffineCells.hpp"
#include "detail/Validity.hpp"
#include "laguerre/core/Error.hpp"

namespace laguerre::core {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using EK = CGAL::Exact_predicates_exact_constructions_kernel;

const CGAL::Cartesian_converter<K, EK> to_exact;

template <class Site>
struct Traits;

template <>
struct Traits<Point2> {
  using Vbi = CGAL::Triangulation_vertex_base_with_info_2<SiteIndex, K>;
  using Tds = CGAL::Triangulation_data_structure_2<Vbi>;
  using RT = CGAL::Delaunay_triangulation_2<K, Tds>;
  static constexpr const char* name = "Voronoi diagram";
  static constexpr const char* non_finite = " has a non-finite coordinate";
  static constexpr const char* triangulation = "CGAL's Delaunay triangulation is not valid";
  static bool finite(const Point2& s) { return std::isfinite(s.x) && std::isfinite(s.y); }
  static WeightedPoint weighted(const Point2& s) { return {s.x, s.y, 0.0}; }
  static K::Point_2 input(const Point2& s) { return K::Point_2(s.x, s.y); }
  static K::Point_2 centre(const RT& rt, typename RT::Finite_faces_iterator f) { return rt.circumcenter(f); }
  /// The exact circumcentre rounded to doubles, for the faces whose centre the doubles overflow to inf
  /// or 0/0 (nearly collinear sites on the hull: their determinant rounds to 0).
  static Point2 exact_centre(typename RT::Finite_faces_iterator f) {
    const auto p = [&](int k) { return to_exact(f->vertex(k)->point()); };
    const EK::Point_2 c = EK().construct_circumcenter_2_object()(p(0), p(1), p(2));
    return {CGAL::to_double(c.x()), CGAL::to_double(c.y())};
  }
  static SiteIndex nearest(const RT& rt, Point2 q) { return rt.nearest_vertex(K::Point_2(q.x, q.y))->info(); }
  /// A hidden site is an exact duplicate of the visible site located at its point.
  static std::string hidden_violation(const std::vector<Point2>& sites, SiteIndex i, SiteIndex located) {
    if (located == no_site || sites[located].x != sites[i].x || sites[located].y != sites[i].y)
      return "hidden site " + std::to_string(i) + " is not a duplicate of a visible site";
    return "";
  }
};

template <>
struct Traits<WeightedPoint> {
  using Vb = CGAL::Regular_triangulation_vertex_base_2<K>;
  using Vbi = CGAL::Triangulation_vertex_base_with_info_2<SiteIndex, K, Vb>;
  using Fb = CGAL::Regular_triangulation_face_base_2<K>;
  using Tds = CGAL::Triangulation_data_structure_2<Vbi, Fb>;
  using RT = CGAL::Regular_triangulation_2<K, Tds>;
  static constexpr const char* name = "power diagram";
  static constexpr const char* non_finite = " has a non-finite coordinate or weight";
  static constexpr const char* triangulation = "CGAL's regular triangulation is not valid";
  static bool finite(const WeightedPoint& s) { return std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.w); }
  static WeightedPoint weighted(const WeightedPoint& s) { return s; }
  static RT::Weighted_point input(const WeightedPoint& s) { return RT::Weighted_point(K::Point_2(s.x, s.y), s.w); }
  static K::Point_2 centre(const RT& rt, typename RT::Finite_faces_iterator f) { return rt.weighted_circumcenter(f); }
  /// The exact weighted circumcentre rounded to doubles (see Traits<Point2>::exact_centre).
  static Point2 exact_centre(typename RT::Finite_faces_iterator f) {
    const auto p = [&](int k) { return to_exact(f->vertex(k)->point()); };
    const EK::Point_2 c = EK().construct_weighted_circumcenter_2_object()(p(0), p(1), p(2));
    return {CGAL::to_double(c.x()), CGAL::to_double(c.y())};
  }
  static SiteIndex nearest(const RT& rt, Point2 q) { return rt.nearest_power_vertex(K::Point_2(q.x, q.y))->info(); }
  /// A hidden site is hidden for a reason: its power at its own point is not smaller than the located
  /// site's (for an exact duplicate, equal).
  static std::string hidden_violation(const std::vector<WeightedPoint>& sites, SiteIndex i, SiteIndex located) {
    const Point2 p{sites[i].x, sites[i].y};
    if (located == no_site ||
        power_distance(p, sites[located]) > power_distance(p, sites[i]) + 1e-9 * (1 + std::fabs(sites[i].w)))
      return "hidden site " + std::to_string(i) + " is closer to its own point than any visible site";
    return "";
  }
};
}  // namespace

template <class Site>
struct AffineDiagram<Site>::Impl {
  using T = Traits<Site>;
  std::vector<Site> sites;
  std::vector<WeightedPoint> weighted;  // the sites as weighted points, for the shared cell code
  Box box;
  typename T::RT rt;
  std::vector<bool> hidden;
  std::vector<DiagramVertex> vertices;
  detail::AffineCells cells;
};

template <class Site>
AffineDiagram<Site>::AffineDiagram(std::vector<Site> sites, const Box& box) : impl_(std::make_unique<Impl>()) {
  using T = Traits<Site>;
  using RT = typename T::RT;
  if (!box.valid()) throw InputError(std::string(T::name) + ": the box must satisfy xmin < xmax and ymin < ymax");
  for (std::size_t i = 0; i < sites.size(); ++i)
    if (!T::finite(sites[i])) throw InputError(std::string(T::name) + ": site " + std::to_string(i) + T::non_finite);
  Impl& m = *impl_;
  m.sites = std::move(sites);
  m.box = box;
  std::vector<std::pair<decltype(T::input(m.sites[0])), SiteIndex>> input;
  input.reserve(m.sites.size());
  for (SiteIndex i = 0; i < m.sites.size(); ++i) {
    input.emplace_back(T::input(m.sites[i]), i);
    m.weighted.push_back(T::weighted(m.sites[i]));
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
      Point2 x{std::nan(""), std::nan("")};
      try {  // CGAL asserts a nonzero determinant when its assertions are on (not NDEBUG)
        const K::Point_2 c = T::centre(m.rt, f);
        x = {c.x(), c.y()};
      } catch (const CGAL::Failure_exception&) {
      }
      if (!std::isfinite(x.x) || !std::isfinite(x.y)) x = T::exact_centre(f);
      m.vertices.push_back({x, {f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}});
    }
  m.cells = detail::build_affine_cells(m.weighted, m.hidden, neighbours, box);
}

template <class Site>
AffineDiagram<Site>::~AffineDiagram() = default;
template <class Site>
AffineDiagram<Site>::AffineDiagram(AffineDiagram&&) noexcept = default;
template <class Site>
AffineDiagram<Site>& AffineDiagram<Site>::operator=(AffineDiagram&&) noexcept = default;

template <class Site>
const std::vector<Site>& AffineDiagram<Site>::sites() const {
  return impl_->sites;
}
template <class Site>
const Box& AffineDiagram<Site>::box() const {
  return impl_->box;
}
template <class Site>
int AffineDiagram<Site>::dimension() const {
  return impl_->rt.dimension();
}
template <class Site>
bool AffineDiagram<Site>::is_hidden(SiteIndex i) const {
  return impl_->hidden.at(i);
}
template <class Site>
std::vector<SiteIndex> AffineDiagram<Site>::hidden_sites() const {
  std::vector<SiteIndex> out;
  for (SiteIndex i = 0; i < impl_->hidden.size(); ++i)
    if (impl_->hidden[i]) out.push_back(i);
  return out;
}
template <class Site>
const std::vector<std::pair<SiteIndex, SiteIndex>>& AffineDiagram<Site>::dual_edges() const {
  return impl_->cells.dual;
}
template <class Site>
const std::vector<DiagramVertex>& AffineDiagram<Site>::vertices() const {
  return impl_->vertices;
}
template <class Site>
const Polygon& AffineDiagram<Site>::cell(SiteIndex i) const {
  return impl_->cells.cells.at(i);
}
template <class Site>
const std::vector<StraightEdge>& AffineDiagram<Site>::edges() const {
  return impl_->cells.edges;
}

template <class Site>
SiteIndex AffineDiagram<Site>::locate(Point2 q) const {
  if (impl_->rt.number_of_vertices() == 0) return no_site;
  return Traits<Site>::nearest(impl_->rt, q);
}

template <class Site>
bool AffineDiagram<Site>::is_valid(bool verbose) const {
  const Impl& m = *impl_;
  const std::string violation = [&]() -> std::string {
    if (!m.rt.is_valid()) return Traits<Site>::triangulation;
    std::size_t visible = 0;
    for (bool h : m.hidden) visible += h ? 0 : 1;
    if (visible != m.rt.number_of_vertices())
      return "the triangulation has " + std::to_string(m.rt.number_of_vertices()) + " vertices but " +
             std::to_string(visible) + " sites are reported visible";
    for (SiteIndex i = 0; i < m.sites.size(); ++i) {
      if (!m.hidden[i]) continue;
      const Point2 p{m.sites[i].x, m.sites[i].y};
      if (std::string why = Traits<Site>::hidden_violation(m.sites, i, locate(p)); !why.empty()) return why;
    }
    return detail::check_affine_cells(m.weighted, m.hidden, m.cells, m.vertices, m.box,
                                      [this](Point2 q) { return locate(q); });
  }();
  return detail::report_validity(violation, verbose);
}

template class AffineDiagram<Point2>;
template class AffineDiagram<WeightedPoint>;

}  // namespace laguerre::core
