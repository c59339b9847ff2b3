/// @file
/// Apollonius diagram through CGAL's Apollonius_graph_hierarchy_2 (the only CGAL include of this
/// construction).

#include <CGAL/Apollonius_graph_2.h>
#include <CGAL/Apollonius_graph_filtered_traits_2.h>
#include <CGAL/Apollonius_graph_hierarchy_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <map>
#include <tuple>

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
  std::map<Key, SiteIndex> index;  // equal sites: the smallest index represents them
  for (SiteIndex i = 0; i < sites.size(); ++i) {
    const ApolloniusSite& s = sites[i];
    if (!index.emplace(Key{s.x, s.y, s.w - shift}, i).second) continue;
    ag.insert(Gt::Site_2(K::Point_2(s.x, s.y), s.w - shift));
  }
  std::vector<char> visible(sites.size(), 0);
  auto site_index = [&](Ag::Vertex_handle v) {
    const Gt::Site_2& s = v->site();
    return index.at(Key{s.point().x(), s.point().y(), s.weight()});
  };
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
