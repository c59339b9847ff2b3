// Kleinberg's hyperbolic greedy embedding of a BFS tree (see the header and docs/hyperbolic-baseline.md).
//
// Model: the upper half-plane, isometries as SL(2, R) matrices. The root's tile is the regular ideal
// q-gon centred at i; its side 0 is the half circle |z| = h, h = cot(π/(2q)), at distance D/2 from i,
// D = 2 artanh cos(π/q) (the inradius of the ideal q-gon: tanh(D/2) = cos(π/q)). With
//   H   = [[0, −h], [1/h, 0]]        the half turn about ih (z ↦ −h²/z), swapping the tile with its
//                                     neighbour across side 0 and mapping i to ih²;
//   R_j = [[cos jθ, sin jθ], [−sin jθ, cos jθ]], θ = π/q, the rotation by 2jπ/q about i,
// the neighbour across side j is G_j(tile) with G_j = R_j·H. A node v with tree word (j1, …, jk) from
// the root carries the isometry M_v = G_j1 ⋯ G_jk and sits at M_v(i); its parent is across side 0 of
// its own tile (M_v·H(i) = M_parent(i)), so its children use sides 1..q−1 and the root's 0..q−1.
//
// Distances: for A ∈ SL(2, R), 2·cosh d(i, A·i) = ‖A‖_F² (a² + b² + c² + d²). Hence
// 2·cosh d(M_a(i), M_b(i)) = ‖M_a⁻¹ M_b‖_F², and M_a⁻¹ M_b is the product along the tree path from a
// to b once the common prefix of the two words is cancelled — symbolically, so nothing near the
// boundary is ever rounded. Up to rotations (orthogonal: they leave the norm alone) it is
// H·G_{t1}⋯G_{t(L−1)} with every turn t in [1, q), evaluated as (H·C)·P_{t1}⋯P_{t(L−1)}·C⁻¹ where
// P_t = C⁻¹G_tC has nonnegative entries (C maps [0, ∞] onto the arc [−h, h] that every G_t maps into
// itself): no cancellation and no wrapping effect inside the product. Double interval arithmetic
// (CGAL::Interval_nt, directed rounding), rescaled by a power of two after every factor (the entries
// grow like e^{length·D/2}), gives an enclosure m·4^e. Matrix entries are enclosed from a 256-bit MPFR
// evaluation widened by one ulp. docs/hyperbolic-baseline.md has the derivation and the measurements.

#include "laguerre/core/routing/HyperbolicEmbedding.hpp"

#include <mpfr.h>

#include <CGAL/Interval_nt.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <string>

#include "laguerre/core/Error.hpp"

namespace laguerre::core {

namespace {

using I = CGAL::Interval_nt<false>;

// Enclosure of an MPFR value computed with error far below a double ulp: round both ways, widen by one ulp.
void enclose(const mpfr_t x, double& lo, double& hi) {
  lo = std::nextafter(mpfr_get_d(x, MPFR_RNDD), -std::numeric_limits<double>::infinity());
  hi = std::nextafter(mpfr_get_d(x, MPFR_RNDU), std::numeric_limits<double>::infinity());
}

// 2×2 matrix product in MPFR, each matrix 4 consecutive numbers (out may not alias x or y).
void mpfr_mul2(mpfr_ptr out, mpfr_srcptr x, mpfr_srcptr y, mpfr_ptr tmp) {
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) {
      mpfr_mul(out + 2 * r + c, x + 2 * r, y + c, MPFR_RNDN);
      mpfr_mul(tmp, x + 2 * r + 1, y + 2 + c, MPFR_RNDN);
      mpfr_add(out + 2 * r + c, out + 2 * r + c, tmp, MPFR_RNDN);
    }
}

// The matrices of the evaluation, as (lo, hi) enclosures of 4 entries (8 doubles each): for m in
// [1, q), P_m = C⁻¹·G_m·C (slot m), nonnegative; slot 0 holds H·C and slot q holds C⁻¹.
std::vector<double> evaluation_matrices(std::uint32_t q) {
  std::vector<double> out(8 * (static_cast<std::size_t>(q) + 1));
  mpfr_t pi, t, co, si, h, tmp;
  mpfr_inits2(256, pi, t, co, si, h, tmp, static_cast<mpfr_ptr>(nullptr));
  mpfr_t cm[4], ci[4], g[4], gc[4], pm[4];
  for (auto* m : {cm, ci, g, gc, pm})
    for (int k = 0; k < 4; ++k) mpfr_init2(m[k], 256);
  mpfr_const_pi(pi, MPFR_RNDN);
  mpfr_div_ui(t, pi, 2 * q, MPFR_RNDN);  // π/(2q)
  mpfr_cot(h, t, MPFR_RNDN);
  // C = [[h, −h], [1, 1]] maps [0, ∞] onto J = [−h, h]; C⁻¹ = [[1, h], [−1, h]] / (2h).
  mpfr_set(cm[0], h, MPFR_RNDN);
  mpfr_neg(cm[1], h, MPFR_RNDN);
  mpfr_set_ui(cm[2], 1, MPFR_RNDN);
  mpfr_set_ui(cm[3], 1, MPFR_RNDN);
  mpfr_mul_ui(tmp, h, 2, MPFR_RNDN);
  mpfr_ui_div(ci[0], 1, tmp, MPFR_RNDN);
  mpfr_set_d(ci[1], 0.5, MPFR_RNDN);
  mpfr_neg(ci[2], ci[0], MPFR_RNDN);
  mpfr_set_d(ci[3], 0.5, MPFR_RNDN);
  auto store = [&](std::size_t slot, mpfr_t* m) {
    for (int k = 0; k < 4; ++k) enclose(m[k], out[8 * slot + 2 * k], out[8 * slot + 2 * k + 1]);
  };
  // H·C = [[0, −h], [1/h, 0]]·C = [[−h, −h], [1, −1]].
  mpfr_neg(pm[0], h, MPFR_RNDN);
  mpfr_neg(pm[1], h, MPFR_RNDN);
  mpfr_set_ui(pm[2], 1, MPFR_RNDN);
  mpfr_set_si(pm[3], -1, MPFR_RNDN);
  store(0, pm);
  store(q, ci);
  for (std::uint32_t m = 1; m < q; ++m) {
    mpfr_mul_ui(t, pi, m, MPFR_RNDN);
    mpfr_div_ui(t, t, q, MPFR_RNDN);  // mπ/q
    mpfr_sin_cos(si, co, t, MPFR_RNDN);
    // G_m = R_m·H = [[s/h, −c·h], [c/h, s·h]].
    mpfr_div(g[0], si, h, MPFR_RNDN);
    mpfr_mul(g[1], co, h, MPFR_RNDN);
    mpfr_neg(g[1], g[1], MPFR_RNDN);
    mpfr_div(g[2], co, h, MPFR_RNDN);
    mpfr_mul(g[3], si, h, MPFR_RNDN);
    mpfr_mul2(gc[0], g[0], cm[0], tmp);
    mpfr_mul2(pm[0], ci[0], gc[0], tmp);
    // G_m maps J into its arc A_m ⊂ J, so P_m maps [0, ∞] into itself: its entries share one sign
    // (PSL: fix it to +). Entries that are 0 in exact arithmetic come out as ±tiny: clamp at 0.
    mpfr_add(tmp, pm[0], pm[3], MPFR_RNDN);
    const bool negate = mpfr_sgn(tmp) < 0;
    for (int k = 0; k < 4; ++k) {
      if (negate) mpfr_neg(pm[k], pm[k], MPFR_RNDN);
      double lo = 0, hi = 0;
      enclose(pm[k], lo, hi);
      if (lo < -1e-60) throw InternalError("hyperbolic embedding: a conjugated generator has a negative entry");
      out[8 * m + 2 * k] = std::max(lo, 0.0);
      out[8 * m + 2 * k + 1] = std::max(hi, 0.0);
    }
  }
  for (auto* m : {cm, ci, g, gc, pm})
    for (int k = 0; k < 4; ++k) mpfr_clear(m[k]);
  mpfr_clears(pi, t, co, si, h, tmp, static_cast<mpfr_ptr>(nullptr));
  mpfr_free_cache();
  return out;
}

// 2^e · [[a, b], [c, d]] with interval entries.
struct ScaledMatrix {
  I a{1}, b{0}, c{0}, d{1};
  int e = 0;
};

// M ← M·G (G as 8 doubles), then rescaled so the largest |entry| bound lies in [1/2, 1).
void multiply(ScaledMatrix& m, const double* g) {
  const I ga(g[0], g[1]), gb(g[2], g[3]), gc(g[4], g[5]), gd(g[6], g[7]);
  const I a = m.a * ga + m.b * gc, b = m.a * gb + m.b * gd;
  const I c = m.c * ga + m.d * gc, d = m.c * gb + m.d * gd;
  const double top = std::max({std::abs(a.inf()), std::abs(a.sup()), std::abs(b.inf()), std::abs(b.sup()),
                               std::abs(c.inf()), std::abs(c.sup()), std::abs(d.inf()), std::abs(d.sup())});
  int k = 0;
  if (std::isfinite(top) && top > 0) std::frexp(top, &k);
  const I scale(std::ldexp(1.0, -k));  // an exact power of two
  m.a = a * scale;
  m.b = b * scale;
  m.c = c * scale;
  m.d = d * scale;
  m.e += k;
}

// Sign of x − y for two scaled norms, or nothing.
std::optional<Sign> compare_norms(const HyperbolicTreeEmbedding::Norm& x, const HyperbolicTreeEmbedding::Norm& y) {
  CGAL::Protect_FPU_rounding<true> guard;
  // Bring both to the smaller exponent; a difference beyond 250 (4^250 = 2^500) is capped: the
  // normalised mantissas are ≤ 4, so the capped comparison still decides whenever the larger one's
  // lower bound is not tiny, and says "undecided" otherwise.
  const int diff = std::clamp(x.exp - y.exp, -250, 250);
  I mx(x.lo, x.hi), my(y.lo, y.hi);
  if (diff > 0) mx = mx * I(std::ldexp(1.0, 2 * diff));
  else if (diff < 0) my = my * I(std::ldexp(1.0, -2 * diff));
  if (mx.inf() > my.sup()) return Sign::positive;
  if (mx.sup() < my.inf()) return Sign::negative;
  if (x.exp == y.exp && x.lo == x.hi && y.lo == y.hi && x.lo == y.lo) return Sign::zero;
  return std::nullopt;
}

// BFS from `from` over CSR adjacency: distances, and as parent of each vertex its smallest-index
// neighbour one level up — the rule a node applies locally in the distributed set-up
// (protocols/HyperbolicSetup.hpp), where it hears all of that level at once.
void bfs(const std::vector<std::uint32_t>& off, const std::vector<Vertex>& tgt, Vertex from,
         std::vector<std::uint32_t>& dist, std::vector<Vertex>& parent) {
  const std::size_t n = off.size() - 1;
  constexpr std::uint32_t unseen = std::numeric_limits<std::uint32_t>::max();
  dist.assign(n, unseen);
  parent.assign(n, none);
  std::vector<Vertex> queue{from};
  queue.reserve(n);
  dist[from] = 0;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const Vertex v = queue[head];
    for (std::uint32_t k = off[v]; k < off[v + 1]; ++k) {
      const Vertex u = tgt[k];
      if (dist[u] == unseen) {
        dist[u] = dist[v] + 1;
        queue.push_back(u);
      }
      if (dist[u] == dist[v] + 1 && (parent[u] == none || v < parent[u])) parent[u] = v;
    }
  }
}

Vertex farthest(const std::vector<std::uint32_t>& dist) {
  Vertex best = 0;
  for (Vertex v = 1; v < dist.size(); ++v)
    if (dist[v] > dist[best]) best = v;  // smallest index among ties
  return best;
}

// The classical coordinates: every node's Poincaré-disc point M_v(i) ↦ (z − i)/(z + i), with M_v the
// product of the un-conjugated G_j = R_j·H from the root, in MPFR at a precision far beyond what the
// depth needs, then enclosed in double boxes (what a node holding two doubles knows of its point).
std::vector<double> disc_boxes(const HyperbolicTreeEmbedding& e, const std::vector<std::uint32_t>& depth,
                               const std::vector<Vertex>& parent) {
  const std::size_t n = e.size();
  const std::uint32_t q = e.tiling_degree();
  const auto bits = static_cast<mpfr_prec_t>(128 + 3 * std::ceil(e.max_depth() * e.edge_length() / std::log(2.0)));
  std::vector<__mpfr_struct> gen(4 * static_cast<std::size_t>(q)), mat(4 * n);
  mpfr_t pi, t, h, c, s, tmp, x, y, den;
  mpfr_inits2(bits, pi, t, h, c, s, tmp, x, y, den, static_cast<mpfr_ptr>(nullptr));
  for (auto& v : gen) mpfr_init2(&v, bits);
  for (auto& v : mat) mpfr_init2(&v, bits);
  mpfr_const_pi(pi, MPFR_RNDN);
  mpfr_div_ui(t, pi, 2 * q, MPFR_RNDN);
  mpfr_cot(h, t, MPFR_RNDN);
  for (std::uint32_t j = 0; j < q; ++j) {
    mpfr_mul_ui(t, pi, j, MPFR_RNDN);
    mpfr_div_ui(t, t, q, MPFR_RNDN);
    mpfr_sin_cos(s, c, t, MPFR_RNDN);
    mpfr_ptr g = &gen[4 * static_cast<std::size_t>(j)];
    mpfr_div(g, s, h, MPFR_RNDN);
    mpfr_mul(g + 1, c, h, MPFR_RNDN);
    mpfr_neg(g + 1, g + 1, MPFR_RNDN);
    mpfr_div(g + 2, c, h, MPFR_RNDN);
    mpfr_mul(g + 3, s, h, MPFR_RNDN);
  }
  std::vector<Vertex> order(n);
  for (Vertex v = 0; v < n; ++v) order[v] = v;
  std::stable_sort(order.begin(), order.end(), [&](Vertex a, Vertex b) { return depth[a] < depth[b]; });
  std::vector<double> out(4 * n);
  for (const Vertex v : order) {
    const mpfr_ptr m = &mat[4 * static_cast<std::size_t>(v)];
    if (parent[v] == none) {
      for (int k = 0; k < 4; ++k) mpfr_set_ui(m + k, k == 0 || k == 3 ? 1 : 0, MPFR_RNDN);
    } else {
      mpfr_mul2(m, &mat[4 * static_cast<std::size_t>(parent[v])], &gen[4 * static_cast<std::size_t>(e.child_index(v))], tmp);
    }
    // z = x + iy = M(i): x = (ac + bd)/(c² + d²), y = 1/(c² + d²); w = (x² + y² − 1 − 2ix)/(x² + (y + 1)²).
    mpfr_mul(tmp, m + 2, m + 2, MPFR_RNDN);
    mpfr_fma(tmp, m + 3, m + 3, tmp, MPFR_RNDN);
    mpfr_ui_div(y, 1, tmp, MPFR_RNDN);
    mpfr_mul(x, m, m + 2, MPFR_RNDN);
    mpfr_fma(x, m + 1, m + 3, x, MPFR_RNDN);
    mpfr_mul(x, x, y, MPFR_RNDN);
    mpfr_add_ui(tmp, y, 1, MPFR_RNDN);
    mpfr_sqr(den, tmp, MPFR_RNDN);
    mpfr_fma(den, x, x, den, MPFR_RNDN);  // x² + (y + 1)²
    mpfr_sqr(tmp, y, MPFR_RNDN);
    mpfr_fma(tmp, x, x, tmp, MPFR_RNDN);
    mpfr_sub_ui(tmp, tmp, 1, MPFR_RNDN);
    mpfr_div(tmp, tmp, den, MPFR_RNDN);  // Re w
    double* box = &out[4 * static_cast<std::size_t>(v)];
    enclose(tmp, box[0], box[1]);
    mpfr_mul_si(tmp, x, -2, MPFR_RNDN);
    mpfr_div(tmp, tmp, den, MPFR_RNDN);  // Im w
    enclose(tmp, box[2], box[3]);
  }
  for (auto& v : gen) mpfr_clear(&v);
  for (auto& v : mat) mpfr_clear(&v);
  mpfr_clears(pi, t, h, c, s, tmp, x, y, den, static_cast<mpfr_ptr>(nullptr));
  mpfr_free_cache();
  return out;
}

}  // namespace

HyperbolicTreeEmbedding::HyperbolicTreeEmbedding(const PlanarGraph& g, const HyperbolicOptions& options) {
  std::vector<std::uint32_t> off{0};
  std::vector<Vertex> tgt;
  for (Vertex v = 0; v < g.num_vertices(); ++v) {
    for (const Vertex u : g.neighbours(v)) tgt.push_back(u);
    off.push_back(static_cast<std::uint32_t>(tgt.size()));
  }
  build(off, tgt, options);
}

HyperbolicTreeEmbedding::HyperbolicTreeEmbedding(const std::vector<std::vector<Vertex>>& adjacency,
                                                 const HyperbolicOptions& options) {
  std::vector<std::uint32_t> off{0};
  std::vector<Vertex> tgt;
  for (const auto& list : adjacency) {
    for (const Vertex u : list) {
      if (u >= adjacency.size())
        throw InputError("adjacency", 0, "found neighbour " + std::to_string(u) + ", expected a vertex index below " +
                                             std::to_string(adjacency.size()));
      tgt.push_back(u);
    }
    off.push_back(static_cast<std::uint32_t>(tgt.size()));
  }
  build(off, tgt, options);
}

void HyperbolicTreeEmbedding::build(const std::vector<std::uint32_t>& off, const std::vector<Vertex>& tgt,
                                    const HyperbolicOptions& o) {
  const std::size_t n = off.size() - 1;
  if (n == 0) throw InputError("graph", 0, "found no vertex, expected a connected graph to embed");
  std::vector<std::uint32_t> dist;
  std::vector<Vertex> par;
  if (o.root != none && o.root >= n)
    throw InputError("root", 0, "found vertex " + std::to_string(o.root) + ", expected an index below " + std::to_string(n));
  Vertex root = o.root;
  if (root == none) {
    // Double sweep: the middle of a long shortest path approximates a centre, halving the depth
    // (hence the address length) compared with an arbitrary root.
    bfs(off, tgt, 0, dist, par);
    for (Vertex v = 0; v < n; ++v)
      if (dist[v] == std::numeric_limits<std::uint32_t>::max())
        throw InputError("graph", 0, "vertex " + std::to_string(v) + " is not connected to vertex 0, expected a connected graph");
    const Vertex a = farthest(dist);
    swept_ = true;
    sweep_start_depth_ = dist[a];
    bfs(off, tgt, a, dist, par);
    Vertex b = farthest(dist);
    sweep_length_ = dist[b];
    for (std::uint32_t steps = dist[b] / 2; steps > 0; --steps) b = par[b];
    root = b;
  }
  bfs(off, tgt, root, dist, par);
  for (Vertex v = 0; v < n; ++v)
    if (dist[v] == std::numeric_limits<std::uint32_t>::max())
      throw InputError("graph", 0, "vertex " + std::to_string(v) + " is not connected to the root " +
                                       std::to_string(root) + ", expected a connected graph");
  root_ = root;
  parent_ = par;
  depth_ = dist;
  // q: every node needs one side per tree neighbour (the root's children use sides 0..q−1, the
  // others' 1..q−1, side 0 facing the parent).
  std::vector<std::uint32_t> children(n, 0);
  for (Vertex v = 0; v < n; ++v)
    if (v != root) ++children[par[v]];
  std::uint32_t needed = 3;
  max_depth_ = 0;
  for (Vertex v = 0; v < n; ++v) {
    needed = std::max(needed, children[v] + (v == root ? 0 : 1));
    max_depth_ = std::max(max_depth_, dist[v]);
  }
  if (o.tiling_degree != 0 && o.tiling_degree < needed)
    throw InputError("tiling_degree", 0, "found " + std::to_string(o.tiling_degree) + ", expected at least " +
                                             std::to_string(needed) + " (3 and the spanning tree's maximum degree)");
  q_ = o.tiling_degree != 0 ? o.tiling_degree : needed;
  // Children take sides spread evenly over the free ones, in adjacency order: an only child sits
  // opposite its parent, so long chains run along geodesics rather than around an ideal vertex. For
  // odd q there are two middle sides; the spread is mirrored (j ↦ q − j) below odd-depth parents so
  // that a chain alternates between them (a zig-zag along a geodesic, not a horocycle).
  index_.assign(n, 0);
  for (Vertex v = 0; v < n; ++v) {
    std::uint64_t i = 0;  // 1-based rank of the child among v's (simple graph: each listed once)
    for (std::uint32_t k = off[v]; k < off[v + 1]; ++k) {
      const Vertex u = tgt[k];
      if (u == root || par[u] != v) continue;
      ++i;
      index_[u] = hyperbolic_child_side(q_, v == root, dist[v], static_cast<std::uint32_t>(i), children[v]);
    }
  }
  gen_ = evaluation_matrices(q_);
  if (o.coordinates == HyperbolicCoordinates::disc_double) disc_ = disc_boxes(*this, dist, par);
}

std::uint32_t hyperbolic_child_side(std::uint32_t q, bool root, std::uint32_t depth, std::uint32_t rank,
                                    std::uint32_t children) {
  LAGUERRE_PRECONDITION(rank >= 1 && rank <= children && children + (root ? 0 : 1) <= q,
                        "child " + std::to_string(rank) + " of " + std::to_string(children) + " with q = " +
                            std::to_string(q));
  const std::uint64_t i = rank, kids = children;
  if (root) return static_cast<std::uint32_t>((i - 1) * q / kids);
  const auto side = static_cast<std::uint32_t>(1 + (2 * i - 1) * (q - 1) / (2 * kids));
  return depth % 2 == 1 ? q - side : side;
}

std::vector<std::uint32_t> HyperbolicTreeEmbedding::address(Vertex v) const {
  std::vector<std::uint32_t> word(depth_.at(v));
  for (Vertex x = v; x != root_; x = parent_[x]) word[depth_[x] - 1] = index_[x];
  return word;
}

std::size_t hyperbolic_side_bits(std::uint32_t q) {
  std::size_t per_level = 0;
  while ((std::size_t{1} << per_level) < q) ++per_level;
  return per_level;
}

double HyperbolicTreeEmbedding::edge_length() const {
  return 2 * std::atanh(std::cos(std::acos(-1.0) / q_));
}

HyperbolicTreeEmbedding::Norm HyperbolicTreeEmbedding::norm(Vertex a, Vertex b) const {
  if (disc_.empty()) return address_norm(a, b);
  LAGUERRE_PRECONDITION(a < size() && b < size(), "hyperbolic distance between vertices " + std::to_string(a) +
                                                      " and " + std::to_string(b) + " of a " +
                                                      std::to_string(size()) + "-node embedding");
  if (a == b) return {2, 2, 0};
  // 2·cosh d = 2 + 4|w_a − w_b|² / ((1 − |w_a|²)(1 − |w_b|²)) on the boxes; a factor that may vanish
  // (a box touching the unit circle) makes the quotient unbounded, hence every comparison undecided.
  CGAL::Protect_FPU_rounding<true> guard;
  const double* pa = &disc_[4 * static_cast<std::size_t>(a)];
  const double* pb = &disc_[4 * static_cast<std::size_t>(b)];
  const I xa(pa[0], pa[1]), ya(pa[2], pa[3]), xb(pb[0], pb[1]), yb(pb[2], pb[3]);
  const I num = CGAL::square(xa - xb) + CGAL::square(ya - yb);
  const I den = (I(1) - CGAL::square(xa) - CGAL::square(ya)) * (I(1) - CGAL::square(xb) - CGAL::square(yb));
  if (!(den.inf() > 0)) return {2, std::numeric_limits<double>::infinity(), 0};
  const I f = I(2) + I(4) * num / den;
  return {f.inf(), f.sup(), 0};
}

std::span<const double> HyperbolicTreeEmbedding::disc_box(Vertex v) const {
  if (disc_.empty()) return {};
  return {&disc_[4 * static_cast<std::size_t>(v)], 4};
}

HyperbolicTreeEmbedding::Norm HyperbolicTreeEmbedding::address_norm(Vertex a, Vertex b) const {
  LAGUERRE_PRECONDITION(a < size() && b < size(), "hyperbolic distance between vertices " + std::to_string(a) +
                                                      " and " + std::to_string(b) + " of a " +
                                                      std::to_string(size()) + "-node embedding");
  if (a == b) return {2, 2, 0};
  // The sides met from a up to the common ancestor (a's first) and from b up to it (b's first).
  thread_local std::vector<std::uint32_t> up, down, turns;
  up.clear();
  down.clear();
  turns.clear();
  Vertex x = a, y = b;
  while (depth_[x] > depth_[y]) {
    up.push_back(index_[x]);
    x = parent_[x];
  }
  while (depth_[y] > depth_[x]) {
    down.push_back(index_[y]);
    y = parent_[y];
  }
  while (x != y) {
    up.push_back(index_[x]);
    x = parent_[x];
    down.push_back(index_[y]);
    y = parent_[y];
  }
  // M_a⁻¹M_b = H R_{−a_k} H ⋯ H R_{−a_1} R_{b_1} H ⋯ R_{b_m} H (H⁻¹ = ±H); rotations are orthogonal,
  // so the leading/trailing ones drop out of the Frobenius norm and the rest is H·G_{t_1}⋯G_{t_{L−1}}
  // with every turn t in [1, q) (a reduced path never turns back through the side it came from).
  const std::size_t k = up.size(), m = down.size();
  for (std::size_t i = 0; i + 1 < k; ++i) turns.push_back((q_ - up[i]) % q_);
  if (k > 0 && m > 0) turns.push_back((down[m - 1] + q_ - up[k - 1]) % q_);
  for (std::size_t i = m; i >= 2; --i) turns.push_back(down[i - 2]);
  CGAL::Protect_FPU_rounding<true> guard;
  // G_{t_1}⋯G_{t_{L−1}} = C·(P_{t_1}⋯P_{t_{L−1}})·C⁻¹ with nonnegative P: no cancellation, no
  // wrapping effect, relative error O(L·ε); only the two end factors can cancel, by a bounded amount.
  ScaledMatrix p;
  multiply(p, &gen_[0]);  // H·C
  for (const std::uint32_t t : turns) {
    LAGUERRE_ASSERT(t != 0);  // a reduced tree path never turns back
    multiply(p, &gen_[8 * t]);
  }
  multiply(p, &gen_[8 * static_cast<std::size_t>(q_)]);  // C⁻¹
  const I f = CGAL::square(p.a) + CGAL::square(p.b) + CGAL::square(p.c) + CGAL::square(p.d);
  return {f.inf(), f.sup(), p.e};
}

std::optional<Sign> HyperbolicTreeEmbedding::compare_distance(Vertex t, Vertex a, Vertex b) const {
  if (a == b) return Sign::zero;
  if (a == t) return Sign::negative;  // positions are distinct: d(t, t) = 0 < d(b, t)
  if (b == t) return Sign::positive;
  return compare_norms(norm(a, t), norm(b, t));
}

double HyperbolicTreeEmbedding::distance(Vertex a, Vertex b) const {
  if (a == b) return 0;
  const Norm f = address_norm(a, b);
  const double ln_f = std::log(0.5 * (f.lo + f.hi)) + f.exp * std::log(4.0);
  return ln_f > 30 ? ln_f : std::acosh(0.5 * std::exp(ln_f));  // acosh(F/2) = ln F − O(F⁻²)
}

std::size_t HyperbolicTreeEmbedding::address_bits(Vertex v) const { return depth_[v] * hyperbolic_side_bits(q_); }

std::size_t HyperbolicTreeEmbedding::disc_coordinate_bits(Vertex v) const {
  return 2 * (static_cast<std::size_t>(std::ceil(distance(root_, v) / std::log(2.0))) + 53);
}

HyperbolicSetupCost hyperbolic_setup_cost(const HyperbolicTreeEmbedding& e, std::size_t edges) {
  HyperbolicSetupCost c;
  const std::uint64_t n = e.size(), m = edges;
  const std::uint64_t bfs_runs = e.swept() ? 3 : 1;
  c.messages = bfs_runs * (2 * m + (n - 1)) + (n - 1) + 2 * (m - (n - 1));
  if (e.swept()) c.messages += e.sweep_start_depth() + (e.sweep_length() + 1) / 2;
  double sum = 0;
  for (Vertex v = 0; v < n; ++v) {
    const std::size_t bits = e.address_bits(v);
    sum += static_cast<double>(bits);
    c.address_bits_max = std::max(c.address_bits_max, bits);
    c.disc_bits_max = std::max(c.disc_bits_max, e.disc_coordinate_bits(v));
  }
  c.address_bits_mean = sum / static_cast<double>(n);
  return c;
}

HyperbolicHop hyperbolic_hop(const HyperbolicTreeEmbedding& e, std::span<const Vertex> neighbours, Vertex at,
                             Vertex target) {
  const std::size_t deg = neighbours.size();
  for (std::size_t i = 0; i < deg; ++i)
    if (neighbours[i] == target) return {i, true};
  thread_local std::vector<HyperbolicTreeEmbedding::Norm> norms;
  norms.resize(deg);
  const HyperbolicTreeEmbedding::Norm own = e.norm(at, target);
  // The candidate that may be least: the smallest upper bound (in the common scale of the comparison).
  std::size_t least = deg;
  for (std::size_t i = 0; i < deg; ++i) {
    norms[i] = e.norm(neighbours[i], target);
    if (least == deg || compare_norms(norms[i], norms[least]) == Sign::negative) least = i;
  }
  if (least == deg) return {deg, true};
  // Among those the enclosures cannot place above `least` (it included), the smallest index that is
  // certified strictly closer than the holder.
  std::size_t best = deg;
  bool any_undecided = false;
  for (std::size_t i = 0; i < deg; ++i) {
    if (i != least && compare_norms(norms[i], norms[least]) == Sign::positive) continue;
    const auto vs_own = compare_norms(norms[i], own);
    if (vs_own == Sign::negative) {
      if (best == deg || neighbours[i] < neighbours[best]) best = i;
    } else if (!vs_own) {
      any_undecided = true;
    }
  }
  if (best != deg) return {best, true};
  // Otherwise every possible minimiser is provably no closer than the holder, and every other
  // neighbour is above one of them: a certified dead end, unless some comparison was undecided.
  return {deg, !any_undecided};
}

}  // namespace laguerre::core
