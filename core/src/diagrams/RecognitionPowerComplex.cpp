/// @file
/// The power diagram of weighted points as a cell complex with rays (input of the recognition round
/// trip), through CGAL's Regular_triangulation_2.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Regular_triangulation_face_base_2.h>
#include <CGAL/Regular_triangulation_vertex_base_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>
#include <map>

#include "laguerre/core/diagrams/Recognition.hpp"

namespace laguerre::core {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<SiteIndex, K, CGAL::Regular_triangulation_vertex_base_2<K>>;
using Fb = CGAL::Regular_triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Rt = CGAL::Regular_triangulation_2<K, Tds>;
}  // namespace

CellComplex power_diagram_complex(const std::vector<WeightedPoint>& sites, std::vector<SiteIndex>* cell_sites) {
  std::vector<std::pair<K::Weighted_point_2, SiteIndex>> points;
  for (SiteIndex i = 0; i < sites.size(); ++i) {
    const WeightedPoint& s = sites[i];
    if (!std::isfinite(s.x) || !std::isfinite(s.y) || !std::isfinite(s.w))
      throw InputError("power_diagram_complex: site " + std::to_string(i) + " is not finite.");
    points.emplace_back(K::Weighted_point_2(K::Point_2(s.x, s.y), s.w), i);
  }
  Rt rt(points.begin(), points.end());
  if (rt.dimension() != 2)
    throw InputError("power_diagram_complex: the regular triangulation has dimension " +
                                std::to_string(rt.dimension()) + "; expected 2 (three visible, non-collinear sites).");
  CellComplex cx;
  std::map<Rt::Face_handle, std::size_t> vertex_of;
  for (auto f = rt.finite_faces_begin(); f != rt.finite_faces_end(); ++f) {
    const K::Point_2 c = rt.weighted_circumcenter(f);
    vertex_of[f] = cx.vertices.size();
    cx.vertices.push_back({c.x(), c.y()});
  }
  // One ray per convex-hull edge (f finite, f->neighbor(i) infinite), outward.
  std::map<std::pair<Rt::Face_handle, int>, std::size_t> ray_of;
  for (auto f = rt.finite_faces_begin(); f != rt.finite_faces_end(); ++f)
    for (int i = 0; i < 3; ++i) {
      if (!rt.is_infinite(f->neighbor(i))) continue;
      const K::Point_2 a = f->vertex((i + 1) % 3)->point().point(), b = f->vertex((i + 2) % 3)->point().point();
      // (a, b) is counter-clockwise in f, so the outside is on its right: direction rot−90(b − a).
      CellComplex::Ray r;
      r.vertex = vertex_of[f];
      r.direction = {b.y() - a.y(), -(b.x() - a.x())};
      ray_of[{Rt::Face_handle(f), i}] = cx.rays.size();
      cx.rays.push_back(r);
    }
  if (cell_sites) cell_sites->clear();
  for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v) {
    // Faces around v counter-clockwise give the cell boundary counter-clockwise.
    std::vector<Rt::Face_handle> faces;
    auto fc = rt.incident_faces(v), done = fc;
    do faces.push_back(fc); while (++fc != done);
    CellComplex::Cell cell;
    const std::size_t n = faces.size();
    std::size_t start = 0;
    bool unbounded = false;
    for (std::size_t k = 0; k < n; ++k)
      if (rt.is_infinite(faces[k]) && !rt.is_infinite(faces[(k + 1) % n])) start = (k + 1) % n, unbounded = true;
    for (std::size_t k = 0; k < n; ++k) {
      const Rt::Face_handle f = faces[(start + k) % n];
      if (rt.is_infinite(f)) break;
      cell.vertices.push_back(vertex_of[f]);
    }
    if (unbounded) {
      const Rt::Face_handle first = faces[start], last = faces[(start + cell.vertices.size() - 1) % n];
      // Incoming ray: the hull edge of `first` opposite its neighbour before it (infinite); outgoing likewise.
      const Rt::Face_handle before = faces[(start + n - 1) % n], after = faces[(start + cell.vertices.size()) % n];
      cell.ray_in = ray_of.at({first, first->index(before)});
      cell.ray_out = ray_of.at({last, last->index(after)});
    }
    cx.cells.push_back(cell);
    if (cell_sites) cell_sites->push_back(v->info());
  }
  return cx;
}

}  // namespace laguerre::core
