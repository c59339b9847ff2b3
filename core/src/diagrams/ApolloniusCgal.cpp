/// @file
/// Apollonius diagram through CGAL's Apollonius_graph_hierarchy_2 (the only CGAL include of this
/// construction).

#include <CGAL/Apollonius_graph_2.h>
#include <CGAL/Apollonius_graph_filtered_traits_2.h>
#include <CGAL/Apollonius_graph_hierarchy_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>

#include <algorithm>
#include <numeric>
#include <tuple>
#include <unordered_map>

#include "ApolloniusDetail.hpp"

namespace laguerre::core {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Gt = CGAL::Apollonius_graph_filtered_traits_2<K>;
using Ag = CGAL::Apollonius_graph_hierarchy_2<Gt>;
using Key = std::tuple<double, double, double>;
}  // namespace

ApolloniusDiagram apollonius_diagram_cgal(const std::vector<ApolloniusSite>& sites) {
  ApolloniusDiagram d = detail::start_apollonius_diagram(sites, "cgal");
  Ag ag;
  // CGAL's circles have non-negative radii: shift all weights (the diagram does not change).
  double shift = 0;
  for (const ApolloniusSite& s : sites) shift = std::min(shift, s.w);
  // Equal sites (after the shift, which CGAL sees): the smallest index represents them, the others
  // are hidden.
  std::vector<SiteIndex> order(sites.size());
  std::iota(order.begin(), order.end(), SiteIndex{0});
  const auto key = [&](SiteIndex i) { return Key{sites[i].x, sites[i].y, sites[i].w - shift}; };
  std::sort(order.begin(), order.end(), [&](SiteIndex a, SiteIndex b) { return std::pair{key(a), a} < std::pair{key(b), b}; });
  order.erase(std::unique(order.begin(), order.end(), [&](SiteIndex a, SiteIndex b) { return key(a) == key(b); }),
              order.end());
  // Inserted in Hilbert order (CGAL::spatial_sort): at 10^6 uniform sites CGAL alone takes 6.2 CPU s
  // against 16.9 s in the input order (tools/bench/bench_diagrams_aw, BM_CgalApolloniusRaw*).
  std::vector<K::Point_2> points;
  points.reserve(sites.size());
  for (const ApolloniusSite& s : sites) points.emplace_back(s.x, s.y);
  CGAL::spatial_sort(order.begin(), order.end(),
                     CGAL::Spatial_sort_traits_adapter_2<K, decltype(CGAL::make_property_map(points))>(
                         CGAL::make_property_map(points)),
                     CGAL::Hilbert_sort_median_policy());
  // The site of each vertex, by its address (a vertex that a later site hides is freed, and its
  // address may be reused by a later vertex, whose insertion overwrites the entry).
  std::unordered_map<const void*, SiteIndex> of;
  of.reserve(order.size());
  for (const SiteIndex i : order) {
    const Ag::Vertex_handle v = ag.insert(Gt::Site_2(points[i], sites[i].w - shift));
    if (v != Ag::Vertex_handle()) of[&*v] = i;
  }
  std::vector<char> visible(sites.size(), 0);
  auto site_index = [&](Ag::Vertex_handle v) { return of.at(&*v); };
  for (auto v = ag.finite_vertices_begin(); v != ag.finite_vertices_end(); ++v) visible[site_index(v)] = 1;
  for (SiteIndex i = 0; i < sites.size(); ++i)
    if (!visible[i]) d.hidden.push_back(i);
  std::vector<std::pair<SiteIndex, SiteIndex>> edges;
  for (auto e = ag.finite_edges_begin(); e != ag.finite_edges_end(); ++e) {
    const Ag::Face_handle f = e->first;
    const int i = e->second;
    if (ag.dimension() == 1) {
      edges.emplace_back(site_index(f->vertex(0)), site_index(f->vertex(1)));
    } else {
      edges.emplace_back(site_index(f->vertex((i + 1) % 3)), site_index(f->vertex((i + 2) % 3)));
    }
  }
  if (ag.dimension() == 2) {
    for (auto f = ag.finite_faces_begin(); f != ag.finite_faces_end(); ++f) {
      ApolloniusVertex v;
      for (int k = 0; k < 3; ++k) v.sites[static_cast<std::size_t>(k)] = site_index(f->vertex(k));
      Gt::Site_2 circle;
      if (CGAL::assign(circle, ag.dual(Ag::Face_handle(f)))) {
        v.position = {circle.point().x(), circle.point().y()};
        v.distance = apollonius_distance(v.position, sites[v.sites[0]]);
      }
      d.vertices.push_back(v);
    }
  }
  detail::canonicalize(d, std::move(edges), false);
  return d;
}

}  // namespace laguerre::core
