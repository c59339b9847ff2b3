#include "laguerre/core/meshing/Domain3.hpp"

#include "laguerre/core/InputFile.hpp"
#include "laguerre/core/meshing/Medit.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>

namespace laguerre::core {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

Kernel::Point_3 point(const Point3& p) { return {p[0], p[1], p[2]}; }

double signed_volume(const Point3& a, const Point3& b, const Point3& c) {
  return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6;
}

}  // namespace

/// The CGAL surface and its exact inside test.
struct PolyhedralDomain::Locator {
  Mesh mesh;
  std::unique_ptr<CGAL::Side_of_triangle_mesh<Mesh, Kernel>> side;
};

PolyhedralDomain::~PolyhedralDomain() = default;
PolyhedralDomain::PolyhedralDomain(PolyhedralDomain&&) noexcept = default;
PolyhedralDomain& PolyhedralDomain::operator=(PolyhedralDomain&&) noexcept = default;

PolyhedralDomain::PolyhedralDomain(std::vector<Point3> vertices, std::vector<std::array<std::size_t, 3>> triangles,
                                   std::vector<std::size_t> lines, const std::string& source)
    : vertices_(std::move(vertices)), triangles_(std::move(triangles)), locator_(std::make_unique<Locator>()) {
  const auto where = [&](std::size_t f) {
    return f < lines.size() ? "the triangle at line " + std::to_string(lines[f]) : "triangle " + std::to_string(f + 1);
  };
  const auto fail = [&](std::size_t f, const std::string& message) -> DomainError {
    return DomainError(source, f < lines.size() ? lines[f] : 0, message);
  };
  if (triangles_.empty()) throw DomainError(source, 0, "the surface has no triangles");
  for (const Point3& p : vertices_)
    for (double c : p)
      if (!std::isfinite(c)) throw DomainError(source, 0, "a vertex coordinate is not finite");
  for (std::size_t f = 0; f < triangles_.size(); ++f) {
    const auto& t = triangles_[f];
    for (std::size_t v : t)
      if (v >= vertices_.size())
        throw fail(f, "vertex index " + std::to_string(v) + " is out of range (the surface has " +
                          std::to_string(vertices_.size()) + " vertices)");
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
        CGAL::collinear(point(vertices_[t[0]]), point(vertices_[t[1]]), point(vertices_[t[2]])))
      throw fail(f, "degenerate triangle (repeated or collinear vertices); expected three non-collinear vertices");
  }
  // Closed, manifold along edges, consistently oriented: each directed edge once, with its reverse.
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> directed;
  for (std::size_t f = 0; f < triangles_.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::size_t a = triangles_[f][static_cast<std::size_t>(k)], b = triangles_[f][static_cast<std::size_t>((k + 1) % 3)];
      const auto [it, fresh] = directed.emplace(std::make_pair(a, b), f);
      if (!fresh)
        throw fail(f, "the surface is not consistently oriented (or not manifold): " + where(f) + " and " +
                          where(it->second) + " both traverse the edge " + std::to_string(a) + "->" + std::to_string(b) +
                          "; expected the two triangles at an edge to traverse it in opposite directions");
    }
  for (const auto& [e, f] : directed)
    if (!directed.count({e.second, e.first}))
      throw fail(f, "the surface is not closed: the edge " + std::to_string(e.first) + "-" + std::to_string(e.second) +
                        " of " + where(f) + " bounds no other triangle; expected every edge in exactly two triangles");
  // Components (triangles joined across edges).
  std::vector<std::size_t> parent(triangles_.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& [e, f] : directed) parent[find(f)] = find(directed.at({e.second, e.first}));
  std::map<std::size_t, std::size_t> component_of_root;
  std::vector<std::size_t> component(triangles_.size());
  for (std::size_t f = 0; f < triangles_.size(); ++f)
    component[f] = component_of_root.emplace(find(f), component_of_root.size()).first->second;
  components_ = component_of_root.size();
  // The CGAL surface (a vertex shared by two components would be non-manifold: add_face refuses it).
  Mesh& mesh = locator_->mesh;
  std::vector<Mesh::Vertex_index> handle;
  for (const Point3& p : vertices_) handle.push_back(mesh.add_vertex(point(p)));
  std::vector<std::size_t> line_of_face;
  for (std::size_t f = 0; f < triangles_.size(); ++f) {
    const auto& t = triangles_[f];
    if (mesh.add_face(handle[t[0]], handle[t[1]], handle[t[2]]) == Mesh::null_face())
      throw fail(f, where(f) + " makes a vertex non-manifold (two surface sheets touch at a vertex)");
    line_of_face.push_back(f);
  }
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> crossings;
  PMP::self_intersections(mesh, std::back_inserter(crossings));
  if (!crossings.empty()) {
    const std::size_t f = crossings.front().first.idx(), g = crossings.front().second.idx();
    throw fail(std::min(f, g), "the surface intersects itself: " + where(std::min(f, g)) + " and " +
                                   where(std::max(f, g)) + " cross; expected a surface without self-intersections");
  }
  // Orientation: the signed volume of each component tells whether it points outwards; a component
  // inside an odd number of others bounds a cavity and must point into it (negative volume).
  locator_->side = std::make_unique<CGAL::Side_of_triangle_mesh<Mesh, Kernel>>(mesh);
  std::vector<double> volumes(components_, 0);
  for (std::size_t f = 0; f < triangles_.size(); ++f) {
    const auto& t = triangles_[f];
    volumes[component[f]] += signed_volume(vertices_[t[0]], vertices_[t[1]], vertices_[t[2]]);
  }
  std::vector<bool> flip(components_, false);
  for (std::size_t c = 0; c < components_; ++c) {
    std::size_t probe = 0;
    while (component[probe] != c) ++probe;
    const Point3& p = vertices_[triangles_[probe][0]];
    std::size_t depth = 0;  // how many other components enclose p
    for (std::size_t d = 0; d < components_; ++d) {
      if (d == c) continue;
      Mesh other;
      std::map<std::size_t, Mesh::Vertex_index> local;
      for (std::size_t f = 0; f < triangles_.size(); ++f)
        if (component[f] == d) {
          std::array<Mesh::Vertex_index, 3> h;
          for (int k = 0; k < 3; ++k) {
            const std::size_t v = triangles_[f][static_cast<std::size_t>(k)];
            auto it = local.find(v);
            if (it == local.end()) it = local.emplace(v, other.add_vertex(point(vertices_[v]))).first;
            h[static_cast<std::size_t>(k)] = it->second;
          }
          other.add_face(h[0], h[1], h[2]);
        }
      if (CGAL::Side_of_triangle_mesh<Mesh, Kernel>(other)(point(p)) == CGAL::ON_BOUNDED_SIDE) ++depth;
    }
    const bool outward = volumes[c] > 0;
    flip[c] = outward == (depth % 2 == 1);
  }
  volume_ = 0;
  for (std::size_t f = 0; f < triangles_.size(); ++f) {
    if (flip[component[f]]) std::swap(triangles_[f][1], triangles_[f][2]);
    const auto& t = triangles_[f];
    volume_ += signed_volume(vertices_[t[0]], vertices_[t[1]], vertices_[t[2]]);
  }
  if (!(volume_ > 0)) throw DomainError(source, 0, "the surface encloses no volume");
}

PolyhedralDomain PolyhedralDomain::box(double x0, double y0, double z0, double x1, double y1, double z1) {
  if (!(x0 < x1) || !(y0 < y1) || !(z0 < z1)) throw DomainError("a box needs x0 < x1, y0 < y1 and z0 < z1");
  std::vector<Point3> v;
  for (int k = 0; k < 8; ++k) v.push_back({k & 1 ? x1 : x0, k & 2 ? y1 : y0, k & 4 ? z1 : z0});
  // Two triangles per face, outward.
  return PolyhedralDomain(v, {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                              {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}});
}

DomainSide PolyhedralDomain::locate(const Point3& p) const {
  switch ((*locator_->side)(point(p))) {
    case CGAL::ON_BOUNDED_SIDE: return DomainSide::inside;
    case CGAL::ON_BOUNDARY: return DomainSide::boundary;
    default: return DomainSide::outside;
  }
}

std::array<double, 6> PolyhedralDomain::bounding_box() const {
  std::array<double, 6> b{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
  for (const auto& t : triangles_)
    for (std::size_t v : t)
      for (std::size_t k = 0; k < 3; ++k) {
        b[k] = std::min(b[k], vertices_[v][k]);
        b[k + 3] = std::max(b[k + 3], vertices_[v][k]);
      }
  return b;
}

namespace {

PolyhedralDomain read_off(const std::string& path) {
  std::ifstream in = open_input_file(path, "OFF domain file");
  std::string text;
  std::size_t line = 0;
  // Significant lines (comments and blank lines skipped), with their numbers.
  auto next = [&](std::istringstream& words) {
    while (std::getline(in, text)) {
      ++line;
      if (const auto hash = text.find('#'); hash != std::string::npos) text.resize(hash);
      if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
      words = std::istringstream(text);
      return true;
    }
    return false;
  };
  auto fail = [&](const std::string& message) { return DomainError(path, line, message); };
  std::istringstream words;
  if (!next(words)) throw fail("the file is empty; expected 'OFF'");
  std::string header;
  words >> header;
  if (header != "OFF") throw fail("expected 'OFF', found '" + header + "'");
  std::size_t nv = 0, nf = 0, ne = 0;
  if (!(words >> nv)) {  // counts may follow on the same line
    if (!next(words) || !(words >> nv >> nf >> ne)) throw fail("expected the counts 'vertices faces edges'");
  } else if (!(words >> nf >> ne)) {
    throw fail("expected the counts 'vertices faces edges'");
  }
  std::vector<Point3> vertices(nv);
  for (auto& p : vertices) {
    if (!next(words)) throw fail("the file ends after " + std::to_string(&p - vertices.data()) + " of " +
                                 std::to_string(nv) + " vertices");
    std::string w[3];
    for (int k = 0; k < 3; ++k) {
      if (!(words >> w[k])) throw fail("expected a vertex 'x y z', found '" + text + "'");
      char* end = nullptr;
      p[static_cast<std::size_t>(k)] = std::strtod(w[k].c_str(), &end);
      if (*end != '\0' || !std::isfinite(p[static_cast<std::size_t>(k)]))
        throw fail("expected a finite number in a vertex 'x y z', found '" + w[k] + "'");
    }
  }
  std::vector<std::array<std::size_t, 3>> triangles(nf);
  std::vector<std::size_t> lines(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    if (!next(words)) throw fail("the file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    long n = 0;
    if (!(words >> n)) throw fail("expected a face '3 i j k', found '" + text + "'");
    if (n != 3) throw fail("expected a triangle '3 i j k', found a face with " + std::to_string(n) + " vertices");
    for (auto& v : triangles[f]) {
      long i = -1;
      if (!(words >> i)) throw fail("expected a face '3 i j k', found '" + text + "'");
      if (i < 0 || static_cast<std::size_t>(i) >= nv)
        throw fail("vertex index " + std::to_string(i) + " is out of range 0.." + std::to_string(nv - 1));
      v = static_cast<std::size_t>(i);
    }
    lines[f] = line;
  }
  return PolyhedralDomain(std::move(vertices), std::move(triangles), std::move(lines), path);
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

PolyhedralDomain read_polyhedral_domain(const std::string& path) {
  if (ends_with(path, ".off") || ends_with(path, ".OFF")) return read_off(path);
  if (ends_with(path, ".mesh")) {
    TetMesh surface = read_medit_tet_mesh(path);
    return PolyhedralDomain(std::move(surface.points), std::move(surface.triangles), std::move(surface.triangle_lines),
                            path);
  }
  throw DomainError(path, 0, "expected a 3D domain file ending in .off or .mesh");
}

bool is_3d_domain_file(const std::string& path) {
  if (ends_with(path, ".off") || ends_with(path, ".OFF")) return true;
  return ends_with(path, ".mesh") && medit_dimension(path) == 3;
}

}  // namespace laguerre::core
