#include "laguerre/core/geometry/Predicates.hpp"

#include <algorithm>

#include <CGAL/Mpzf.h>

#include "../detail/FastFilter.hpp"
#include "../detail/FastFilter128.hpp"
#include "../detail/Filtered.hpp"

namespace laguerre::core {

using detail::filtered;
using detail::filtered_with;
using detail::sign_of;

// Each predicate first tries the double-precision filter of detail/FastFilter.hpp (no rounding-mode
// switch), then the interval filter, then an exact number type: rationals, or CGAL::Mpzf for the
// radical-centre predicates, which are polynomials (no division) of degree 4 and 6.

// The exact stages are written once over the input type (double or binary128 coordinates): `to_nt`
// (FastFilter128.hpp) gives a coordinate's exact value in NT (an enclosure for intervals).
using detail::to_nt;

namespace {

void require_finite_of(const char* name, std::initializer_list<double> v) { detail::require_finite(name, v); }
void require_finite_of(const char* name, std::initializer_list<Float128> v) { detail::require_finite128(name, v); }

template <class P>
Sign orientation_exact(P a, P b, P c) {
  require_finite_of("orientation", {a.x, a.y, b.x, b.y, c.x, c.y});
  return filtered([&]<class NT>() {
    const NT abx = to_nt<NT>(b.x) - to_nt<NT>(a.x), aby = to_nt<NT>(b.y) - to_nt<NT>(a.y);
    const NT acx = to_nt<NT>(c.x) - to_nt<NT>(a.x), acy = to_nt<NT>(c.y) - to_nt<NT>(a.y);
    return sign_of<NT>(abx * acy - aby * acx);
  });
}

template <class P, class C>
Sign compare_power_exact(P q, const C& a, const C& b) {
  require_finite_of("compare_power", {q.x, q.y, a.x, a.y, a.r, b.x, b.y, b.r});
  return filtered([&]<class NT>() {
    const NT ax = to_nt<NT>(q.x) - to_nt<NT>(a.x), ay = to_nt<NT>(q.y) - to_nt<NT>(a.y);
    const NT bx = to_nt<NT>(q.x) - to_nt<NT>(b.x), by = to_nt<NT>(q.y) - to_nt<NT>(b.y);
    const NT ra = to_nt<NT>(a.r), rb = to_nt<NT>(b.r);
    return sign_of<NT>(ax * ax + ay * ay - ra * ra - bx * bx - by * by + rb * rb);
  });
}

template <class P>
Sign compare_distance_exact(P q, P a, P b) {
  require_finite_of("compare_distance", {q.x, q.y, a.x, a.y, b.x, b.y});
  return filtered([&]<class NT>() {
    const NT ax = to_nt<NT>(q.x) - to_nt<NT>(a.x), ay = to_nt<NT>(q.y) - to_nt<NT>(a.y);
    const NT bx = to_nt<NT>(q.x) - to_nt<NT>(b.x), by = to_nt<NT>(q.y) - to_nt<NT>(b.y);
    return sign_of<NT>(ax * ax + ay * ay - bx * bx - by * by);
  });
}
}  // namespace

Sign orientation(Point2 a, Point2 b, Point2 c) {
  const double ux = b.x - a.x, uy = b.y - a.y, wx = c.x - a.x, wy = c.y - a.y;
  if (detail::in_range(ux) && detail::in_range(uy) && detail::in_range(wx) && detail::in_range(wy))
    if (const auto s = detail::certified_difference(ux * wy, uy * wx)) return *s;
  return orientation_exact(a, b, c);
}

template <Binary128Point P>
Sign orientation(P a, P b, P c) {
  if (const auto s = detail::certified_orientation(a, b, c)) return *s;
  return orientation_exact(a, b, c);
}

Sign compare_power(Point2 q, const Circle& a, const Circle& b) {
  // Equal radii cancel exactly: the comparison is then one of distances, whose filter does not
  // carry the (possibly large) r² terms.
  if (a.r == b.r) return compare_distance(q, centre(a), centre(b));
  if (const auto s = detail::certified_sign(detail::approx_power(q, a), detail::approx_power(q, b))) return *s;
  return compare_power_exact(q, a, b);
}

template <Binary128Point P>
Sign compare_power(P q, const Circle128& a, const Circle128& b) {
  if (a.r == b.r) return compare_distance(q, centre(a), centre(b));
  if (const auto s = detail::certified_sign(detail::approx_power(q, a), detail::approx_power(q, b))) return *s;
  return compare_power_exact(q, a, b);
}

Sign compare_distance(Point2 q, Point2 a, Point2 b) {
  if (const auto s = detail::certified_sign(detail::approx_distance(q, a), detail::approx_distance(q, b))) return *s;
  return compare_distance_exact(q, a, b);
}

template <Binary128Point P>
Sign compare_distance(P q, P a, P b) {
  if (const auto s = detail::certified_sign(detail::approx_distance(q, a), detail::approx_distance(q, b))) return *s;
  return compare_distance_exact(q, a, b);
}

namespace {
// Radical centre of (u, a, b): c = (nx, ny) / (2 d) with d = det[p_a − p_u; p_b − p_u].
// From pow(x, s) − pow(x, u) = −2 x·(p_s − p_u) + (z_s − z_u), z_s = |p_s|² − r_s².
template <class NT>
struct RadicalCentre {
  NT d, nx, ny;
};

template <class NT, class C>
NT lifted(const C& s) {
  const NT x = to_nt<NT>(s.x), y = to_nt<NT>(s.y), r = to_nt<NT>(s.r);
  return x * x + y * y - r * r;
}

template <class NT, class C>
RadicalCentre<NT> radical_centre(const C& u, const C& a, const C& b) {
  const NT aax = to_nt<NT>(a.x) - to_nt<NT>(u.x), aay = to_nt<NT>(a.y) - to_nt<NT>(u.y);
  const NT abx = to_nt<NT>(b.x) - to_nt<NT>(u.x), aby = to_nt<NT>(b.y) - to_nt<NT>(u.y);
  const NT zu = lifted<NT>(u);
  const NT ba = lifted<NT>(a) - zu, bb = lifted<NT>(b) - zu;
  return {aax * aby - aay * abx, aby * ba - aay * bb, aax * bb - abx * ba};
}

template <class C>
Sign power_side_exact(const C& u, const C& a, const C& b, const C& t) {
  require_finite_of("radical_centre_power_side", {u.x, u.y, u.r, a.x, a.y, a.r, b.x, b.y, b.r, t.x, t.y, t.r});
  return filtered_with<CGAL::Mpzf>([&]<class NT>() {
    // The translated form of certified_power_side, E = d·(pow(c, t) − pow(c, u)): the same exact value
    // as in absolute coordinates (E is translation-invariant), and tighter intervals.
    const NT ru2 = to_nt<NT>(u.r) * to_nt<NT>(u.r);
    auto beta = [&](const NT& sx, const NT& sy, const C& s) {
      const NT r = to_nt<NT>(s.r);
      return sx * sx + sy * sy - r * r + ru2;
    };
    const NT ux = to_nt<NT>(u.x), uy = to_nt<NT>(u.y);
    const NT ax = to_nt<NT>(a.x) - ux, ay = to_nt<NT>(a.y) - uy, bx = to_nt<NT>(b.x) - ux, by = to_nt<NT>(b.y) - uy;
    const NT d = ax * by - ay * bx;
    const Sign sd = sign_of<NT>(d);
    if (sd == Sign::zero) return Sign::zero;
    const NT ba = beta(ax, ay, a), bb = beta(bx, by, b);
    const NT nx = by * ba - ay * bb, ny = ax * bb - bx * ba;
    const NT tx = to_nt<NT>(t.x) - ux, ty = to_nt<NT>(t.y) - uy;
    const Sign sn = sign_of<NT>(d * beta(tx, ty, t) - tx * nx - ty * ny);
    return static_cast<Sign>(static_cast<int>(sn) * static_cast<int>(sd));
  });
}

template <class C>
Sign outside_unit_disc_exact(const C& u, const C& a, const C& b) {
  require_finite_of("radical_centre_outside_unit_disc", {u.x, u.y, u.r, a.x, a.y, a.r, b.x, b.y, b.r});
  return filtered_with<CGAL::Mpzf>([&]<class NT>() {  // a polynomial: exact in Mpzf
    const auto c = radical_centre<NT>(u, a, b);
    if (sign_of<NT>(c.d) == Sign::zero) return Sign::zero;
    return sign_of<NT>(c.nx * c.nx + c.ny * c.ny - 4 * c.d * c.d);
  });
}

template <class P, class C>
bool segment_meets_power_cell_t(P s0, P s1, const C& site, const C* others, std::size_t count) {
  require_finite_of("segment_meets_power_cell", {s0.x, s0.y, s1.x, s1.y, site.x, site.y, site.r});
  for (std::size_t i = 0; i < count; ++i)
    require_finite_of("segment_meets_power_cell", {others[i].x, others[i].y, others[i].r});
  return filtered([&]<class NT>() {
    auto pw = [](const NT& qx, const NT& qy, const C& c) -> NT {
      const NT dx = qx - to_nt<NT>(c.x), dy = qy - to_nt<NT>(c.y), r = to_nt<NT>(c.r);
      return dx * dx + dy * dy - r * r;
    };
    const NT x0 = to_nt<NT>(s0.x), y0 = to_nt<NT>(s0.y), x1 = to_nt<NT>(s1.x), y1 = to_nt<NT>(s1.y);
    const NT p0 = pw(x0, y0, site), p1 = pw(x1, y1, site);
    NT lo(0), hi(1);  // feasible parameters t ∈ [lo, hi]
    for (std::size_t i = 0; i < count; ++i) {
      // f(t) = pow(s(t), site) − pow(s(t), o) is affine in t; we need f(t) ≤ 0.
      const NT f0 = p0 - pw(x0, y0, others[i]);
      const NT f1 = p1 - pw(x1, y1, others[i]);
      if (f0 <= 0 && f1 <= 0) continue;
      if (f0 > 0 && f1 > 0) return false;
      const NT t = f0 / (f0 - f1);  // the root, in [0, 1]
      if (f0 <= 0) {                // f increasing: t ≤ root
        if (t < hi) hi = t;
      } else if (t > lo) {          // f decreasing: t ≥ root
        lo = t;
      }
      if (lo > hi) return false;
    }
    return true;
  });
}
}  // namespace

Sign radical_centre_power_side(const Circle& u, const Circle& a, const Circle& b, const Circle& t) {
  // Double stage (translated and rescaled, detail::certified_power_side), then intervals, then Mpzf:
  // the expression is a polynomial in the inputs, so Mpzf evaluates it exactly without rationals.
  if (const auto s = detail::certified_power_side(u, a, b, t)) return *s;
  return power_side_exact(u, a, b, t);
}

template <Binary128Circle C>
Sign radical_centre_power_side(const C& u, const C& a, const C& b, const C& t) {
  if (const auto s = detail::certified_power_side(u, a, b, t)) return *s;
  return power_side_exact(u, a, b, t);
}

Sign radical_centre_outside_unit_disc(const Circle& u, const Circle& a, const Circle& b) {
  return outside_unit_disc_exact(u, a, b);
}

template <Binary128Circle C>
Sign radical_centre_outside_unit_disc(const C& u, const C& a, const C& b) {
  return outside_unit_disc_exact(u, a, b);
}

bool segment_meets_power_cell(Point2 s0, Point2 s1, const Circle& site, const Circle* others, std::size_t count) {
  return segment_meets_power_cell_t(s0, s1, site, others, count);
}

template <Binary128Point P>
bool segment_meets_power_cell(P s0, P s1, const Circle128& site, const Circle128* others, std::size_t count) {
  return segment_meets_power_cell_t(s0, s1, site, others, count);
}

template Sign orientation<Point128>(Point128, Point128, Point128);
template Sign compare_power<Point128>(Point128, const Circle128&, const Circle128&);
template Sign compare_distance<Point128>(Point128, Point128, Point128);
template Sign radical_centre_power_side<Circle128>(const Circle128&, const Circle128&, const Circle128&, const Circle128&);
template Sign radical_centre_outside_unit_disc<Circle128>(const Circle128&, const Circle128&, const Circle128&);
template bool segment_meets_power_cell<Point128>(Point128, Point128, const Circle128&, const Circle128*, std::size_t);

Sign compare_deviation(Point2 v, Point2 t, Point2 a, Point2 b) {
  detail::require_finite("compare_deviation", {v.x, v.y, t.x, t.y, a.x, a.y, b.x, b.y});
  return filtered([&]<class NT>() {
    const NT tx = NT(t.x) - NT(v.x), ty = NT(t.y) - NT(v.y);
    auto q = [&](Point2 p) -> NT {  // cos(angle)·|cos(angle)|·|t − v|², a monotone image of cos
      const NT dx = NT(p.x) - NT(v.x), dy = NT(p.y) - NT(v.y);
      const NT len2 = dx * dx + dy * dy;
      if (len2 == 0) return NT(0);
      const NT dot = dx * tx + dy * ty;
      return NT((dot < 0 ? NT(-dot * dot) : NT(dot * dot)) / len2);
    };
    // Smaller angle ⇔ larger cosine.
    return sign_of<NT>(q(b) - q(a));
  });
}

bool segments_intersect(Point2 a, Point2 b, Point2 c, Point2 d) {
  const int o1 = static_cast<int>(orientation(a, b, c)), o2 = static_cast<int>(orientation(a, b, d));
  const int o3 = static_cast<int>(orientation(c, d, a)), o4 = static_cast<int>(orientation(c, d, b));
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  auto on_segment = [](Point2 p, Point2 q, Point2 r) {  // r collinear with pq: is r within the box?
    return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y &&
           r.y <= std::max(p.y, q.y);
  };
  if (o1 == 0 && on_segment(a, b, c)) return true;
  if (o2 == 0 && on_segment(a, b, d)) return true;
  if (o3 == 0 && on_segment(c, d, a)) return true;
  if (o4 == 0 && on_segment(c, d, b)) return true;
  return false;
}

Sign compare_crossings_along(Point2 p, Point2 q, Point2 a1, Point2 b1, Point2 a2, Point2 b2) {
  detail::require_finite("compare_crossings_along", {p.x, p.y, q.x, q.y, a1.x, a1.y, b1.x, b1.y, a2.x, a2.y, b2.x, b2.y});
  return filtered([&]<class NT>() {
    auto orient = [](Point2 a, Point2 b, Point2 c) -> NT {
      return (NT(b.x) - NT(a.x)) * (NT(c.y) - NT(a.y)) - (NT(b.y) - NT(a.y)) * (NT(c.x) - NT(a.x));
    };
    auto param = [&](Point2 a, Point2 b) -> NT {
      const NT op = orient(a, b, p), oq = orient(a, b, q);
      return op / (op - oq);
    };
    return sign_of<NT>(param(a1, b1) - param(a2, b2));
  });
}

}  // namespace laguerre::core
