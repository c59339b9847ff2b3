// Every sensor routed: links, attachment to the core, planarization routing, all-pairs evaluation.
#include "laguerre/scenarios/fields/SensorNetwork.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/geometry/Delaunay.hpp"
#include "laguerre/core/graph/Embedding.hpp"
#include "laguerre/core/random/Random.hpp"
#include "laguerre/core/routing/Router.hpp"

namespace laguerre::scenarios {

using core::Route;
using core::RouteOutcome;
using core::Vertex;

namespace {

constexpr std::uint32_t kFar = std::numeric_limits<std::uint32_t>::max();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Compressed adjacency of an edge list on n vertices, rows sorted.
struct Csr {
  std::vector<std::size_t> offset;
  std::vector<Vertex> list;
  Csr(std::size_t n, const EdgeList& edges) : offset(n + 1, 0), list(2 * edges.size()) {
    for (auto [a, b] : edges) ++offset[a + 1], ++offset[b + 1];
    for (std::size_t v = 0; v < n; ++v) offset[v + 1] += offset[v];
    std::vector<std::size_t> fill(offset.begin(), offset.end() - 1);
    for (auto [a, b] : edges) list[fill[a]++] = b, list[fill[b]++] = a;
    for (std::size_t v = 0; v < n; ++v)
      std::sort(list.begin() + static_cast<std::ptrdiff_t>(offset[v]), list.begin() + static_cast<std::ptrdiff_t>(offset[v + 1]));
  }
  std::span<const Vertex> operator[](std::size_t v) const { return {list.data() + offset[v], offset[v + 1] - offset[v]}; }
  std::size_t size() const { return offset.size() - 1; }
};

/// Multi-source BFS from `sources` (in the order given); returns the queue (visit order).
std::vector<Vertex> bfs(const Csr& g, std::span<const Vertex> sources, std::vector<std::uint32_t>& dist) {
  std::vector<Vertex> queue(sources.begin(), sources.end());
  for (Vertex s : sources) dist[s] = 0;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const Vertex v = queue[head];
    for (Vertex w : g[v])
      if (dist[w] == kFar) {
        dist[w] = dist[v] + 1;
        queue.push_back(w);
      }
  }
  return queue;
}

/// The tree path from v up to (and including) `stop`, which must be an ancestor of v.
void climb(const Attachment& a, Vertex v, Vertex stop, std::vector<Vertex>& out) {
  out.push_back(v);
  while (v != stop) out.push_back(v = a.parent[v]);
}

/// The lowest common ancestor of u and v in one tree.
Vertex lowest_common_ancestor(const Attachment& a, Vertex u, Vertex v) {
  while (a.depth[u] > a.depth[v]) u = a.parent[u];
  while (a.depth[v] > a.depth[u]) v = a.parent[v];
  while (u != v) u = a.parent[u], v = a.parent[v];
  return u;
}

/// s up to `top_s`, then `middle` (sensor ids, from top_s to top_t), then down from top_t to t.
Route tree_route(const Attachment& a, Vertex s, Vertex top_s, const std::vector<Vertex>& middle, Vertex top_t, Vertex t) {
  Route r;
  r.outcome = RouteOutcome::delivered;
  climb(a, s, top_s, r.path);
  r.path.insert(r.path.end(), middle.begin() + (middle.empty() ? 0 : 1), middle.end());
  std::vector<Vertex> down;
  climb(a, t, top_t, down);
  r.path.insert(r.path.end(), down.rbegin() + 1, down.rend());
  return r;
}

}  // namespace

EdgeList link_edges(std::span<const core::Point2> points, const LinkOptions& options) {
  EdgeList udg = unit_disk_edges(points, options.radius);
  if (!options.quasi) return udg;
  LAGUERRE_PRECONDITION(options.inner_ratio > 0 && options.inner_ratio <= 1 && options.probability >= 0 &&
                            options.probability <= 1,
                        "quasi-unit-disk links need an inner ratio in (0, 1] and a probability in [0, 1].");
  const double inner = options.inner_ratio * options.radius;
  EdgeList out;
  for (auto [a, b] : udg) {
    if (core::compare_length(points[a], points[b], inner) != core::Sign::positive) {
      out.emplace_back(a, b);
      continue;
    }
    const std::uint64_t h = core::splitmix64(options.seed ^ core::splitmix64((std::uint64_t{a} << 32) | b));
    if (core::to_unit_double(h) < options.probability) out.emplace_back(a, b);
  }
  return out;
}

EdgeList common_edges(const EdgeList& a, const EdgeList& b) {
  EdgeList out;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

Attachment attach_to_core(std::size_t n, const EdgeList& links, const core::PlanarGraph& core) {
  const Csr g(n, links);
  Attachment a;
  a.anchor.assign(n, core::none);
  a.parent.assign(n, core::none);
  a.depth.assign(n, kFar);
  a.component.assign(n, 0);
  a.core_vertex.assign(n, core::none);
  std::vector<Vertex> roots;
  for (Vertex v = 0; v < core.num_vertices(); ++v) {
    const auto s = static_cast<Vertex>(core.id(v));
    LAGUERRE_PRECONDITION(s < n, "core vertex id " + std::to_string(s) + " is not a sensor.");
    a.core_vertex[s] = v;
    roots.push_back(s);
  }
  std::sort(roots.begin(), roots.end());
  // One tree per BFS wave: first from the core, then from the smallest sensor not reached yet.
  const auto grow = [&](std::span<const Vertex> sources, bool core_wave) {
    const std::vector<Vertex> order = bfs(g, sources, a.depth);
    const Vertex label = *std::min_element(order.begin(), order.end());
    for (Vertex v : order) {  // by increasing depth: the parent is settled first
      a.component[v] = label;
      if (!core_wave) ++a.stray;
      if (a.depth[v] == 0) {
        a.parent[v] = a.anchor[v] = v;
        continue;
      }
      for (Vertex w : g[v])  // rows are sorted: the first neighbour one hop closer is the smallest
        if (a.depth[w] + 1 == a.depth[v]) {
          a.parent[v] = w;
          break;
        }
      a.anchor[v] = a.anchor[a.parent[v]];
      if (core_wave) ++a.attached;
    }
  };
  if (!roots.empty()) grow(roots, true);
  for (Vertex v = 0; v < n; ++v)
    if (a.depth[v] == kFar) {
      const Vertex root[] = {v};
      grow(root, false);
    }
  return a;
}

SensorRouter attached_router(const SensorNetwork& net, const core::PlanarGraph& core, const core::CircleEmbedding& phi) {
  auto router = std::make_shared<core::Router>(core, phi);  // scratch reused across packets
  return [&net, &core, router](Vertex s, Vertex t) -> Route {
    const Attachment& a = net.attachment;
    if (a.component[s] != a.component[t]) return Route{RouteOutcome::dead_end, {s}, s};
    if (a.anchor[s] == a.anchor[t]) {
      const Vertex m = lowest_common_ancestor(a, s, t);
      return tree_route(a, s, m, {}, m, t);
    }
    // Different anchors in one component: both are core sensors (other components are single trees).
    const Vertex as = a.anchor[s], at = a.anchor[t];
    const Route inner = router->route(core::Scheme::greedy_power, a.core_vertex[as], a.core_vertex[at]);
    std::vector<Vertex> middle;
    for (Vertex v : inner.path) middle.push_back(static_cast<Vertex>(core.id(v)));
    if (inner.outcome != RouteOutcome::delivered) {
      Route r;
      r.outcome = inner.outcome;
      climb(a, s, as, r.path);
      r.path.insert(r.path.end(), middle.begin() + 1, middle.end());
      r.stuck = static_cast<Vertex>(core.id(inner.stuck));
      return r;
    }
    return tree_route(a, s, as, middle, at, t);
  };
}

PlanarizationRouter::PlanarizationRouter(const SensorNetwork& net) {
  const std::size_t n = net.points.size();
  part_of_.assign(n, std::numeric_limits<std::size_t>::max());
  local_.assign(n, core::none);
  const Csr g(n, net.planar);
  std::vector<std::uint32_t> dist(n, kFar);
  for (Vertex v = 0; v < n; ++v) {
    if (dist[v] != kFar || g[v].empty()) continue;
    const Vertex source[] = {v};
    std::vector<Vertex> members = bfs(g, source, dist);
    std::sort(members.begin(), members.end());
    for (std::size_t i = 0; i < members.size(); ++i) {
      part_of_[members[i]] = parts_.size();
      local_[members[i]] = static_cast<Vertex>(i);
    }
    std::vector<std::uint64_t> ids(members.begin(), members.end());
    std::vector<core::Point2> positions;
    Part part;
    for (Vertex m : members) {
      positions.push_back(net.points[m]);
      part.positions.push_back({net.points[m].x, net.points[m].y, 0.0});
    }
    std::vector<std::pair<Vertex, Vertex>> local;
    for (auto [a, b] : net.planar)
      if (part_of_[a] == parts_.size()) local.emplace_back(local_[a], local_[b]);
    part.graph = core::graph_from_drawing(std::move(ids), std::move(positions), local, "planarization", false).graph;
    parts_.push_back(std::move(part));
  }
  for (const Part& part : parts_) routers_.push_back(std::make_unique<core::Router>(part.graph, part.positions));
}

SensorRouter PlanarizationRouter::router(core::Scheme s) const {
  return [this, s](Vertex source, Vertex target) -> Route {
    if (source == target) return Route{RouteOutcome::delivered, {source}, core::none};
    const std::size_t p = part_of_[source];
    if (p == std::numeric_limits<std::size_t>::max() || p != part_of_[target])
      return Route{RouteOutcome::dead_end, {source}, source};
    const Part& part = parts_[p];
    Route r = routers_[p]->route(s, local_[source], local_[target]);
    for (Vertex& v : r.path) v = static_cast<Vertex>(part.graph.id(v));
    if (r.stuck != core::none) r.stuck = static_cast<Vertex>(part.graph.id(r.stuck));
    return r;
  };
}

std::vector<AllPairsStats> evaluate_all_pairs(const SensorNetwork& net, std::span<const SensorRouter> routers,
                                              const core::PairSelection& selection) {
  const std::size_t n = net.points.size();
  const Csr g(n, net.links);
  const Attachment& a = net.attachment;
  LAGUERRE_PRECONDITION(a.component.size() == n, "evaluate_all_pairs needs the attachment of every sensor.");
  std::vector<AllPairsStats> out(routers.size());
  std::vector<std::vector<double>> stretches(routers.size());
  std::vector<double> stretch_sum(routers.size(), 0), hops_sum(routers.size(), 0);
  std::vector<std::uint32_t> dist(n, kFar);
  Vertex bfs_source = core::none;
  for (const auto& [s, t] : core::select_pairs(n, selection)) {
    if (s != bfs_source) {
      std::fill(dist.begin(), dist.end(), kFar);
      const Vertex source[] = {s};
      (void)bfs(g, source, dist);
      bfs_source = s;
    }
    for (std::size_t k = 0; k < routers.size(); ++k) {
      AllPairsStats& st = out[k];
      ++st.pairs;
      if (dist[t] == kFar) {
        ++st.disconnected;
        continue;
      }
      const Route r = routers[k](s, t);
      if (r.outcome != RouteOutcome::delivered) continue;
      ++st.delivered;
      for (std::size_t i = 0; i + 1 < r.path.size(); ++i) {
        const auto row = g[r.path[i]];
        if (!std::binary_search(row.begin(), row.end(), r.path[i + 1])) {
          ++st.invalid_routes;
          break;
        }
      }
      const double hops = static_cast<double>(r.hops());
      const double stretch = hops / static_cast<double>(dist[t]);
      hops_sum[k] += hops;
      stretch_sum[k] += stretch;
      st.stretch_max = std::max(st.stretch_max, stretch);
      stretches[k].push_back(stretch);
    }
  }
  for (std::size_t k = 0; k < routers.size(); ++k) {
    AllPairsStats& st = out[k];
    const std::size_t connected = st.pairs - st.disconnected;
    st.delivery_rate = connected == 0 ? kNaN : static_cast<double>(st.delivered) / static_cast<double>(connected);
    if (st.delivered == 0) {
      st.stretch_mean = st.stretch_p95 = st.stretch_max = st.hops_mean = kNaN;
    } else {
      st.stretch_mean = stretch_sum[k] / static_cast<double>(st.delivered);
      st.hops_mean = hops_sum[k] / static_cast<double>(st.delivered);
      st.stretch_p95 = core::nearest_rank_percentile(stretches[k], 95);
    }
  }
  return out;
}

}  // namespace laguerre::scenarios
