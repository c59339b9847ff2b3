/// @file
/// The inverse problem for affine diagrams: exact recognition of power diagrams (see Recognition.hpp),
/// the cells-file reader and writer.

#include <CGAL/Exact_rational.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <tuple>
#include <type_traits>
#include <map>
#include <sstream>

#include "laguerre/core/diagrams/Recognition.hpp"
#include "laguerre/core/diagrams/SitesFile.hpp"

namespace laguerre::core {

namespace {

using Q = CGAL::Exact_rational;

struct QVec {
  Q x, y;
};
Q cross(const QVec& a, const QVec& b) { return a.x * b.y - a.y * b.x; }
Q dot(const QVec& a, const QVec& b) { return a.x * b.x + a.y * b.y; }
Q abs_q(const Q& v) { return v < 0 ? Q(-v) : v; }

/// Parses an integer text (optional sign, digits) exactly; false on anything else.
bool parse_integer(const std::string& s, Q& out) {
  std::size_t i = 0;
  bool negative = false;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) negative = s[i++] == '-';
  if (i == s.size()) return false;
  Q v(0);
  for (; i < s.size(); ++i) {
    if (s[i] < '0' || s[i] > '9') return false;
    v = v * 10 + (s[i] - '0');
  }
  out = negative ? Q(-v) : v;
  return true;
}

/// Parses a decimal (`-1.25`, `3e-2`) or a fraction (`1/3`) exactly.
bool parse_exact(const std::string& s, Q& out) {
  if (const auto slash = s.find('/'); slash != std::string::npos) {
    Q p, q;
    if (!parse_integer(s.substr(0, slash), p) || !parse_integer(s.substr(slash + 1), q) || q == 0) return false;
    out = p / q;
    return true;
  }
  std::string mantissa = s;
  long exponent = 0;
  if (const auto e = s.find_first_of("eE"); e != std::string::npos) {
    Q ex;
    const std::string et = s.substr(e + 1);
    if (et.empty() || et.size() > 6 || !parse_integer(et, ex)) return false;
    exponent = std::stol(et);
    mantissa = s.substr(0, e);
  }
  std::string digits;
  bool seen_dot = false, seen_digit = false;
  for (std::size_t i = 0; i < mantissa.size(); ++i) {
    const char c = mantissa[i];
    if ((c == '+' || c == '-') && i == 0) {
      digits += c;
    } else if (c == '.' && !seen_dot) {
      seen_dot = true;
    } else if (c >= '0' && c <= '9') {
      digits += c, seen_digit = true;
      if (seen_dot) --exponent;
    } else {
      return false;
    }
  }
  if (!seen_digit || std::abs(exponent) > 400) return false;
  Q v;
  if (!parse_integer(digits, v)) return false;
  Q ten(1);
  for (long k = 0; k < std::abs(exponent); ++k) ten = ten * 10;
  out = exponent >= 0 ? Q(v * ten) : Q(v / ten);
  return true;
}

/// Edge structure of a complex: finite edges (canonical u < v) then rays, with their left/right cells.
struct Topology {
  struct Edge {
    std::size_t from = 0;           ///< canonical start vertex
    std::optional<std::size_t> to;  ///< end vertex (none for a ray)
    std::size_t ray = 0;            ///< ray index when `to` is empty
    std::optional<std::size_t> left, right;
  };
  std::vector<Edge> edges;
  std::vector<std::vector<std::size_t>> at_vertex;  ///< incident edges per vertex
};

using Where = std::function<std::string(std::size_t cell)>;

Topology build_topology(const CellComplex& cx, const Where& where) {
  Topology t;
  t.at_vertex.resize(cx.vertices.size());
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> finite;
  auto check_vertex = [&](std::size_t c, std::size_t v) {
    if (v >= cx.vertices.size())
      throw CellComplexError(where(c) + "vertex " + std::to_string(v) + " does not exist; expected an index below " +
                             std::to_string(cx.vertices.size()) + ".");
  };
  auto add_side = [&](std::size_t e, bool left, std::size_t c, const std::string& what) {
    auto& side = left ? t.edges[e].left : t.edges[e].right;
    if (side)
      throw CellComplexError(where(c) + what + " is already used in the same direction by cell " +
                             std::to_string(*side) + "; expected each edge in two cells, once in each direction.");
    side = c;
  };
  for (std::size_t r = 0; r < cx.rays.size(); ++r) {
    if (cx.rays[r].vertex >= cx.vertices.size())
      throw CellComplexError("ray " + std::to_string(r) + ": vertex " + std::to_string(cx.rays[r].vertex) +
                             " does not exist.");
  }
  std::vector<std::size_t> ray_edge(cx.rays.size());
  for (std::size_t r = 0; r < cx.rays.size(); ++r) {
    ray_edge[r] = t.edges.size();
    t.edges.push_back({cx.rays[r].vertex, std::nullopt, r, std::nullopt, std::nullopt});
    t.at_vertex[cx.rays[r].vertex].push_back(ray_edge[r]);
  }
  for (std::size_t c = 0; c < cx.cells.size(); ++c) {
    const CellComplex::Cell& cell = cx.cells[c];
    if (cell.vertices.empty()) throw CellComplexError(where(c) + "a cell without vertices; expected at least one.");
    if (cell.ray_in.has_value() != cell.ray_out.has_value())
      throw CellComplexError(where(c) + "an unbounded cell needs an incoming and an outgoing ray.");
    const bool bounded = !cell.ray_in;
    if (bounded && cell.vertices.size() < 3)
      throw CellComplexError(where(c) + "a bounded cell with " + std::to_string(cell.vertices.size()) +
                             " vertices; expected at least 3.");
    for (std::size_t v : cell.vertices) check_vertex(c, v);
    const std::size_t k = cell.vertices.size(), steps = bounded ? k : k - 1;
    for (std::size_t m = 0; m < steps; ++m) {
      const std::size_t a = cell.vertices[m], b = cell.vertices[(m + 1) % k];
      if (a == b) throw CellComplexError(where(c) + "vertex " + std::to_string(a) + " repeated consecutively.");
      const auto key = std::minmax(a, b);
      auto [it, fresh] = finite.emplace(std::pair{key.first, key.second}, t.edges.size());
      if (fresh) {
        t.edges.push_back({key.first, key.second, 0, std::nullopt, std::nullopt});
        t.at_vertex[a].push_back(it->second);
        t.at_vertex[b].push_back(it->second);
      }
      add_side(it->second, a < b, c, "edge " + std::to_string(a) + "-" + std::to_string(b));
    }
    if (!bounded) {
      for (auto [r, out] : {std::pair{*cell.ray_in, false}, std::pair{*cell.ray_out, true}}) {
        if (r >= cx.rays.size())
          throw CellComplexError(where(c) + "ray " + std::to_string(r) + " does not exist; expected an index below " +
                                 std::to_string(cx.rays.size()) + ".");
        const std::size_t expected = out ? cell.vertices.back() : cell.vertices.front();
        if (cx.rays[r].vertex != expected)
          throw CellComplexError(where(c) + "ray " + std::to_string(r) + " starts at vertex " +
                                 std::to_string(cx.rays[r].vertex) + "; expected vertex " + std::to_string(expected) +
                                 (out ? " (the last vertex of the cell)." : " (the first vertex of the cell)."));
        add_side(ray_edge[r], out, c, "ray " + std::to_string(r));
      }
    }
  }
  for (std::size_t e = 0; e < t.edges.size(); ++e) {
    const Topology::Edge& ed = t.edges[e];
    if (!ed.left || !ed.right) {
      const std::string name = ed.to ? "edge " + std::to_string(ed.from) + "-" + std::to_string(*ed.to)
                                     : "ray " + std::to_string(ed.ray);
      throw CellComplexError(where(ed.left ? *ed.left : ed.right ? *ed.right : 0) + name +
                             " borders only one cell; expected two cells on either side of every edge.");
    }
  }
  return t;
}

}  // namespace

RecognitionResult recognize_power_diagram(const CellComplex& cx, const RecognitionOptions& options) {
  const Topology topo = build_topology(cx, [](std::size_t c) { return "cell " + std::to_string(c) + ": "; });
  const std::size_t V = cx.vertices.size(), E = topo.edges.size();
  // Exact coordinates: the decimal text when present, else the double itself.
  auto exact = [](const std::string& text, double value, const std::string& what) {
    Q q;
    if (text.empty()) {
      if (!std::isfinite(value)) throw CellComplexError(what + " is not finite.");
      return Q(value);
    }
    if (!parse_exact(text, q)) throw CellComplexError(what + ": `" + text + "` is not a decimal or a fraction.");
    return q;
  };
  std::vector<QVec> P(V);
  for (std::size_t v = 0; v < V; ++v) {
    const bool t = v < cx.vertex_text.size();
    const std::string what = "vertex " + std::to_string(v);
    P[v] = {exact(t ? cx.vertex_text[v][0] : "", cx.vertices[v].x, what), exact(t ? cx.vertex_text[v][1] : "", cx.vertices[v].y, what)};
  }
  std::vector<QVec> ray_dir(cx.rays.size());
  for (std::size_t r = 0; r < cx.rays.size(); ++r) {
    const std::string what = "ray " + std::to_string(r);
    ray_dir[r] = {exact(cx.rays[r].text[0], cx.rays[r].direction.x, what), exact(cx.rays[r].text[1], cx.rays[r].direction.y, what)};
  }
  // Canonical edge vector and the vector pointing away from vertex v.
  auto edge_vec = [&](std::size_t e) -> QVec {
    const Topology::Edge& ed = topo.edges[e];
    if (!ed.to) return ray_dir[ed.ray];
    return {P[*ed.to].x - P[ed.from].x, P[*ed.to].y - P[ed.from].y};
  };
  auto outward = [&](std::size_t e, std::size_t v) -> QVec {
    QVec t = edge_vec(e);
    if (topo.edges[e].from != v) t = {-t.x, -t.y};
    return t;
  };
  const Q tau(options.tolerance);
  RecognitionResult result;

  // Convexity (strict left turns; a straight pass-through is allowed) of every corner.
  for (std::size_t c = 0; c < cx.cells.size(); ++c) {
    const CellComplex::Cell& cell = cx.cells[c];
    const std::size_t k = cell.vertices.size();
    const bool bounded = !cell.ray_in;
    for (std::size_t m = 0; m < k; ++m) {
      const std::size_t v = cell.vertices[m];
      QVec in, out;
      if (!bounded && m == 0) {
        in = {-ray_dir[*cell.ray_in].x, -ray_dir[*cell.ray_in].y};
      } else {
        const std::size_t u = cell.vertices[(m + k - 1) % k];
        in = {P[v].x - P[u].x, P[v].y - P[u].y};
      }
      if (!bounded && m + 1 == k) {
        out = ray_dir[*cell.ray_out];
      } else {
        const std::size_t w = cell.vertices[(m + 1) % k];
        out = {P[w].x - P[v].x, P[w].y - P[v].y};
      }
      const Q turn = cross(in, out);
      if (turn < 0 || (turn == 0 && dot(in, out) <= 0))
        result.broken.push_back({"convexity", c, v, {c}, CGAL::to_double(turn)});
    }
  }

  // Local closure of the cycle of bisectors around every bounded cell whose vertices have degree 3.
  for (std::size_t c = 0; c < cx.cells.size(); ++c) {
    const CellComplex::Cell& cell = cx.cells[c];
    if (cell.ray_in) continue;
    const std::size_t k = cell.vertices.size();
    Q num(1), den(1);
    bool usable = true;
    std::vector<std::size_t> cycle;
    for (std::size_t m = 0; m < k && usable; ++m) {
      const std::size_t v = cell.vertices[m], u = cell.vertices[(m + k - 1) % k], w = cell.vertices[(m + 1) % k];
      if (topo.at_vertex[v].size() != 3) {
        usable = false;
        break;
      }
      QVec tp{P[u].x - P[v].x, P[u].y - P[v].y}, tn{P[w].x - P[v].x, P[w].y - P[v].y}, t3;
      for (std::size_t e : topo.at_vertex[v]) {
        const Topology::Edge& ed = topo.edges[e];
        const bool is_p = ed.to && std::minmax(u, v) == std::minmax(ed.from, *ed.to);
        const bool is_n = ed.to && std::minmax(w, v) == std::minmax(ed.from, *ed.to);
        if (!is_p && !is_n) t3 = outward(e, v);
      }
      // λ_n / λ_p = −cross(t_p, t_3) / cross(t_n, t_3).
      const Q a = -cross(tp, t3), b = cross(tn, t3);
      if (b == 0 || a == 0) {
        usable = false;
        break;
      }
      num = num * a, den = den * b;
      // The neighbour across the edge (v, w).
      for (std::size_t e : topo.at_vertex[v]) {
        const Topology::Edge& ed = topo.edges[e];
        if (ed.to && std::minmax(w, v) == std::minmax(ed.from, *ed.to)) cycle.push_back(*ed.left == c ? *ed.right : *ed.left);
      }
    }
    if (!usable) continue;
    const Q defect = abs_q(num / den - 1);
    if (defect > tau * static_cast<int>(k)) result.broken.push_back({"cell", c, cell.vertices[0], cycle, CGAL::to_double(defect)});
  }

  // Propagation of the multipliers λ along the primal graph (λ = 1 on edge 0), verification of the
  // vertex equations, integration of f_c = a_c·x + b_c over the dual graph from cell 0 (a = 0, b = 0).
  // NT = Q: exact (the decision for complexes with vertices of degree ≠ 3); NT = long double: only
  // the recovery of the sites once the local tests have decided (degree 3 everywhere), because exact
  // λ grow by a few digits per propagation step.
  struct Outcome {
    bool holds = true;
    std::vector<BrokenCycle> vertex_failures;
    std::vector<WeightedPoint> sites;
  };
  const std::size_t C = cx.cells.size();
  auto run = [&]<class NT>(bool check) {
    struct V2 {
      NT x, y;
    };
    auto to_nt = [](const Q& q) {
      if constexpr (std::is_same_v<NT, Q>) return q;
      else return static_cast<NT>(CGAL::to_double(q));
    };
    auto to_d = [](const NT& v) {
      if constexpr (std::is_same_v<NT, Q>) return CGAL::to_double(v);
      else return static_cast<double>(v);
    };
    auto absn = [](const NT& v) { return v < 0 ? NT(-v) : v; };
    std::vector<V2> PN(V), RN(ray_dir.size());
    for (std::size_t v = 0; v < V; ++v) PN[v] = {to_nt(P[v].x), to_nt(P[v].y)};
    for (std::size_t r = 0; r < ray_dir.size(); ++r) RN[r] = {to_nt(ray_dir[r].x), to_nt(ray_dir[r].y)};
    auto evec = [&](std::size_t e) -> V2 {
      const Topology::Edge& ed = topo.edges[e];
      if (!ed.to) return RN[ed.ray];
      return {PN[*ed.to].x - PN[ed.from].x, PN[*ed.to].y - PN[ed.from].y};
    };
    auto out_vec = [&](std::size_t e, std::size_t v) -> V2 {
      V2 t = evec(e);
      if (topo.edges[e].from != v) t = {-t.x, -t.y};
      return t;
    };
    auto crs = [](const V2& p, const V2& q) { return NT(p.x * q.y - p.y * q.x); };
    auto dt = [](const V2& p, const V2& q) { return NT(p.x * q.x + p.y * q.y); };
    Outcome o;
    std::vector<std::optional<NT>> lambda(E);
    std::vector<std::size_t> queue;
    auto set_lambda = [&](std::size_t e, const NT& value) {
      lambda[e] = value;
      queue.push_back(topo.edges[e].from);
      if (topo.edges[e].to) queue.push_back(*topo.edges[e].to);
    };
    if (E > 0) set_lambda(0, NT(1));
    std::vector<char> settled(V, 0);
    for (;;) {
      while (!queue.empty()) {
        const std::size_t v = queue.back();
        queue.pop_back();
        if (settled[v]) continue;
        V2 known{NT(0), NT(0)};
        std::vector<std::size_t> unknown;
        for (std::size_t e : topo.at_vertex[v]) {
          if (lambda[e]) {
            const V2 t = out_vec(e, v);
            known.x += *lambda[e] * t.x, known.y += *lambda[e] * t.y;
          } else {
            unknown.push_back(e);
          }
        }
        if (unknown.empty()) {
          settled[v] = 1;
        } else if (unknown.size() == 1) {
          const V2 t = out_vec(unknown[0], v);
          const NT tt = dt(t, t);
          if (tt == 0) continue;
          set_lambda(unknown[0], NT(-dt(known, t) / tt));  // checked with the vertex equations below
          settled[v] = 1;
        } else if (unknown.size() == 2) {
          const V2 t1 = out_vec(unknown[0], v), t2 = out_vec(unknown[1], v);
          const NT det = crs(t1, t2);
          if (det == 0) continue;
          // λ1 t1 + λ2 t2 = −known.
          set_lambda(unknown[0], NT(crs(t2, known) / det));
          set_lambda(unknown[1], NT(crs(known, t1) / det));
          settled[v] = 1;
        }
      }
      // Stuck (vertices of degree ≥ 4, or parallel edges): free multipliers are set to 1.
      std::optional<std::size_t> free_edge;
      for (std::size_t v = 0; v < V && !free_edge; ++v) {
        bool touched = false;
        for (std::size_t e : topo.at_vertex[v]) touched = touched || lambda[e].has_value();
        if (!touched) continue;
        for (std::size_t e : topo.at_vertex[v])
          if (!lambda[e]) {
            free_edge = e;
            break;
          }
      }
      if (!free_edge) break;
      set_lambda(*free_edge, NT(1));
    }
    const NT tau_nt = to_nt(tau);
    for (std::size_t v = 0; v < V && check; ++v) {
      V2 sum{NT(0), NT(0)};
      NT norm(0);
      bool positive = true;
      for (std::size_t e : topo.at_vertex[v]) {
        if (!lambda[e] || !(*lambda[e] > 0)) positive = false;
        if (!lambda[e]) continue;
        const V2 t = out_vec(e, v);
        sum.x += *lambda[e] * t.x, sum.y += *lambda[e] * t.y;
        norm += absn(*lambda[e]) * (absn(t.x) + absn(t.y));
      }
      if (positive && absn(sum.x) <= tau_nt * norm && absn(sum.y) <= tau_nt * norm) continue;
      o.holds = false;
      BrokenCycle b{"vertex", 0, v, {}, norm > 0 ? to_d(NT((absn(sum.x) + absn(sum.y)) / norm)) : 1.0};
      // The cells around v, counter-clockwise (left cells of the outward edges sorted by angle).
      std::vector<std::pair<double, std::size_t>> around;
      for (std::size_t e : topo.at_vertex[v]) {
        const V2 t = out_vec(e, v);
        const Topology::Edge& ed = topo.edges[e];
        around.emplace_back(std::atan2(to_d(t.y), to_d(t.x)), ed.from == v ? *ed.left : *ed.right);
      }
      std::sort(around.begin(), around.end());
      for (const auto& [angle, cell] : around) b.cycle.push_back(cell);
      o.vertex_failures.push_back(std::move(b));
    }
    if (!o.holds) return o;
    for (std::size_t e = 0; e < E; ++e)
      if (!lambda[e]) lambda[e] = NT(1);  // only for unreached parts (a disconnected complex)
    std::vector<std::optional<std::pair<V2, NT>>> f(C);
    std::vector<std::vector<std::size_t>> cell_edges(C);
    for (std::size_t e = 0; e < E; ++e) cell_edges[*topo.edges[e].left].push_back(e), cell_edges[*topo.edges[e].right].push_back(e);
    std::vector<std::size_t> stack;
    if (C > 0) f[0] = std::pair{V2{NT(0), NT(0)}, NT(0)}, stack.push_back(0);
    while (!stack.empty()) {
      const std::size_t c = stack.back();
      stack.pop_back();
      for (std::size_t e : cell_edges[c]) {
        const Topology::Edge& ed = topo.edges[e];
        const std::size_t L = *ed.left, R = *ed.right, other = L == c ? R : L;
        if (f[other]) continue;
        const V2 t = evec(e);
        const V2 diff{NT(t.y * *lambda[e]), NT(-t.x * *lambda[e])};  // a_L − a_R = −λ·rot90(t)
        const NT bdiff = -dt(diff, PN[ed.from]);                      // b_L − b_R
        const auto& [a, bb] = *f[c];
        if (c == L)
          f[other] = std::pair{V2{NT(a.x - diff.x), NT(a.y - diff.y)}, NT(bb - bdiff)};
        else
          f[other] = std::pair{V2{NT(a.x + diff.x), NT(a.y + diff.y)}, NT(bb + bdiff)};
        stack.push_back(other);
      }
    }
    o.sites.resize(C);
    for (std::size_t c = 0; c < C; ++c) {
      if (!f[c]) continue;
      const auto& [a, bb] = *f[c];
      const NT px = -a.x / 2, py = -a.y / 2;
      o.sites[c] = {to_d(px), to_d(py), to_d(NT(px * px + py * py - bb))};
    }
    return o;
  };

  bool all_degree_3 = true;
  for (std::size_t v = 0; v < V; ++v) all_degree_3 = all_degree_3 && topo.at_vertex[v].size() == 3;
  Outcome outcome;
  if (result.broken.empty()) {
    if (all_degree_3)
      outcome = run.template operator()<long double>(false);
    else
      outcome = run.template operator()<Q>(true);
  }
  if (!outcome.holds) result.broken = std::move(outcome.vertex_failures);

  if (!result.broken.empty()) {
    std::sort(result.broken.begin(), result.broken.end(), [](const BrokenCycle& a, const BrokenCycle& b) {
      return std::tie(a.kind, a.cell, a.vertex) < std::tie(b.kind, b.cell, b.vertex);
    });
    const BrokenCycle& first = result.broken.front();
    std::ostringstream msg;
    msg << "not a power diagram: ";
    if (first.kind == "cell")
      msg << "the cycle of bisectors around cell " << first.cell << " does not close (defect " << first.defect << ")";
    else if (first.kind == "convexity")
      msg << "cell " << first.cell << " is not convex at vertex " << first.vertex;
    else
      msg << "no positive multipliers satisfy the equation at vertex " << first.vertex;
    msg << "; " << result.broken.size() << " broken cycle(s) in all.";
    result.message = msg.str();
    return result;
  }
  result.sites = std::move(outcome.sites);
  result.is_power_diagram = true;
  result.message = "a power diagram: sites and weights recovered (site of cell 0 at the origin with weight 0).";
  return result;
}

CellComplex read_cell_complex(const std::string& path) {
  CellComplex cx;
  std::vector<std::size_t> cell_line;
  for (const InputLine& record : read_input_lines(path, "cells file")) {
    const std::vector<std::string>& w = record.words;
    const std::size_t number = record.number;
    const std::string where = path + ":" + std::to_string(number) + ": ";
    auto number_at = [&](std::size_t i) {
      Q exact;
      if (!parse_exact(w[i], exact))
        throw CellComplexError(where + "found `" + w[i] + "`; expected a decimal or a fraction p/q.");
      return CGAL::to_double(exact);
    };
    auto index_at = [&](const std::string& s, const std::string& what) {
      std::size_t used = 0;
      unsigned long long v = 0;
      try {
        v = std::stoull(s, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != s.size() || s.empty() || s[0] == '-')
        throw CellComplexError(where + "found `" + s + "`; expected " + what + ".");
      return static_cast<std::size_t>(v);
    };
    if (w[0] == "v") {
      if (w.size() != 3) throw CellComplexError(where + "found " + std::to_string(w.size() - 1) + " fields after `v`; expected `v X Y`.");
      cx.vertices.push_back({number_at(1), number_at(2)});
      cx.vertex_text.push_back({w[1], w[2]});
    } else if (w[0] == "r") {
      if (w.size() != 4) throw CellComplexError(where + "found " + std::to_string(w.size() - 1) + " fields after `r`; expected `r V DX DY`.");
      CellComplex::Ray r;
      r.vertex = index_at(w[1], "a vertex index");
      if (r.vertex >= cx.vertices.size())
        throw CellComplexError(where + "vertex " + w[1] + " is not defined yet; expected an index below " + std::to_string(cx.vertices.size()) + ".");
      r.direction = {number_at(2), number_at(3)};
      if (r.direction.x == 0 && r.direction.y == 0) throw CellComplexError(where + "a ray with direction (0, 0); expected a non-zero direction.");
      r.text = {w[2], w[3]};
      cx.rays.push_back(r);
    } else if (w[0] == "c") {
      CellComplex::Cell cell;
      std::size_t first = 1, last = w.size();
      if (w.size() >= 2 && w[1][0] == 'r') {
        cell.ray_in = index_at(w[1].substr(1), "a ray index after `r`");
        if (w.back()[0] != 'r') throw CellComplexError(where + "an unbounded cell must end with an outgoing ray `rB`.");
        cell.ray_out = index_at(w.back().substr(1), "a ray index after `r`");
        first = 2, last = w.size() - 1;
      }
      for (std::size_t i = first; i < last; ++i) cell.vertices.push_back(index_at(w[i], "a vertex index"));
      cx.cells.push_back(cell);
      cell_line.push_back(number);
    } else {
      throw CellComplexError(where + "found `" + w[0] + "`; expected a record `v`, `r` or `c`.");
    }
  }
  build_topology(cx, [&](std::size_t c) {
    return path + ":" + std::to_string(c < cell_line.size() ? cell_line[c] : 0) + ": cell " + std::to_string(c) + ": ";
  });
  return cx;
}

std::string format_cell_complex(const CellComplex& cx) {
  std::ostringstream out;
  auto num = [](double v, const std::string& text) {
    if (!text.empty()) return text;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return std::string(buf);
  };
  out << "# laguerre cells file: v X Y | r V DX DY | c V0 .. Vk | c rA V0 .. Vk rB\n";
  for (std::size_t v = 0; v < cx.vertices.size(); ++v) {
    const bool has_text = v < cx.vertex_text.size();
    out << "v " << num(cx.vertices[v].x, has_text ? cx.vertex_text[v][0] : "") << ' '
        << num(cx.vertices[v].y, has_text ? cx.vertex_text[v][1] : "") << '\n';
  }
  for (const CellComplex::Ray& r : cx.rays)
    out << "r " << r.vertex << ' ' << num(r.direction.x, r.text[0]) << ' ' << num(r.direction.y, r.text[1]) << '\n';
  for (const CellComplex::Cell& c : cx.cells) {
    out << 'c';
    if (c.ray_in) out << " r" << *c.ray_in;
    for (std::size_t v : c.vertices) out << ' ' << v;
    if (c.ray_out) out << " r" << *c.ray_out;
    out << '\n';
  }
  return out.str();
}

}  // namespace laguerre::core
