#include "laguerre/core/meshing/StarMesher3.hpp"

#include "detail/BucketGrid.hpp"
#include "detail/LocalDelaunay3.hpp"
#include "detail/StarRefinement.hpp"
#include "laguerre/core/random/Random.hpp"

#include <algorithm>
#include <limits>
#include <cmath>
#include <map>
#include <queue>
#include <set>
#include <tuple>

namespace laguerre::core {

namespace {

using Index = std::uint32_t;
using P3 = std::array<double, 3>;
using Key = std::array<Index, 4>;  // a tetrahedron's sorted vertices

P3 sub(const P3& a, const P3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
P3 add(const P3& a, const P3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
P3 scale(const P3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
double dot(const P3& a, const P3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
P3 cross(const P3& a, const P3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const P3& a) { return std::sqrt(dot(a, a)); }

Key sorted_key(Index v, Index a, Index b, Index c) {
  Key k{v, a, b, c};
  std::sort(k.begin(), k.end());
  return k;
}

/// Circumcentre of the triangle (a, b, c) of space, in its plane.
P3 triangle_circumcentre(const P3& a, const P3& b, const P3& c) {
  const P3 u = sub(b, a), w = sub(c, a), n = cross(u, w);
  const double d = 2 * dot(n, n);
  return add(a, scale(add(scale(cross(n, u), dot(w, w)), scale(cross(w, n), dot(u, u))), 1 / d));
}

/// Circumcentre of the tetrahedron (0, a, b, c) (relative coordinates).
P3 tet_circumcentre(const P3& a, const P3& b, const P3& c) {
  const double d = 2 * dot(a, cross(b, c));
  return scale(add(add(scale(cross(b, c), dot(a, a)), scale(cross(c, a), dot(b, b))), scale(cross(a, b), dot(c, c))),
               1 / d);
}

std::array<double, 6> entries(const Metric3& m) { return {m.xx, m.xy, m.xz, m.yy, m.yz, m.zz}; }

/// Half-extents of the M-ball of radius r: r·√((M⁻¹)_kk).
P3 ball_extent(const Metric3& m, double r) {
  const double c00 = m.yy * m.zz - m.yz * m.yz, c11 = m.xx * m.zz - m.xz * m.xz, c22 = m.xx * m.yy - m.xy * m.xy;
  const double det = m.xx * c00 - m.xy * (m.xy * m.zz - m.yz * m.xz) + m.xz * (m.xy * m.yz - m.yy * m.xz);
  return {r * std::sqrt(c00 / det), r * std::sqrt(c11 / det), r * std::sqrt(c22 / det)};
}

/// A tetrahedron (v, a, b, c) of S_v, positively oriented, with its M_v measures.
struct StarTet {
  Index a, b, c;
  Key key;           ///< sorted_key(v, a, b, c): what the other stars are searched for
  P3 centre;         ///< M_v-circumcentre (plane coordinates)
  double radius;     ///< M_v-circumradius
  double shortest;   ///< shortest M_v-edge
  double sliverity;  ///< M_v-volume / shortest³
};

/// A facet (v, a, b) of S_v on the boundary of Ω, with its M_v-equatorial ball.
struct BoundaryFacet {
  Index a, b;
  int plane;         ///< the face plane it lies on
  P3 centre;         ///< M_v-circumcentre of (v, a, b), in its plane (plane coordinates)
  double radius;     ///< M_v-circumradius of (v, a, b)
};

struct Star {
  std::vector<StarTet> tets;
  std::vector<BoundaryFacet> boundary;
  std::uint32_t version = 0;
  double query_radius = 0;
  bool open = false;  ///< the link of v in the kept tetrahedra is not closed
  std::size_t open_tet = 0;  ///< then: a kept tetrahedron on an unmatched facet
  P3 lo{1, 1, 1}, hi{0, 0, 0};  ///< registered zone box (empty if lo > hi)
  std::uint32_t zone = 0;       ///< generation of the zone's registrations (older ones are dead)
  std::vector<std::pair<Index, double>> gamma;  ///< γ(M_v, M_w) per neighbour w of the last evaluation, by w
};

/// A registration of S_v's zone box in a cell of the zones grid, alive while `generation` is S_v's.
struct ZoneEntry {
  Index v;
  std::uint32_t generation;
};

struct Crease {
  Index a, b;
  bool alive = true;
  P3 lo{}, hi{};
};

/// A face plane of the domain: the input triangles on one oriented plane.
struct Plane {
  std::array<P3, 3> ref;                       ///< an input triangle of it (outward)
  std::vector<std::array<P3, 3>> triangles;    ///< all its input triangles
  int drop = 2;                                ///< the coordinate dropped to project it (dominant normal axis)
};

constexpr Index kFacet = std::numeric_limits<Index>::max();  ///< Request::c of a boundary-facet request

struct Request {
  int rule;
  double radius;
  Index v, a, b, c;  ///< c == kFacet: the boundary facet (v, a, b)
  std::uint32_t version;
  bool operator<(const Request& o) const {  // top = lowest rule, then largest radius
    if (rule != o.rule) return rule > o.rule;
    if (radius != o.radius) return radius < o.radius;
    return std::tie(v, a, b, c) > std::tie(o.v, o.a, o.b, o.c);
  }
};

std::pair<Index, Index> edge_key(Index a, Index b) { return {std::min(a, b), std::max(a, b)}; }

Point2 project(const P3& p, int drop) {
  return drop == 0 ? Point2{p[1], p[2]} : drop == 1 ? Point2{p[2], p[0]} : Point2{p[0], p[1]};
}

/// The closed projected triangle abc contains q (exact orientations).
bool in_triangle(Point2 q, Point2 a, Point2 b, Point2 c) {
  const Sign s0 = orientation(a, b, q), s1 = orientation(b, c, q), s2 = orientation(c, a, q);
  const bool has_neg = s0 == Sign::negative || s1 == Sign::negative || s2 == Sign::negative;
  const bool has_pos = s0 == Sign::positive || s1 == Sign::positive || s2 == Sign::positive;
  return !(has_neg && has_pos);
}

/// The face planes of a domain (coplanar input triangles with the same outward normal grouped).
std::vector<Plane> face_planes(const PolyhedralDomain& domain) {
  std::vector<Plane> planes;
  const auto& v = domain.vertices();
  for (const auto& t : domain.triangles()) {
    const std::array<P3, 3> tri{v[t[0]], v[t[1]], v[t[2]]};
    const P3 n = cross(sub(tri[1], tri[0]), sub(tri[2], tri[0]));
    Plane* found = nullptr;
    for (Plane& p : planes) {
      const P3 m = cross(sub(p.ref[1], p.ref[0]), sub(p.ref[2], p.ref[0]));
      bool coplanar = dot(n, m) > 0;
      for (const P3& q : tri) coplanar = coplanar && detail::orientation3(p.ref[0], p.ref[1], p.ref[2], q) == 0;
      if (coplanar) found = &p;
    }
    if (!found) {
      planes.push_back({tri, {}, 2});
      found = &planes.back();
      const double ax = std::abs(n[0]), ay = std::abs(n[1]), az = std::abs(n[2]);
      found->drop = ax >= ay && ax >= az ? 0 : ay >= az ? 1 : 2;
    }
    found->triangles.push_back(tri);
  }
  return planes;
}

/// Whether the triangle (a, b, c), whose vertices lie on `plane`, lies on its face: its centroid is in
/// one of the plane's input triangles (projected, exact orientations on the rounded centroid).
bool on_face(const Plane& plane, const P3& a, const P3& b, const P3& c) {
  const Point2 g = project(scale(add(add(a, b), c), 1.0 / 3), plane.drop);
  for (const auto& t : plane.triangles)
    if (in_triangle(g, project(t[0], plane.drop), project(t[1], plane.drop), project(t[2], plane.drop))) return true;
  return false;
}

class StarMesher3 : detail::StarRefinement<StarMesher3, Request, Index> {
public:
  StarMesher3(const PolyhedralDomain& domain, const MetricField3& field, const StarMesh3Options& options)
      : domain_(domain), field_(field), options_(options), rng_{options.seed}, box_(expanded_box(domain)),
        planes_(face_planes(domain)), sites_grid_(box_, 48), creases_grid_(box_, 24), zones_grid_(box_, 24) {}

  StarMesh3Result run() {
    for (const Point3& p : domain_.vertices()) add_site(p, INFINITY);
    // Constraint edges: input edges between non-coplanar triangles (exact).
    std::map<std::pair<Index, Index>, std::vector<std::size_t>> faces_at;
    const auto& tris = domain_.triangles();
    for (std::size_t f = 0; f < tris.size(); ++f)
      for (std::size_t k = 0; k < 3; ++k)
        faces_at[edge_key(static_cast<Index>(tris[f][k]), static_cast<Index>(tris[f][(k + 1) % 3]))].push_back(f);
    for (const auto& [e, faces] : faces_at) {
      const auto& t = tris[faces[0]];
      Index opposite = 0;
      for (std::size_t w : tris[faces[1]])
        if (w != e.first && w != e.second) opposite = static_cast<Index>(w);
      if (detail::orientation3(points_[t[0]], points_[t[1]], points_[t[2]], points_[opposite]) != 0)
        add_crease(e.first, e.second);
    }
    for (Index s = 0; s < creases_.size(); ++s) check_crease(s);

    return refine_until_done<StarMesh3Result>(options_.max_vertices, 2, {"tetrahedra", "tetrahedralization"});
  }

private:
  friend detail::StarRefinement<StarMesher3, Request, Index>;

  // --- the hooks of detail::StarRefinement -------------------------------------------------------

  std::size_t site_count() const { return points_.size(); }
  std::string stop_reason() const { return {}; }
  bool split_queued_constraint() {
    if (crease_queue_.empty()) return false;
    const Index s = crease_queue_.back();
    crease_queue_.pop_back();
    if (creases_[s].alive && crease_is_bad(s)) split_crease(s);
    return true;
  }
  std::uint32_t star_version(Index v) const { return stars_[v].version; }
  bool last_resort() { return false; }
  std::string check(const StarMesh3Result& result) const { return check_tetrahedralization(result.mesh, domain_); }

  static std::array<double, 6> expanded_box(const PolyhedralDomain& d) {
    auto b = d.bounding_box();
    const double pad = 1e-6 * std::max({b[3] - b[0], b[4] - b[1], b[5] - b[2]});
    for (std::size_t k = 0; k < 3; ++k) b[k] -= pad, b[k + 3] += pad;
    return b;
  }

  /// Whether a site sits exactly at p.
  bool is_site(const P3& p) const {
    for (Index w : sites_grid_.cell_of(p))
      if (points_[w] == p) return true;
    return false;
  }

  Index add_site(const P3& p, double hint) {
    LAGUERRE_ASSERT(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])
                    );
    const Index v = static_cast<Index>(points_.size());
    points_.push_back(p);
    hint_.push_back(hint);
    const Metric3 m = field_.at(p[0], p[1], p[2]);
    metrics_.push_back(m);
    roots_.push_back(square_root(m));
    stars_.emplace_back();
    is_dirty_.push_back(false);
    std::vector<int> on;
    for (std::size_t k = 0; k < planes_.size(); ++k)
      if (detail::orientation3(planes_[k].ref[0], planes_[k].ref[1], planes_[k].ref[2], p) == 0) on.push_back(static_cast<int>(k));
    planes_of_.push_back(std::move(on));
    if (options_.progress && v % 1000 == 0 && v > 0) options_.progress(v);
    sites_grid_.add_box(p, p, v);
    mark_dirty(v);
    for_zones_at(p, [&](Index w) {
      if (!is_dirty_[w] && in_conflict_zone(w, p)) mark_dirty(w);
    });
    creases_grid_.for_box(p, p, [&](Index s) {
      if (creases_[s].alive && crease_encroached_by(s, v)) crease_queue_.push_back(s);
    });
    return v;
  }

  bool in_conflict_zone(Index w, const P3& p) const {
    for (const StarTet& t : stars_[w].tets)
      if (metric_length(metrics_[w], sub(p, t.centre)) < t.radius) return true;
    return false;
  }

  // --- constraint edges ----------------------------------------------------------------------------

  void add_crease(Index a, Index b) {
    const Index s = static_cast<Index>(creases_.size());
    const P3 mid = scale(add(points_[a], points_[b]), 0.5);
    P3 lo = mid, hi = mid;
    for (Index e : {a, b}) {
      const P3 ext = ball_extent(metrics_[e], metric_length(metrics_[e], sub(points_[a], mid)) * (1 + 1e-9));
      for (std::size_t k = 0; k < 3; ++k) lo[k] = std::min(lo[k], mid[k] - ext[k]), hi[k] = std::max(hi[k], mid[k] + ext[k]);
    }
    creases_.push_back({a, b, true, lo, hi});
    creases_grid_.add_box(lo, hi, s);
  }

  /// q strictly inside the diametral ball of crease s in the metric of an endpoint or `mq`.
  bool crease_encroached(Index s, const P3& q, const Metric3& mq) const {
    const Crease& c = creases_[s];
    const P3 mid = scale(add(points_[c.a], points_[c.b]), 0.5);
    for (const Metric3* m : std::array<const Metric3*, 3>{&metrics_[c.a], &metrics_[c.b], &mq})
      if (metric_length(*m, sub(q, mid)) < metric_length(*m, sub(points_[c.a], mid)) * (1 - 1e-12)) return true;
    return false;
  }

  bool crease_encroached_by(Index s, Index w) const {
    return w != creases_[s].a && w != creases_[s].b && crease_encroached(s, points_[w], metrics_[w]);
  }

  bool crease_is_bad(Index s) const {
    const Crease& c = creases_[s];
    for (Index e : {c.a, c.b})
      if (metric_length(metrics_[e], sub(points_[c.b], points_[c.a])) > 2 * options_.size_bound) return true;
    if (distortion(metrics_[c.a], metrics_[c.b]) >= options_.distortion_bound) return true;
    bool bad = false;
    sites_grid_.for_box(c.lo, c.hi, [&](Index w) { bad = bad || crease_encroached_by(s, w); });
    return bad;
  }

  void check_crease(Index s) {
    if (crease_is_bad(s)) crease_queue_.push_back(s);
  }

  /// Splits crease s at its midpoint (exact for dyadic coordinates; see the file comment).
  void split_crease(Index s) {
    ++stats_.edge_splits;
    Crease& c = creases_[s];
    c.alive = false;
    creases_grid_.remove_box(c.lo, c.hi, s);
    const Index a = c.a, b = c.b;
    const double length = metric_length(metrics_[a], sub(points_[b], points_[a]));
    const Index m = add_site(scale(add(points_[a], points_[b]), 0.5), 2 * length);
    const Index s1 = static_cast<Index>(creases_.size());
    add_crease(a, m);
    add_crease(m, b);
    check_crease(s1);
    check_crease(s1 + 1);
  }

  // --- stars ---------------------------------------------------------------------------------------

  /// The face plane the triangle (v, x, y) lies on, or −1.
  int boundary_plane(Index v, Index x, Index y) const {
    for (int k : planes_of_[v]) {
      const auto& px = planes_of_[x];
      const auto& py = planes_of_[y];
      if (std::find(px.begin(), px.end(), k) == px.end() || std::find(py.begin(), py.end(), k) == py.end()) continue;
      if (on_face(planes_[static_cast<std::size_t>(k)], points_[v], points_[x], points_[y])) return k;
    }
    return -1;
  }

  void update_star(Index v) {
    ++stats_.star_updates;
    Star& star = stars_[v];
    const P3 p = points_[v];
    const Matrix3& f = roots_[v];
    const Metric3& m = metrics_[v];
    double r = star.query_radius > 0 ? star.query_radius : hint_[v];
    std::vector<Index> ids;
    std::vector<P3> local;
    std::vector<std::array<std::size_t, 3>> raw;
    std::vector<StarTet> kept;
    std::vector<BoundaryFacet> boundary;
    bool closed = false;
    std::size_t open_tet = 0;
    double needed = 0;
    while (true) {
      ids.clear();
      local.clear();
      std::size_t centre = 0;
      const P3 ext = std::isfinite(r) ? ball_extent(m, r) : P3{INFINITY, INFINITY, INFINITY};
      sites_grid_.for_box(sub(p, ext), add(p, ext), [&](Index w) {
        if (metric_length(m, sub(points_[w], p)) > r) return;
        if (w == v) centre = ids.size();
        ids.push_back(w);
        local.push_back(points_[w]);
      });
      bool everything = true;
      for (int c = 0; c < 8; ++c) {
        const P3 corner{box_[c & 1 ? 3 : 0], box_[c & 2 ? 4 : 1], box_[c & 4 ? 5 : 2]};
        everything = everything && metric_length(m, sub(corner, p)) <= r;
      }
      bool on_hull = false;
      const bool spatial = ids.size() >= 4 && detail::delaunay_star3(local, centre, entries(m), raw, on_hull);
      kept.clear();
      boundary.clear();
      needed = 0;
      closed = false;
      if (spatial) {
        std::map<std::pair<Index, Index>, int> facet_plane;  // v-facet -> face plane or −1
        const std::vector<std::int8_t> side = classify(v, ids, raw, facet_plane);
        std::map<std::pair<Index, Index>, int> count;
        for (std::size_t k = 0; k < raw.size(); ++k) {
          if (side[k] <= 0) continue;
          const Index a = ids[raw[k][0]], b = ids[raw[k][1]], c = ids[raw[k][2]];
          // Defensive: the exact stars are positively oriented (LocalDelaunay3.hpp); a flat one would
          // not be a tetrahedron, and the star would stay open there and be refined.
          if (detail::orientation3(p, points_[a], points_[b], points_[c]) <= 0) continue;
          const P3 sa = multiply(f, sub(points_[a], p)), sb = multiply(f, sub(points_[b], p)), sc = multiply(f, sub(points_[c], p));
          const P3 u = tet_circumcentre(sa, sb, sc);
          const double radius = norm(u);
          // A sliver so thin that its circumcentre overflows: as if flat (the star stays open there).
          if (!std::isfinite(radius)) continue;
          needed = std::max(needed, 2 * radius);
          const double shortest = std::min({norm(sa), norm(sb), norm(sc), norm(sub(sa, sb)), norm(sub(sb, sc)), norm(sub(sa, sc))});
          const double volume = dot(sa, cross(sb, sc)) / 6;
          kept.push_back({a, b, c, sorted_key(v, a, b, c), add(p, solve(f, u)), radius, shortest,
                          volume / (shortest * shortest * shortest)});
          for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
            ++count[edge_key(x, y)];
            const int plane = facet_plane.at(edge_key(x, y));
            if (plane < 0) continue;
            const P3 o = triangle_circumcentre({0, 0, 0}, multiply(f, sub(points_[x], p)), multiply(f, sub(points_[y], p)));
            boundary.push_back({x, y, plane, add(p, solve(f, o)), norm(o)});
          }
        }
        closed = !kept.empty();
        open_tet = 0;
        for (const auto& [e, n] : count)
          if (n > 2 || (n == 1 && facet_plane.at(e) < 0)) {
            if (closed)
              for (std::size_t k = 0; k < kept.size(); ++k)
                if (edge_key(kept[k].a, kept[k].b) == e || edge_key(kept[k].b, kept[k].c) == e ||
                    edge_key(kept[k].a, kept[k].c) == e)
                  open_tet = k;
            closed = false;
          }
      }
      const bool certified = everything || (spatial && needed * (1 + 1e-9) <= r);
      if ((certified && closed) || everything) break;
      r *= 1.6;
    }
    star.tets = std::move(kept);
    star.boundary = std::move(boundary);
    star.open = !closed;
    star.open_tet = open_tet;
    star.query_radius = needed > 0 ? std::min(r, 1.2 * needed) : (std::isfinite(r) ? r : 0);
    ++star.version;
    register_zone(v);
    evaluate(v, ids);
  }

  /// Which tetrahedra of the local star of v lie in Ω (+1) or not (−1), by flood fill from the v-facets
  /// on the boundary (see the file comment of StarMesher3.hpp). Fills `facet_plane`.
  std::vector<std::int8_t> classify(Index v, const std::vector<Index>& ids, const std::vector<std::array<std::size_t, 3>>& raw,
                                    std::map<std::pair<Index, Index>, int>& facet_plane) const {
    std::vector<std::int8_t> side(raw.size(), 0);
    std::map<std::pair<Index, Index>, std::vector<std::size_t>> by_facet;
    std::vector<std::size_t> queue;
    for (std::size_t k = 0; k < raw.size(); ++k) {
      const Index t[3] = {ids[raw[k][0]], ids[raw[k][1]], ids[raw[k][2]]};
      for (int i = 0; i < 3; ++i) {
        const Index x = t[i], y = t[(i + 1) % 3], opposite = t[(i + 2) % 3];
        const auto key = edge_key(x, y);
        by_facet[key].push_back(k);
        auto it = facet_plane.find(key);
        if (it == facet_plane.end()) it = facet_plane.emplace(key, planes_of_[v].empty() ? -1 : boundary_plane(v, x, y)).first;
        if (it->second < 0) continue;
        const Plane& plane = planes_[static_cast<std::size_t>(it->second)];
        const std::int8_t s_k =
            detail::orientation3(plane.ref[0], plane.ref[1], plane.ref[2], points_[opposite]) < 0 ? 1 : -1;
        if (side[k] == 0) queue.push_back(k);
        side[k] = side[k] == 0 ? s_k : std::min(side[k], s_k);
      }
    }
    if (queue.empty()) {
      side.assign(raw.size(), 1);
      return side;
    }
    while (!queue.empty()) {
      const std::size_t k = queue.back();
      queue.pop_back();
      const Index t[3] = {ids[raw[k][0]], ids[raw[k][1]], ids[raw[k][2]]};
      for (int i = 0; i < 3; ++i) {
        const auto key = edge_key(t[i], t[(i + 1) % 3]);
        if (facet_plane.at(key) >= 0) continue;
        for (std::size_t n : by_facet[key])
          if (n != k && side[n] == 0) {
            side[n] = side[k];
            queue.push_back(n);
          }
      }
    }
    return side;
  }

  /// Calls f(w) for every star w whose registered zone box holds the point p, in registration order.
  template <class F>
  void for_zones_at(const P3& p, F&& f) const {
    for (const ZoneEntry& e : zones_grid_.cell_of(p))
      if (e.generation == stars_[e.v].zone) f(e.v);
  }

  /// (Re)registers the zone box of S_v. The former registrations are not searched for and erased
  /// (that was a linear search per cell of the box): they die by the generation, are skipped by
  /// for_zones_at and compacted away, order kept, when a cell's size reaches a power of two.
  void register_zone(Index v) {
    Star& star = stars_[v];
    ++star.zone;
    star.lo = {1, 1, 1};
    star.hi = {0, 0, 0};
    if (star.tets.empty()) return;
    P3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    for (const StarTet& t : star.tets) {
      const P3 ext = ball_extent(metrics_[v], t.radius);
      for (std::size_t k = 0; k < 3; ++k)
        lo[k] = std::min(lo[k], t.centre[k] - ext[k]), hi[k] = std::max(hi[k], t.centre[k] + ext[k]);
    }
    star.lo = lo;
    star.hi = hi;
    zones_grid_.add_box_compacting(lo, hi, ZoneEntry{v, star.zone},
                                   [&](const ZoneEntry& e) { return e.generation != stars_[e.v].zone; });
  }

  /// q strictly inside the M_v-equatorial ball of boundary facet b of S_v.
  bool facet_encroached(Index v, const BoundaryFacet& b, const P3& q) const {
    return metric_length(metrics_[v], sub(q, b.centre)) < b.radius * (1 - 1e-12);
  }

  void evaluate(Index v, const std::vector<Index>& local) {
    const Metric3& m = metrics_[v];
    Star& star = stars_[v];
    // γ(M_v, M_w) once per neighbour w (a neighbour is in several tetrahedra of the star), and kept
    // for the next evaluation of S_v: the same values distortion() gives, fewer eigen-decompositions.
    std::vector<std::pair<Index, double>> gamma;
    const auto gamma_to = [&](Index w) {
      const auto less = [](const std::pair<Index, double>& e, Index x) { return e.first < x; };
      if (const auto it = std::lower_bound(gamma.begin(), gamma.end(), w, less); it != gamma.end() && it->first == w)
        return it->second;
      const auto old = std::lower_bound(star.gamma.begin(), star.gamma.end(), w, less);
      const double g = old != star.gamma.end() && old->first == w ? old->second : distortion(m, metrics_[w]);
      gamma.insert(std::lower_bound(gamma.begin(), gamma.end(), w, less), {w, g});
      return g;
    };
    // Rule 1 on the boundary facets of the star: encroached in M_v by a site of the query (the
    // equatorial ball lies in it, see update_star), too large, or too distorted.
    for (const BoundaryFacet& b : star.boundary) {
      bool bad = b.radius > options_.size_bound || gamma_to(b.a) >= options_.distortion_bound ||
                 gamma_to(b.b) >= options_.distortion_bound;
      for (std::size_t i = 0; !bad && i < local.size(); ++i)
        if (local[i] != v && local[i] != b.a && local[i] != b.b) bad = facet_encroached(v, b, points_[local[i]]);
      if (bad) requests_.push({1, b.radius, v, b.a, b.b, kFacet, star.version});
    }
    for (const StarTet& t : star.tets) {
      if (!std::isfinite(t.radius)) continue;
      double g = std::max({gamma_to(t.a), gamma_to(t.b), gamma_to(t.c)});
      try {
        g = std::max(g, distortion(m, field_.at(t.centre[0], t.centre[1], t.centre[2])));
      } catch (const FieldError&) {
        // outside a background mesh: the vertices' metrics decide
      }
      int rule = 0;
      if (g >= options_.distortion_bound) rule = 2;
      else if (t.radius > options_.size_bound) rule = 3;
      else if (t.radius > options_.radius_edge_bound * t.shortest) rule = 4;
      else if (t.sliverity < options_.sliver_bound) rule = 5;
      if (rule) requests_.push({rule, t.radius, v, t.a, t.b, t.c, star.version});
    }
    star.gamma = std::move(gamma);
  }

  /// The tetrahedron `key` in S_w, or null.
  const StarTet* find_tet(Index w, const Key& key) const {
    for (const StarTet& t : stars_[w].tets)  // four comparisons, not memcmp
      if (t.key[0] == key[0] && t.key[1] == key[1] && t.key[2] == key[2] && t.key[3] == key[3]) return &t;
    return nullptr;
  }

  bool star_has(Index w, const Key& key) const { return find_tet(w, key) != nullptr; }

  bool consistent(Index v, const StarTet& t) const {
    const Key key = sorted_key(v, t.a, t.b, t.c);
    return star_has(t.a, key) && star_has(t.b, key) && star_has(t.c, key);
  }

  bool consistency_sweep() {
    ++stats_.consistency_sweeps;
    std::size_t found = 0;
    for (Index v = 0; v < stars_.size(); ++v)
      for (const StarTet& t : stars_[v].tets)
        if (!consistent(v, t)) {
          requests_.push({6, t.radius, v, t.a, t.b, t.c, stars_[v].version});
          ++found;
        }
    // An open star (its link does not close up) misses a tetrahedron: refine the one at the gap.
    for (Index v = 0; v < stars_.size(); ++v)
      if (stars_[v].open && !stars_[v].tets.empty()) {
        const StarTet& t = stars_[v].tets[std::min(stars_[v].open_tet, stars_[v].tets.size() - 1)];
        requests_.push({6, t.radius, v, t.a, t.b, t.c, stars_[v].version});
        ++found;
      }
    stats_.last_sweep_inconsistent = found;
    return found > 0;
  }

  /// What inserting p would do (Pick_valid, thesis §3.4): `conflicts` counts the inconsistencies it
  /// would create, decided with exact metric in-sphere tests on the input points:
  ///   - a tetrahedron (p, x, y, z) of p's star in M_p (among the sites within `radius` in M_p) whose
  ///     M_u-circumsphere holds a site strictly inside for one of u = x, y, z (it would not be in S_u);
  ///   - a tetrahedron τ of a current star S_w with p strictly inside its M_w-circumsphere (p destroys it
  ///     in S_w) but not strictly inside its M_u-circumsphere for another vertex u whose star holds τ (it
  ///     would stay in S_u), or the other way round.
  /// Both are γ₀-cospherical configurations of p with four sites (§3.3.2). `sliverity` is the worst
  /// sliverity in M_p of the new tetrahedra (Pick_valid_for_sliver). Tetrahedra whose circumball leaves
  /// the query are skipped (not certain members).
  struct PickScore {
    std::size_t conflicts = 0;
    double sliverity = INFINITY;
    bool better_than(const PickScore& o, double sliver_bound) const {
      const bool fat = sliverity >= sliver_bound, other_fat = o.sliverity >= sliver_bound;
      if (conflicts != o.conflicts) return conflicts < o.conflicts;
      if (fat != other_fat) return fat;
      return sliverity > o.sliverity;
    }
  };

  /// Whether q is strictly inside the M-circumsphere of the positively oriented tetrahedron (a, b, c, d),
  /// whose M-circumcentre and M-circumradius (floating point) are `centre` and `radius`: a float filter
  /// with a relative margin of 1e-6, trusted only for tetrahedra of sliverity at least 1e-3 (whose
  /// circumcentre is computed to far better than the margin), and the exact predicate otherwise.
  static bool strictly_inside(const Metric3& m, const P3& a, const P3& b, const P3& c, const P3& d, const P3& centre,
                              double radius, double sliverity, const P3& q) {
    if (sliverity >= 1e-3 && std::isfinite(radius)) {
      const double dist = metric_length(m, sub(q, centre));
      if (dist > radius * (1 + 1e-6)) return false;
      if (dist < radius * (1 - 1e-6)) return true;
    }
    return detail::metric_in_sphere(a, b, c, d, q, entries(m)) > 0;
  }

  PickScore score_pick(const P3& p, double radius) const {
    PickScore score;
    const Metric3 m = field_.at(p[0], p[1], p[2]);
    const Matrix3 f = square_root(m);
    std::vector<P3> local{p};
    std::vector<Index> ids{kFacet};
    const P3 ext = ball_extent(m, radius);
    sites_grid_.for_box(sub(p, ext), add(p, ext), [&](Index w) {
      if (metric_length(m, sub(points_[w], p)) <= radius) local.push_back(points_[w]), ids.push_back(w);
    });
    std::vector<std::array<std::size_t, 3>> raw;
    bool on_hull = false;
    if (local.size() >= 4 && detail::delaunay_star3(local, 0, entries(m), raw, on_hull))
      for (const auto& t : raw) {
        const P3 a = multiply(f, sub(local[t[0]], p)), b = multiply(f, sub(local[t[1]], p)), c = multiply(f, sub(local[t[2]], p));
        if (2 * norm(tet_circumcentre(a, b, c)) > radius) continue;
        const double shortest = std::min({norm(a), norm(b), norm(c), norm(sub(a, b)), norm(sub(b, c)), norm(sub(a, c))});
        const double sliverity = dot(a, cross(b, c)) / 6 / (shortest * shortest * shortest);
        score.sliverity = std::min(score.sliverity, sliverity);
        bool conflict = false;
        for (std::size_t i = 0; i < 3 && !conflict; ++i) {
          // The tetrahedron in the metric of its vertex u = ids[t[i]].
          const Index u = ids[t[i]];
          const P3 ua = multiply(roots_[u], sub(local[t[0]], p)), ub = multiply(roots_[u], sub(local[t[1]], p)),
                   uc = multiply(roots_[u], sub(local[t[2]], p));
          const P3 o = tet_circumcentre(ua, ub, uc);
          const P3 centre = add(p, solve(roots_[u], o));
          const double r = norm(o);
          // M_u's sliverity is within γ⁶ of M_p's; the filter's threshold asks for it in M_u.
          const double su = std::min({norm(ua), norm(ub), norm(uc), norm(sub(ua, ub)), norm(sub(ub, uc)), norm(sub(ua, uc))});
          const double sliverity_u = dot(ua, cross(ub, uc)) / 6 / (su * su * su);
          for (std::size_t k = 1; k < local.size() && !conflict; ++k)
            if (k != t[0] && k != t[1] && k != t[2])
              conflict = strictly_inside(metrics_[u], p, local[t[0]], local[t[1]], local[t[2]], centre, r, sliverity_u, local[k]);
        }
        score.conflicts += conflict;
      }
    // The current stars whose conflict zone may hold p.
    std::vector<Index> near;
    for_zones_at(p, [&](Index w) { near.push_back(w); });
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    for (Index w : near)
      for (const StarTet& t : stars_[w].tets) {
        if (!strictly_inside(metrics_[w], points_[w], points_[t.a], points_[t.b], points_[t.c], t.centre, t.radius,
                             t.sliverity, p))
          continue;  // the other way round is seen from S_u, whose zone holds p
        const Key key = sorted_key(w, t.a, t.b, t.c);
        for (Index u : {t.a, t.b, t.c})
          if (const StarTet* tu = find_tet(u, key);
              tu && !strictly_inside(metrics_[u], points_[u], points_[tu->a], points_[tu->b], points_[tu->c], tu->centre,
                                     tu->radius, tu->sliverity, p)) {
            ++score.conflicts;
            break;
          }
      }
    return score;
  }

  /// A random point of the M_v-ball of radius ρ around c.
  P3 pick_in_ball(Index v, const P3& c, double rho) {
    P3 u;
    do {
      u = {2 * rng_.uniform01() - 1, 2 * rng_.uniform01() - 1, 2 * rng_.uniform01() - 1};
    } while (dot(u, u) > 1);
    return add(c, solve(roots_[v], scale(u, rho)));
  }

  void refine(const Request& r) {
    if (r.c == kFacet) {
      for (const BoundaryFacet& b : stars_[r.v].boundary)
        if (b.a == r.a && b.b == r.b) {
          const BoundaryFacet facet = b;
          if (refine_facet(r.v, facet)) ++stats_.facet_splits;
          return;
        }
      return;
    }
    const StarTet* t = nullptr;
    for (const StarTet& c : stars_[r.v].tets)
      if (c.a == r.a && c.b == r.b && c.c == r.c) t = &c;
    if (!t) return;
    if (r.rule == 6 && !stars_[r.v].open && consistent(r.v, *t)) return;  // fixed meanwhile
    const StarTet tet = *t;  // insertions reallocate stars_
    const double rho = options_.picking_ratio * tet.radius;
    P3 pick = pick_in_ball(r.v, tet.centre, rho);
    if (options_.picking_tries > 1) {
      PickScore best;
      best.conflicts = std::numeric_limits<std::size_t>::max();
      P3 chosen = pick;
      for (int k = 0; k < options_.picking_tries; ++k) {
        if (k > 0) pick = pick_in_ball(r.v, tet.centre, rho);
        if (domain_.locate(pick) != DomainSide::inside) continue;  // snapped anyway
        const PickScore s = score_pick(pick, 3 * tet.radius);
        if (s.better_than(best, options_.sliver_bound)) best = s, chosen = pick;
        if (s.conflicts == 0 && (r.rule != 5 || s.sliverity >= options_.sliver_bound)) break;
        ++stats_.rejected_picks;
      }
      pick = chosen;
    }
    const P3 g = scale(add(add(points_[r.v], points_[tet.a]), add(points_[tet.b], points_[tet.c])), 0.25);
    if (!place(pick, g, 3 * tet.radius)) return;
    switch (r.rule) {
      case 2: ++stats_.distortion; break;
      case 3: ++stats_.size; break;
      case 4: ++stats_.shape; break;
      case 5: ++stats_.sliver; break;
      default: ++stats_.inconsistency; break;
    }
  }

  /// Refines the boundary facet b of S_v: its M_v-circumcentre in its plane (an axis-aligned plane's
  /// constant coordinate kept exactly), or the constraint edge that point encroaches, or, when it
  /// falls off the face, the constraint edge nearest to it. False if nothing was done.
  bool refine_facet(Index v, const BoundaryFacet& b) {
    P3 c = b.centre;
    for (std::size_t k = 0; k < 3; ++k)
      if (points_[v][k] == points_[b.a][k] && points_[v][k] == points_[b.b][k]) c[k] = points_[v][k];
    const Metric3 mc = field_.at(c[0], c[1], c[2]);
    std::vector<Index> hit;
    creases_grid_.for_box(c, c, [&](Index s) {
      if (creases_[s].alive && crease_encroached(s, c, mc)) hit.push_back(s);
    });
    if (hit.empty() && domain_.locate(c) != DomainSide::boundary) {
      double best = INFINITY;
      Index nearest = kFacet;
      for (Index s = 0; s < creases_.size(); ++s)
        if (creases_[s].alive) {
          const double d = norm(sub(scale(add(points_[creases_[s].a], points_[creases_[s].b]), 0.5), c));
          if (d < best) best = d, nearest = s;
        }
      if (nearest == kFacet) return false;
      hit.push_back(nearest);
    }
    if (!hit.empty()) {
      std::sort(hit.begin(), hit.end());
      hit.erase(std::unique(hit.begin(), hit.end()), hit.end());
      for (Index s : hit)
        if (creases_[s].alive) split_crease(s);
      return true;
    }
    if (is_site(c)) return false;
    add_site(c, 3 * b.radius);
    return true;
  }

  /// Insert or snap: a pick encroaching a constraint edge splits it, else one encroaching a boundary
  /// facet of a star whose zone holds it refines that facet, else one outside Ω refines the boundary
  /// facet crossed from g (or the nearest one); otherwise p is inserted. False when nothing was done.
  bool place(const P3& q, const P3& g, double hint) {
    const Metric3 mq = field_.at(q[0], q[1], q[2]);
    std::vector<Index> hit;
    creases_grid_.for_box(q, q, [&](Index s) {
      if (creases_[s].alive && crease_encroached(s, q, mq)) hit.push_back(s);
    });
    if (!hit.empty()) {
      ++stats_.snapped;
      std::sort(hit.begin(), hit.end());
      hit.erase(std::unique(hit.begin(), hit.end()), hit.end());
      for (Index s : hit)
        if (creases_[s].alive) split_crease(s);
      return true;
    }
    // Boundary facets of the stars whose conflict zones may hold q.
    std::vector<Index> near;
    for_zones_at(q, [&](Index w) {
      if (!stars_[w].boundary.empty()) near.push_back(w);
    });
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    for (Index w : near)
      for (const BoundaryFacet& b : stars_[w].boundary)
        if (facet_encroached(w, b, q)) {
          ++stats_.snapped;
          const BoundaryFacet facet = b;
          return refine_facet(w, facet);
        }
    if (domain_.locate(q) != DomainSide::inside) {
      double best = INFINITY;
      Index owner = kFacet;
      BoundaryFacet chosen{};
      for (Index w : near)
        for (const BoundaryFacet& b : stars_[w].boundary) {
          if (detail::segment_meets_triangle(g, q, points_[w], points_[b.a], points_[b.b])) {
            best = -1, owner = w, chosen = b;
          } else if (best >= 0) {
            const double d = norm(sub(b.centre, q));
            if (d < best) best = d, owner = w, chosen = b;
          }
        }
      if (owner == kFacet) return false;
      ++stats_.snapped;
      return refine_facet(owner, chosen);
    }
    if (is_site(q)) return false;
    add_site(q, hint);
    return true;
  }

  // --- output --------------------------------------------------------------------------------------

  void merge(StarMesh3Result& result) const {
    result.stats = stats_;
    TetMesh& mesh = result.mesh;
    mesh.points = points_;
    mesh.point_refs.assign(points_.size(), 0);
    for (Index v = 0; v < stars_.size(); ++v)
      for (const StarTet& t : stars_[v].tets)
        if (v < t.a && v < t.b && v < t.c && consistent(v, t)) {
          mesh.tetrahedra.push_back({v, t.a, t.b, t.c});
          mesh.tetrahedron_refs.push_back(0);
        }
    set_boundary_from_tetrahedra(mesh);
    result.metrics = metrics_;
  }

  const PolyhedralDomain& domain_;
  const MetricField3& field_;
  StarMesh3Options options_;
  SplitMix64 rng_;
  std::array<double, 6> box_;
  std::vector<Plane> planes_;
  detail::BucketGrid3<Index> sites_grid_, creases_grid_;
  detail::BucketGrid3<ZoneEntry> zones_grid_;
  std::vector<P3> points_;
  std::vector<Metric3> metrics_;
  std::vector<Matrix3> roots_;
  std::vector<double> hint_;
  std::vector<std::vector<int>> planes_of_;
  std::vector<Star> stars_;
  std::vector<Crease> creases_;
  std::vector<Index> crease_queue_;
  StarMesh3Stats stats_;
};

}  // namespace

StarMesh3Result mesh_with_stars(const PolyhedralDomain& domain, const MetricField3& field,
                                const StarMesh3Options& options) {
  return StarMesher3(domain, field, options).run();
}

void set_boundary_from_tetrahedra(TetMesh& mesh) {
  const auto& p = mesh.points;
  std::map<std::array<std::size_t, 3>, std::pair<std::array<std::size_t, 3>, int>> facets;  // sorted -> oriented, count
  for (const auto& q : mesh.tetrahedra)
    // Facet i, oriented with the tetrahedron on its negative (inner) side.
    for (std::size_t i = 0; i < 4; ++i) {
      std::array<std::size_t, 3> f{q[(i + 1) % 4], q[(i + 2) % 4], q[(i + 3) % 4]};
      if (detail::orientation3(p[f[0]], p[f[1]], p[f[2]], p[q[i]]) > 0) std::swap(f[1], f[2]);
      std::array<std::size_t, 3> key = f;
      std::sort(key.begin(), key.end());
      auto& entry = facets[key];
      entry.first = f;
      ++entry.second;
    }
  mesh.triangles.clear();
  mesh.triangle_refs.clear();
  mesh.triangle_lines.clear();
  for (const auto& [key, entry] : facets)
    if (entry.second == 1) {
      mesh.triangles.push_back(entry.first);
      mesh.triangle_refs.push_back(1);
    }
}

std::string check_tetrahedralization(const TetMesh& mesh, const PolyhedralDomain& domain) {
  const auto& p = mesh.points;
  // facet (sorted) -> the tetrahedra holding it and their opposite vertices
  std::map<std::array<std::size_t, 3>, std::vector<std::pair<std::size_t, std::size_t>>> facets;
  double volume = 0;
  for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t) {
    const auto& q = mesh.tetrahedra[t];
    if (detail::orientation3(p[q[0]], p[q[1]], p[q[2]], p[q[3]]) <= 0)
      return "tetrahedron " + std::to_string(t) + " is not positively oriented";
    volume += dot(sub(p[q[1]], p[q[0]]), cross(sub(p[q[2]], p[q[0]]), sub(p[q[3]], p[q[0]]))) / 6;
    for (std::size_t i = 0; i < 4; ++i) {
      std::array<std::size_t, 3> f{q[(i + 1) % 4], q[(i + 2) % 4], q[(i + 3) % 4]};
      std::sort(f.begin(), f.end());
      auto& list = facets[f];
      list.push_back({t, q[i]});
      if (list.size() > 2)
        return "facet " + std::to_string(f[0]) + "-" + std::to_string(f[1]) + "-" + std::to_string(f[2]) +
               " is in more than two tetrahedra";
    }
  }
  std::map<std::array<std::size_t, 3>, std::size_t> boundary;
  double area = 0;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    auto f = mesh.triangles[i];
    area += norm(cross(sub(p[f[1]], p[f[0]]), sub(p[f[2]], p[f[0]]))) / 2;
    std::sort(f.begin(), f.end());
    if (!boundary.emplace(f, i).second) return "boundary triangle " + std::to_string(i) + " is listed twice";
  }
  for (const auto& [f, list] : facets) {
    if (list.size() == 2) {
      if (boundary.count(f)) return "boundary triangle " + std::to_string(boundary.at(f)) + " is in two tetrahedra";
      const int s0 = detail::orientation3(p[f[0]], p[f[1]], p[f[2]], p[list[0].second]);
      const int s1 = detail::orientation3(p[f[0]], p[f[1]], p[f[2]], p[list[1].second]);
      if (s0 * s1 >= 0)
        return "tetrahedra " + std::to_string(list[0].first) + " and " + std::to_string(list[1].first) +
               " overlap across their common facet";
      continue;
    }
    const auto it = boundary.find(f);
    if (it == boundary.end())
      return "facet " + std::to_string(f[0]) + "-" + std::to_string(f[1]) + "-" + std::to_string(f[2]) +
             " bounds a single tetrahedron but is not a boundary triangle (a hole in the mesh)";
    const auto& b = mesh.triangles[it->second];
    if (detail::orientation3(p[b[0]], p[b[1]], p[b[2]], p[list[0].second]) >= 0)
      return "tetrahedron " + std::to_string(list[0].first) + " lies outside its boundary triangle " +
             std::to_string(it->second);
  }
  for (const auto& [f, i] : boundary)
    if (!facets.count(f)) return "boundary triangle " + std::to_string(i) + " is covered by no tetrahedron";
  // Every boundary triangle lies on a face of the domain (exact coplanarity, centroid on the face).
  const std::vector<Plane> planes = face_planes(domain);
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    bool on_surface = false;
    for (const Plane& plane : planes) {
      bool coplanar = true;
      for (std::size_t v : t) coplanar = coplanar && detail::orientation3(plane.ref[0], plane.ref[1], plane.ref[2], p[v]) == 0;
      if (coplanar && on_face(plane, p[t[0]], p[t[1]], p[t[2]])) on_surface = true;
    }
    if (!on_surface) return "boundary triangle " + std::to_string(i) + " does not lie on the domain's surface";
  }
  double surface = 0;
  for (const auto& t : domain.triangles()) {
    const auto& v = domain.vertices();
    surface += norm(cross(sub(v[t[1]], v[t[0]]), sub(v[t[2]], v[t[0]]))) / 2;
  }
  if (!std::isfinite(volume) || std::abs(volume - domain.volume()) > 1e-9 * domain.volume())
    return "the tetrahedra have a volume of " + std::to_string(volume) + " instead of " + std::to_string(domain.volume());
  if (std::abs(area - surface) > 1e-9 * surface)
    return "the boundary triangles have an area of " + std::to_string(area) + " instead of " + std::to_string(surface);
  return {};
}

}  // namespace laguerre::core
