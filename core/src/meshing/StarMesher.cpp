#include "laguerre/core/meshing/StarMesher.hpp"

#include "detail/BucketGrid.hpp"
#include "detail/LocalDelaunay.hpp"
#include "detail/StarRefinement.hpp"
#include "laguerre/core/random/Random.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>
#include <set>
#include <tuple>

namespace laguerre::core {

namespace {

using Index = std::uint32_t;

/// A triangle (v, a, b) of the star of v, with its M_v-circumball.
struct StarTriangle {
  Index a, b;      ///< the other vertices, (v, a, b) counter-clockwise
  double cx, cy;   ///< M_v-circumcentre
  double radius;   ///< M_v-circumradius
  double shortest; ///< shortest M_v-edge
};

struct Star {
  std::vector<StarTriangle> triangles;
  std::uint32_t version = 0;
  double query_radius = 0;
  std::array<std::size_t, 4> cells{1, 1, 0, 0};  ///< registered zone cells: i0, j0, i1, j1 (empty if i0 > i1)
};

struct Subsegment {
  Index a, b;
  bool alive = true;
  bool two_sided = false;  ///< an interior constraint (Ω on both sides); boundary edges have Ω on their left
  std::array<std::size_t, 4> cells{};  ///< registered cells of subs_grid_: i0, j0, i1, j1
};

/// A refinement request: rule (2..5), the star's site and version, the triangle.
struct Request {
  int rule;
  double radius;
  Index v, a, b;
  std::uint32_t version;
  bool operator<(const Request& o) const {  // priority_queue: top = lowest rule, then largest radius
    if (rule != o.rule) return rule > o.rule;
    if (radius != o.radius) return radius < o.radius;
    return std::tie(v, a, b) > std::tie(o.v, o.a, o.b);
  }
};

class StarMesher : detail::StarRefinement<StarMesher, Request, Index> {
public:
  StarMesher(const Domain& domain, const MetricField& field, const StarMeshOptions& options)
      : domain_(domain), field_(field), options_(options), rng_{options.seed}, box_(expanded_box(domain)),
        sites_grid_(box_, 256), zones_grid_(box_, 128), subs_grid_(box_, 128) {}

  StarMeshResult run() {
    // Sites: every constraint endpoint once; subsegments: the constraints.
    std::map<std::pair<double, double>, Index> index_of;
    auto site_of = [&](Point2 p) {
      const auto [it, inserted] = index_of.emplace(std::make_pair(p.x, p.y), 0);
      if (inserted) it->second = add_site(p, INFINITY);
      return it->second;
    };
    const std::size_t boundary_edges = domain_.constraints().size() - domain_.segments().size();
    // A constraint endpoint may lie inside another constraint (a wall ending on the boundary): that
    // constraint is split there, so that every site on a constraint is a subsegment endpoint.
    for (const Domain::ConstraintPiece& piece : domain_.constraint_pieces())
      add_subsegment(site_of(piece.a), site_of(piece.b), piece.constraint >= boundary_edges);
    for (std::size_t s = 0; s < subs_.size(); ++s) check_subsegment(static_cast<Index>(s));

    return refine_until_done<StarMeshResult>(options_.max_vertices, 0, {"triangles", "triangulation"});
  }

private:
  friend detail::StarRefinement<StarMesher, Request, Index>;

  // --- the hooks of detail::StarRefinement -------------------------------------------------------

  std::size_t site_count() const { return points_.size(); }
  std::string stop_reason() const { return degenerate_; }
  bool split_queued_constraint() {
    if (split_queue_.empty()) return false;
    const Index s = split_queue_.back();
    split_queue_.pop_back();
    if (subs_[s].alive && subsegment_is_bad(s)) split(s);
    return true;
  }
  std::uint32_t star_version(Index v) const { return stars_[v].version; }
  bool last_resort() { return options_.no_lonely_corners && refine_lonely_corners(); }
  std::string check(const StarMeshResult& result) const { return check_triangulation(result.mesh, domain_); }

  static std::array<double, 4> expanded_box(const Domain& d) {
    auto b = d.bounding_box();
    const double pad = 1e-6 * std::max(b[2] - b[0], b[3] - b[1]);
    return {b[0] - pad, b[1] - pad, b[2] + pad, b[3] + pad};
  }

  /// Adds a site; `hint` is a first guess of its star's query radius in its metric.
  Index add_site(Point2 p, double hint) {
    const Index v = static_cast<Index>(points_.size());
    points_.push_back(p);
    hint_.push_back(hint);
    const Metric m = field_.at(p.x, p.y);
    metrics_.push_back(m);
    roots_.push_back(square_root(m));
    largest_size_.push_back(sizes_of(m)[0]);
    stars_.emplace_back();
    is_dirty_.push_back(false);
    local_stamp_.push_back(0);
    local_index_.push_back(0);
    if (options_.progress && v % 1000 == 0 && v > 0) options_.progress(v);
    sites_grid_.at(sites_grid_.ix(p.x), sites_grid_.iy(p.y)).push_back(v);
    // Stars whose conflict zone contains p change; so does p's own.
    mark_dirty(v);
    for (Index w : zones_grid_.at(zones_grid_.ix(p.x), zones_grid_.iy(p.y)))
      if (!is_dirty_[w] && in_conflict_zone(w, p)) mark_dirty(w);
    // Subsegments p may encroach.
    for (Index s : subs_grid_.at(subs_grid_.ix(p.x), subs_grid_.iy(p.y)))
      if (subs_[s].alive && encroaches(s, p)) split_queue_.push_back(s);
    return v;
  }

  bool in_conflict_zone(Index w, Point2 p) const {
    for (const StarTriangle& t : stars_[w].triangles)
      if (metric_length(metrics_[w], p.x - t.cx, p.y - t.cy) < t.radius) return true;
    return false;
  }

  // --- subsegments -------------------------------------------------------------------------------

  void add_subsegment(Index a, Index b, bool two_sided) {
    const Index s = static_cast<Index>(subs_.size());
    subs_.push_back({a, b, true, two_sided});
    sub_seen_.push_back(0);
    // Register over the bounding box of both diametral ellipses.
    const Point2 pa = points_[a], pb = points_[b];
    const double mx = (pa.x + pb.x) / 2, my = (pa.y + pb.y) / 2;
    double ex = 0, ey = 0;
    for (Index e : {a, b}) {
      const Metric& m = metrics_[e];
      const double r = metric_length(m, pa.x - mx, pa.y - my);
      const double det = m.a * m.c - m.b * m.b;
      ex = std::max(ex, r * std::sqrt(m.c / det));
      ey = std::max(ey, r * std::sqrt(m.a / det));
    }
    subs_[s].cells = {subs_grid_.ix(mx - ex), subs_grid_.iy(my - ey),  //
                      subs_grid_.ix(mx + ex), subs_grid_.iy(my + ey)};
    const auto& c = subs_[s].cells;
    for (std::size_t j = c[1]; j <= c[3]; ++j)
      for (std::size_t i = c[0]; i <= c[2]; ++i) subs_grid_.at(i, j).push_back(s);
  }

  /// p lies strictly inside the M_a- or M_b-diametral ball of subsegment s, on a side of s where the
  /// domain is: for a boundary subsegment, only points strictly on its left (Ω's side) encroach, so
  /// that across a sharp hole corner the other edge's sites do not (the cascade Ruppert's small-angle
  /// problem would otherwise cause).
  bool encroaches(Index s, Point2 p) const {
    const Subsegment& sub = subs_[s];
    const Point2 pa = points_[sub.a], pb = points_[sub.b];
    if (!sub.two_sided && orientation(pa, pb, p) != Sign::positive) return false;
    const double mx = (pa.x + pb.x) / 2, my = (pa.y + pb.y) / 2;
    for (Index e : {sub.a, sub.b}) {
      const Metric& m = metrics_[e];
      if (metric_length(m, p.x - mx, p.y - my) < metric_length(m, pa.x - mx, pa.y - my) * (1 - 1e-12)) return true;
    }
    return false;
  }

  bool subsegment_is_bad(Index s) const {
    const Subsegment& sub = subs_[s];
    const Point2 pa = points_[sub.a], pb = points_[sub.b];
    for (Index e : {sub.a, sub.b})
      if (metric_length(metrics_[e], pb.x - pa.x, pb.y - pa.y) > 2 * options_.size_bound) return true;
    if (distortion(metrics_[sub.a], metrics_[sub.b]) >= options_.distortion_bound) return true;
    // Encroached by a site near its midpoint.
    const double mx = (pa.x + pb.x) / 2, my = (pa.y + pb.y) / 2;
    double reach = 0;  // Euclidean extent of the diametral ellipses: radius × largest size
    for (Index e : {sub.a, sub.b})
      reach = std::max(reach, metric_length(metrics_[e], pa.x - mx, pa.y - my) * largest_size_[e]);
    bool bad = false;
    for_sites_in_box(mx - reach, my - reach, mx + reach, my + reach, [&](Index w) {
      if (!bad && w != sub.a && w != sub.b && encroaches(s, points_[w])) bad = true;
    });
    return bad;
  }

  void check_subsegment(Index s) {
    if (subsegment_is_bad(s)) split_queue_.push_back(s);
  }

  void split(Index s) {
    ++stats_.encroachment;
    subs_[s].alive = false;
    // Unregister it: the cells would otherwise fill up with dead subsegments that every query skips.
    const auto c = subs_[s].cells;
    for (std::size_t j = c[1]; j <= c[3]; ++j)
      for (std::size_t i = c[0]; i <= c[2]; ++i) {
        auto& cell = subs_grid_.at(i, j);
        cell.erase(std::find(cell.begin(), cell.end(), s));
      }
    const Index a = subs_[s].a, b = subs_[s].b;
    const Point2 m{(points_[a].x + points_[b].x) / 2, (points_[a].y + points_[b].y) / 2};
    const double length = metric_length(metrics_[a], points_[b].x - points_[a].x, points_[b].y - points_[a].y);
    const Index v = add_site(m, 2 * length);
    const Index s1 = static_cast<Index>(subs_.size());
    add_subsegment(a, v, subs_[s].two_sided);
    add_subsegment(v, b, subs_[s].two_sided);
    check_subsegment(s1);
    check_subsegment(s1 + 1);
  }

  template <class F>
  void for_sites_in_box(double x0, double y0, double x1, double y1, F&& f) const {
    const std::size_t i0 = sites_grid_.ix(x0), i1 = sites_grid_.ix(x1);
    const std::size_t j0 = sites_grid_.iy(y0), j1 = sites_grid_.iy(y1);
    for (std::size_t j = j0; j <= j1; ++j)
      for (std::size_t i = i0; i <= i1; ++i)
        for (Index w : sites_grid_.at(i, j)) f(w);
  }

  // --- stars ---------------------------------------------------------------------------------------

  /// Recomputes S_v from a growing neighbourhood until the fan is provably the Delaunay one (every
  /// triangle's M_v-circumball inside the queried M_v-ball, and the fan closed or its gap outside Ω).
  void update_star(Index v) {
    ++stats_.star_updates;
    Star& star = stars_[v];
    const Point2 p = points_[v];
    const Matrix2& f = roots_[v];
    const Metric& m = metrics_[v];
    // The query region is the M_v-ball of radius r around v (r in metric units): its bounding box
    // has half-extents r·√((M⁻¹)₁₁) and r·√((M⁻¹)₂₂).
    const double det_m = m.a * m.c - m.b * m.b;
    const double sx = std::sqrt(m.c / det_m), sy = std::sqrt(m.a / det_m);
    double r = star.query_radius > 0 ? star.query_radius : hint_[v];
    std::vector<Index> ids;
    std::vector<std::array<double, 2>> stretched, plane;
    std::vector<std::array<std::size_t, 2>> fan, constraints;
    std::vector<Index> near_subs, inner_subs, straddling;
    std::vector<std::int8_t> side;
    std::vector<std::pair<Index, int>> at_v;
    std::vector<StarTriangle> kept;
    const std::array<double, 3> metric{m.a, m.b, m.c};
    double needed = 0;  // the largest |circumcentre| + circumradius over the kept triangles, in the metric
    while (true) {
      ids.clear();
      stretched.clear();
      plane.clear();
      std::size_t centre = 0;
      const double ex = r * sx, ey = r * sy;
      ++local_epoch_;
      for_sites_in_box(p.x - ex, p.y - ey, p.x + ex, p.y + ey, [&](Index w) {
        const double dx = points_[w].x - p.x, dy = points_[w].y - p.y;
        const double qx = f.m00 * dx + f.m01 * dy, qy = f.m10 * dx + f.m11 * dy;
        if (qx * qx + qy * qy > r * r) return;
        if (w == v) centre = ids.size();
        local_stamp_[w] = local_epoch_;
        local_index_[w] = ids.size();
        ids.push_back(w);
        stretched.push_back({qx, qy});
        plane.push_back({points_[w].x, points_[w].y});
      });
      // The subsegments that may pass through the queried ball. Those with both endpoints in it are
      // constraints of the local triangulation, so that no triangle of the star crosses Ω's boundary
      // or a wall; one leaving the ball cannot be, but the star is not certified while it crosses one
      // of the star's triangles or is one of v's own subsegments (checked below).
      near_subs.clear();
      ++sub_epoch_;
      const std::size_t i0 = subs_grid_.ix(p.x - ex), i1 = subs_grid_.ix(p.x + ex);
      const std::size_t j0 = subs_grid_.iy(p.y - ey), j1 = subs_grid_.iy(p.y + ey);
      for (std::size_t j = j0; j <= j1; ++j)
        for (std::size_t i = i0; i <= i1; ++i)
          for (Index s : subs_grid_.at(i, j)) {
            if (!subs_[s].alive || sub_seen_[s] == sub_epoch_) continue;
            sub_seen_[s] = sub_epoch_;
            if (stretched_distance_to_subsegment(f, p, s) <= r * (1 + 1e-6)) near_subs.push_back(s);
          }
      constraints.clear();
      inner_subs.clear();
      straddling.clear();
      for (Index s : near_subs) {
        const Index a = subs_[s].a, b = subs_[s].b;
        if (local_stamp_[a] == local_epoch_ && local_stamp_[b] == local_epoch_) {
          constraints.push_back({local_index_[a], local_index_[b]});
          inner_subs.push_back(s);
        } else {
          straddling.push_back(s);
        }
      }
      // The ball covers the whole box only if the box's four corners are inside it.
      bool everything = true;
      for (const double cx : {box_[0], box_[2]})
        for (const double cy : {box_[1], box_[3]})
          everything = everything && metric_length(m, cx - p.x, cy - p.y) <= r;
      bool on_hull = true;
      ++stats_.star_attempts;
      stats_.star_points += ids.size();
      if (ids.size() >= 3) detail::delaunay_fan(plane, centre, metric, constraints, fan, on_hull);
      else fan.clear();
      bool complete = !fan.empty() || everything;
      at_v.clear();
      for (Index s : inner_subs)
        if (!subs_[s].two_sided && (subs_[s].a == v || subs_[s].b == v))
          at_v.push_back({subs_[s].a == v ? subs_[s].b : subs_[s].a, subs_[s].a == v ? 1 : -1});
      classify_fan(ids, fan, on_hull, at_v, side);
      kept.clear();
      needed = 0;
      for (std::size_t k = 0; k < fan.size(); ++k) {
        if (side[k] <= 0) continue;  // outside Ω: neither part of the star nor needed to certify it
        const auto [ia, ib] = fan[k];
        const auto& sa = stretched[ia];
        const auto& sb = stretched[ib];
        // Circumcentre of (0, sa, sb) in the stretched frame.
        const double d = 2 * (sa[0] * sb[1] - sa[1] * sb[0]);
        const double na = sa[0] * sa[0] + sa[1] * sa[1], nb = sb[0] * sb[0] + sb[1] * sb[1];
        const double ux = (sb[1] * na - sa[1] * nb) / d, uy = (sa[0] * nb - sb[0] * na) / d;
        const double radius = std::hypot(ux, uy);
        // Back to the plane: c = p + F⁻¹u.
        const double det = f.m00 * f.m11 - f.m01 * f.m10;
        const double cx = p.x + (f.m11 * ux - f.m01 * uy) / det, cy = p.y + (-f.m10 * ux + f.m00 * uy) / det;
        needed = std::max(needed, std::hypot(ux, uy) + radius);
        if (!everything && !(needed * (1 + 1e-9) <= r)) {
          complete = false;
          break;
        }
        const double shortest = std::min({std::hypot(sa[0], sa[1]), std::hypot(sb[0], sb[1]),
                                          std::hypot(sa[0] - sb[0], sa[1] - sb[1])});
        kept.push_back({ids[ia], ids[ib], cx, cy, radius, shortest});
      }
      // v's own subsegments must be constraints: they alone decide which fan triangles are in Ω.
      for (Index s : straddling)
        if (subs_[s].a == v || subs_[s].b == v) complete = false;
      for (std::size_t k = 0; complete && k < kept.size(); ++k)
        for (Index s : straddling)
          if (crosses_triangle(s, v, kept[k].a, kept[k].b)) {
            complete = false;
            break;
          }
      if (complete && on_hull && !everything && !fan.empty()) complete = gap_outside_domain(v, ids[fan.front()[0]], ids[fan.back()[1]]);
      if (complete) break;
      r *= 1.6;
    }
    // A star triangle whose circumcentre is not finite in doubles cannot be refined (its picking
    // region is undefined); exact predicates keep collinear boundary sites from forming one, so this
    // is a safeguard: stop with a status rather than feed inf/NaN to the predicates.
    for (const StarTriangle& t : kept)
      if (degenerate_.empty() && !(std::isfinite(t.cx) && std::isfinite(t.cy) && std::isfinite(t.radius)))
        degenerate_ = "a flat triangle (" + std::to_string(v) + ", " + std::to_string(t.a) + ", " +
                      std::to_string(t.b) + ") in a star has no finite circumcentre";
    star.triangles = std::move(kept);
    kept = {};
    // Next time, start from what this star needed (stars only shrink as sites are added).
    star.query_radius = needed > 0 ? std::min(r, 1.2 * needed) : r;
    ++star.version;
    register_zone(v);
    evaluate(v, m);
  }

  /// Which triangles of a constrained fan around v lie in Ω (side +1) or outside (−1), from the
  /// boundary subsegments at v alone (`at_v`: the other endpoint w, +1 for a subsegment v→w, −1 for
  /// w→v; Ω is on the left of each): the face after the edge v→w counter-clockwise is on the left of
  /// v→w, the face before it on its right, and the side only changes across such an edge. Exact and
  /// purely combinatorial (no point location on rounded points), so a sliver between a boundary
  /// edge and sites split off it by rounding is classified by the subsegments that bound it. With no
  /// boundary subsegment at v (v strictly inside Ω or on a wall), the whole fan is in Ω.
  static void classify_fan(const std::vector<Index>& ids, const std::vector<std::array<std::size_t, 2>>& fan,
                           bool open, const std::vector<std::pair<Index, int>>& at_v, std::vector<std::int8_t>& side) {
    side.assign(fan.size(), 0);
    const auto orientation_of = [&](Index w) {
      for (const auto& [u, o] : at_v)
        if (u == w) return o;
      return 0;
    };
    bool seeded = false;
    for (std::size_t k = 0; k < fan.size(); ++k) {
      const int after = orientation_of(ids[fan[k][0]]);   // edge v→a: the face is on its left
      const int before = orientation_of(ids[fan[k][1]]);  // edge v→b: the face is on its right
      int s = 0;
      if (after != 0) s = after;
      if (before != 0) s = s == 0 ? -before : std::min(s, -before);
      side[k] = static_cast<std::int8_t>(s);
      seeded = seeded || s != 0;
    }
    if (!seeded) {
      side.assign(fan.size(), 1);
      return;
    }
    const std::size_t n = fan.size();
    std::size_t first = 0;
    while (side[first] == 0) ++first;
    // Forward from the first seeded face (round the whole cycle for a closed fan), then, for an open
    // fan, backward from it to the fan's start.
    const std::size_t steps = open ? n - 1 - first : n - 1;
    for (std::size_t i = 1; i <= steps; ++i) {
      const std::size_t k = (first + i) % n, prev = (first + i - 1) % n;
      if (side[k] == 0) side[k] = side[prev];
    }
    for (std::size_t k = first; open && k-- > 0;)
      if (side[k] == 0) side[k] = side[k + 1];
  }

  /// For an open fan at v from neighbour `first` (ccw) round to `last`: the directions in the gap from
  /// `last` counter-clockwise to `first` lie outside the domain (tested on the gap's bisector).
  bool gap_outside_domain(Index v, Index first, Index last) const {
    const Point2 p = points_[v];
    const double ux = points_[first].x - p.x, uy = points_[first].y - p.y;
    const double wx = points_[last].x - p.x, wy = points_[last].y - p.y;
    const double lu = std::hypot(ux, uy), lw = std::hypot(wx, wy);
    // For unit vectors w = (cos α, sin α) and u = w turned by φ ∈ (0, 2π) counter-clockwise, w − u
    // turned by +90° is 2 sin(φ/2) times the bisector: one formula for every gap, well conditioned at
    // φ = π (a boundary vertex between two collinear neighbours, where w + u vanishes).
    const double dx = wx / lw - ux / lu, dy = wy / lw - uy / lu;
    const double bx = -dy, by = dx;
    const double lb = std::hypot(bx, by);
    if (!(lb > 0)) return false;
    const double eps = 1e-7 * std::min(lu, lw);
    return domain_.locate({p.x + eps * bx / lb, p.y + eps * by / lb}) == DomainSide::outside;
  }

  /// Subsegment s properly crosses an edge of the triangle (u, a, b), so it meets its interior (a site
  /// on a subsegment is always one of its endpoints, so s cannot enter through a vertex). Exact.
  bool crosses_triangle(Index s, Index u, Index a, Index b) const {
    const Point2 s0 = points_[subs_[s].a], s1 = points_[subs_[s].b];
    const auto opposite = [](Sign x, Sign y) {
      return (x == Sign::positive && y == Sign::negative) || (x == Sign::negative && y == Sign::positive);
    };
    const Index corners[3] = {u, a, b};
    for (int k = 0; k < 3; ++k) {
      const Point2 e0 = points_[corners[k]], e1 = points_[corners[(k + 1) % 3]];
      if (opposite(orientation(e0, e1, s0), orientation(e0, e1, s1)) &&
          opposite(orientation(s0, s1, e0), orientation(s0, s1, e1)))
        return true;
    }
    return false;
  }

  /// The M-distance from p to subsegment s, for the stretching f = M^{1/2} (in doubles: a filter with
  /// a relative margin, not a predicate).
  double stretched_distance_to_subsegment(const Matrix2& f, Point2 p, Index s) const {
    const auto stretch = [&](Point2 q) {
      const double dx = q.x - p.x, dy = q.y - p.y;
      return std::array<double, 2>{f.m00 * dx + f.m01 * dy, f.m10 * dx + f.m11 * dy};
    };
    const auto a = stretch(points_[subs_[s].a]), b = stretch(points_[subs_[s].b]);
    const double ux = b[0] - a[0], uy = b[1] - a[1], uu = ux * ux + uy * uy;
    const double t = uu > 0 ? std::clamp(-(a[0] * ux + a[1] * uy) / uu, 0.0, 1.0) : 0.0;
    return std::hypot(a[0] + t * ux, a[1] + t * uy);
  }

  void register_zone(Index v) {
    Star& star = stars_[v];
    if (star.cells[0] <= star.cells[2])
      for (std::size_t j = star.cells[1]; j <= star.cells[3]; ++j)
        for (std::size_t i = star.cells[0]; i <= star.cells[2]; ++i) {
          auto& cell = zones_grid_.at(i, j);
          cell.erase(std::find(cell.begin(), cell.end(), v));
        }
    if (star.triangles.empty()) {
      star.cells = {1, 1, 0, 0};
      return;
    }
    const Metric& m = metrics_[v];
    const double det = m.a * m.c - m.b * m.b;
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (const StarTriangle& t : star.triangles) {
      const double ex = t.radius * std::sqrt(m.c / det), ey = t.radius * std::sqrt(m.a / det);
      x0 = std::min(x0, t.cx - ex), x1 = std::max(x1, t.cx + ex);
      y0 = std::min(y0, t.cy - ey), y1 = std::max(y1, t.cy + ey);
    }
    star.cells = {zones_grid_.ix(x0), zones_grid_.iy(y0), zones_grid_.ix(x1), zones_grid_.iy(y1)};
    for (std::size_t j = star.cells[1]; j <= star.cells[3]; ++j)
      for (std::size_t i = star.cells[0]; i <= star.cells[2]; ++i) zones_grid_.at(i, j).push_back(v);
  }

  /// Queues the rule-2..4 violations of S_v (rule 5 waits for a consistency sweep).
  void evaluate(Index v, const Metric& m) {
    const Star& star = stars_[v];
    for (const StarTriangle& t : star.triangles) {
      if (!std::isfinite(t.radius)) continue;  // the refinement stops (degenerate_)
      int rule = 0;
      double g = std::max(distortion(m, metrics_[t.a]), distortion(m, metrics_[t.b]));
      try {
        g = std::max(g, distortion(m, field_.at(t.cx, t.cy)));
      } catch (const FieldError&) {
        // The circumcentre lies outside a background mesh: the vertices' metrics decide.
      }
      if (g >= options_.distortion_bound) rule = 2;
      else if (t.radius > options_.size_bound) rule = 3;
      else if (t.radius > options_.radius_edge_bound * t.shortest) rule = 4;
      if (rule) requests_.push({rule, t.radius, v, t.a, t.b, star.version});
    }
  }

  bool star_has(Index v, Index a, Index b) const {
    for (const StarTriangle& t : stars_[v].triangles)
      if (t.a == a && t.b == b) return true;
    return false;
  }

  /// Queues every inconsistent triangle; false if there is none.
  bool consistency_sweep() {
    ++stats_.consistency_sweeps;
    bool found = false;
    for (Index v = 0; v < stars_.size(); ++v)
      for (const StarTriangle& t : stars_[v].triangles)
        if (!star_has(t.a, t.b, v) || !star_has(t.b, v, t.a)) {
          requests_.push({5, t.radius, v, t.a, t.b, stars_[v].version});
          found = true;
        }
    return found;
  }

  void refine(const Request& r) {
    const StarTriangle* t = nullptr;
    for (const StarTriangle& c : stars_[r.v].triangles)
      if (c.a == r.a && c.b == r.b) t = &c;
    if (!t) return;
    if (r.rule == 5 && star_has(t->a, t->b, r.v) && star_has(t->b, r.v, t->a)) return;  // fixed meanwhile
    // Pick a point in the picking region: the M_v-ball of radius δR around the circumcentre.
    const Matrix2& f = roots_[r.v];
    const double det = f.m00 * f.m11 - f.m01 * f.m10;
    const double rho = options_.picking_ratio * t->radius * std::sqrt(rng_.uniform01());
    const double angle = 2 * M_PI * rng_.uniform01();
    const double ux = rho * std::cos(angle), uy = rho * std::sin(angle);
    const Point2 p{t->cx + (f.m11 * ux - f.m01 * uy) / det, t->cy + (-f.m10 * ux + f.m00 * uy) / det};
    const Point2 g{(points_[r.v].x + points_[r.a].x + points_[r.b].x) / 3,
                   (points_[r.v].y + points_[r.a].y + points_[r.b].y) / 3};
    const double hint = 3 * t->radius;
    if (place(p, g, hint) != Placement::inserted) return;
    switch (r.rule) {
      case 2: ++stats_.distortion; break;
      case 3: ++stats_.size; break;
      case 4: ++stats_.shape; break;
      default: ++stats_.inconsistency; break;
    }
  }

  /// What `place` did with a refinement point.
  enum class Placement { skipped, snapped, inserted };

  /// Insert or snap: a point encroaching a subsegment, or outside Ω, splits a subsegment instead (those
  /// it encroaches, or the one crossed on the way from `from`, a point of Ω, to p); else p is inserted
  /// with star query hint `hint`.
  Placement place(Point2 p, Point2 from, double hint) {
    std::vector<Index> hit;
    if (p.x >= box_[0] && p.x <= box_[2] && p.y >= box_[1] && p.y <= box_[3])
      for (Index s : subs_grid_.at(subs_grid_.ix(p.x), subs_grid_.iy(p.y)))
        if (subs_[s].alive && encroaches(s, p)) hit.push_back(s);
    if (hit.empty() && domain_.locate(p) != DomainSide::inside) {
      for (std::size_t s = 0; s < subs_.size() && hit.empty(); ++s)
        if (subs_[s].alive && segments_intersect(from, p, points_[subs_[s].a], points_[subs_[s].b]))
          hit.push_back(static_cast<Index>(s));
      if (hit.empty()) return Placement::skipped;  // cannot happen for a triangle inside Ω; skip rather than loop
    }
    if (!hit.empty()) {
      ++stats_.snapped;
      for (Index s : hit)
        if (subs_[s].alive) split(s);
      return Placement::snapped;
    }
    add_site(p, hint);
    return Placement::inserted;
  }

  // --- rule 6: lonely corners ------------------------------------------------------------------------

  /// Applies rule 6 (StarMesher.hpp) to every site whose star is a single triangle; false if there is
  /// none or nothing could be done.
  bool refine_lonely_corners() {
    std::vector<std::pair<Index, StarTriangle>> lonely;  // copies: insertions reallocate stars_
    for (Index v = 0; v < stars_.size(); ++v)
      if (stars_[v].triangles.size() == 1) lonely.emplace_back(v, stars_[v].triangles.front());
    bool changed = false;
    for (const auto& [v, t] : lonely) changed = refine_corner(v, t) || changed;
    return changed;
  }

  /// Rule 6 at the corner v of its only triangle (v, t.a, t.b).
  bool refine_corner(Index v, const StarTriangle& t) {
    const Point2 p = points_[v];
    const Matrix2& f = roots_[v];
    const auto stretch = [&](double x, double y) {
      const double dx = x - p.x, dy = y - p.y;
      return std::array<double, 2>{f.m00 * dx + f.m01 * dy, f.m10 * dx + f.m11 * dy};
    };
    const auto sa = stretch(points_[t.a].x, points_[t.a].y), sb = stretch(points_[t.b].x, points_[t.b].y);
    const auto so = stretch(t.cx, t.cy);
    const double la = std::hypot(sa[0], sa[1]), lb = std::hypot(sb[0], sb[1]);
    double dx = sa[0] / la + sb[0] / lb, dy = sa[1] / la + sb[1] / lb;
    const double ld = std::hypot(dx, dy);
    if (!(ld > 0)) return false;  // a flat corner cannot bound a single triangle
    dx /= ld, dy /= ld;
    const double cos_half = (sa[0] * dx + sa[1] * dy) / la;
    const double lower = std::max(la, lb) * cos_half;   // outside both diametral balls from here on
    const double upper = 2 * (so[0] * dx + so[1] * dy);  // inside the circumcircle up to here
    ++stats_.corners;
    if (lower > 0 && lower < upper * (1 - 1e-6)) {
      const double r = std::sqrt(lower * upper);
      const double ux = r * dx, uy = r * dy;
      const double det = f.m00 * f.m11 - f.m01 * f.m10;
      const Point2 q{p.x + (f.m11 * ux - f.m01 * uy) / det, p.y + (-f.m10 * ux + f.m00 * uy) / det};
      const Point2 g{(p.x + points_[t.a].x + points_[t.b].x) / 3, (p.y + points_[t.a].y + points_[t.b].y) / 3};
      return place(q, g, 3 * t.radius) != Placement::skipped;
    }
    // A sharp corner with unequal subsegments: split the longer one (then the shorter, if it is not one).
    const Index first = la >= lb ? t.a : t.b, second = la >= lb ? t.b : t.a;
    for (const Index w : {first, second})
      for (std::size_t s = 0; s < subs_.size(); ++s)
        if (subs_[s].alive && ((subs_[s].a == v && subs_[s].b == w) || (subs_[s].a == w && subs_[s].b == v))) {
          split(static_cast<Index>(s));
          return true;
        }
    --stats_.corners;
    return false;
  }

  // --- output --------------------------------------------------------------------------------------

  void merge(StarMeshResult& result) const {
    result.stats = stats_;
    TriangleMesh& mesh = result.mesh;
    for (const Point2& p : points_) mesh.points.push_back({p.x, p.y});
    mesh.point_refs.assign(points_.size(), 0);
    for (Index v = 0; v < stars_.size(); ++v)
      for (const StarTriangle& t : stars_[v].triangles)
        if (v < t.a && v < t.b && star_has(t.a, t.b, v) && star_has(t.b, v, t.a)) {
          mesh.triangles.push_back({v, t.a, t.b});
          mesh.triangle_refs.push_back(0);
        }
    for (const Subsegment& s : subs_)
      if (s.alive) {
        mesh.edges.push_back({s.a, s.b});
        mesh.edge_refs.push_back(1);
      }
    result.metrics = metrics_;
  }

  const Domain& domain_;
  const MetricField& field_;
  StarMeshOptions options_;
  SplitMix64 rng_;  // the picking's random stream (deterministic across standard libraries)
  std::array<double, 4> box_;
  detail::BucketGrid<Index> sites_grid_, zones_grid_, subs_grid_;
  std::vector<Point2> points_;
  std::vector<Metric> metrics_;
  std::vector<Matrix2> roots_;
  std::vector<double> largest_size_;
  std::vector<double> hint_;
  std::vector<Star> stars_;
  std::vector<Subsegment> subs_;
  std::vector<std::uint64_t> sub_seen_;  ///< per subsegment: the last star query that met it
  std::uint64_t sub_epoch_ = 0;
  std::vector<std::uint64_t> local_stamp_;  ///< per site: the last star query that took it
  std::vector<std::size_t> local_index_;    ///< per site: its index in that query
  std::uint64_t local_epoch_ = 0;
  std::vector<Index> split_queue_;
  StarMeshStats stats_;
  std::string degenerate_;  ///< why the refinement must stop (a star triangle it cannot refine), or ""
};

}  // namespace

StarMeshResult mesh_with_stars(const Domain& domain, const MetricField& field, const StarMeshOptions& options) {
  return StarMesher(domain, field, options).run();
}

std::string check_triangulation(const TriangleMesh& mesh, const Domain& domain) {
  std::map<std::pair<std::size_t, std::size_t>, int> directed;
  double area = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Point2 p{mesh.points[tri[0]][0], mesh.points[tri[0]][1]}, q{mesh.points[tri[1]][0], mesh.points[tri[1]][1]},
        r{mesh.points[tri[2]][0], mesh.points[tri[2]][1]};
    if (orientation(p, q, r) != Sign::positive) return "triangle " + std::to_string(t) + " is not counter-clockwise";
    area += ((q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x)) / 2;
    for (int k = 0; k < 3; ++k)
      if (++directed[{tri[static_cast<std::size_t>(k)], tri[static_cast<std::size_t>((k + 1) % 3)]}] > 1)
        return "triangles overlap along edge " + std::to_string(tri[static_cast<std::size_t>(k)]) + "–" +
               std::to_string(tri[static_cast<std::size_t>((k + 1) % 3)]);
  }
  std::set<std::pair<std::size_t, std::size_t>> constraints;
  for (const auto& e : mesh.edges) constraints.insert({std::min(e[0], e[1]), std::max(e[0], e[1])});
  for (const auto& [e, count] : directed) {
    if (directed.count({e.second, e.first})) continue;  // interior edge, used once each way
    if (!constraints.count({std::min(e.first, e.second), std::max(e.first, e.second)}))
      return "edge " + std::to_string(e.first) + "–" + std::to_string(e.second) +
             " bounds a single triangle but is not a boundary subsegment (a hole in the mesh)";
  }
  const double expected = domain.area();
  // A domain (or mesh) beyond what doubles represent has a non-finite area: never call it valid.
  if (!std::isfinite(expected) || !std::isfinite(area))
    return "the area of the domain (" + std::to_string(expected) + ") or of the triangles (" + std::to_string(area) +
           ") is not finite";
  if (std::abs(area - expected) > 1e-9 * std::abs(expected))
    return "the triangles cover an area of " + std::to_string(area) + " instead of " + std::to_string(expected);
  return {};
}

}  // namespace laguerre::core
