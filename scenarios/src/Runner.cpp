// Expanding a scenario into runs and executing them on worker threads.
#include "laguerre/scenarios/Runner.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <thread>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/random/Random.hpp"
#include "laguerre/core/routing/HyperbolicEmbedding.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"
#include "laguerre/scenarios/ProtocolRun.hpp"
#include "laguerre/sim/LiveCluster.hpp"  // append_bytes, read_bytes

namespace laguerre::scenarios {

std::uint64_t derive_run_seed(std::uint64_t scenario_seed, std::size_t point, std::size_t repetition) {
  return splitmix64(splitmix64(splitmix64(scenario_seed) ^ static_cast<std::uint64_t>(point)) ^
                    static_cast<std::uint64_t>(repetition));
}

std::string canonical_text(const TopologySpec& topology) {
  std::map<std::string, std::string> sorted;
  for (const auto& [k, v] : topology.params.entries()) {
    std::string text = describe(v);
    if (const auto* p = std::get_if<Polygons>(&v)) {  // the polygons themselves, not their count
      text.clear();
      for (const auto& poly : *p) {
        text += "(";
        for (const auto& q : poly) text += std::to_string(q.x) + " " + std::to_string(q.y) + ",";
        text += ")";
      }
    }
    sorted[k] = text;
  }
  std::string s = topology.generator;
  for (const auto& [k, v] : sorted) s += ";" + k + "=" + v;
  return s;
}

std::uint64_t derive_topology_seed(std::uint64_t scenario_seed, const TopologySpec& topology, std::size_t repetition) {
  return splitmix64(splitmix64(splitmix64(scenario_seed) ^ fnv1a64(canonical_text(topology))) ^
                    static_cast<std::uint64_t>(repetition));
}

std::vector<RunPlan> plan_runs(const Scenario& scenario) {
  std::vector<RunPlan> plans;
  plans.reserve(scenario.points.size() * scenario.repetitions);
  for (const ScenarioPoint& p : scenario.points)
    for (std::size_t r = 0; r < scenario.repetitions; ++r)
      plans.push_back({p.index, r, derive_run_seed(scenario.seed, p.index, r),
                       derive_topology_seed(scenario.seed, p.config.topology, r)});
  return plans;
}

std::string_view to_string(RunStatus status) {
  switch (status) {
    case RunStatus::ok: return "ok";
    case RunStatus::not_converged: return "not_converged";
    case RunStatus::node_failed: return "node_failed";
    case RunStatus::unsupported: return "unsupported";
    case RunStatus::error: return "error";
  }
  return "?";
}

namespace {

core::CircleEmbedding point_circles(const std::vector<core::Point2>& positions) {
  core::CircleEmbedding out;
  out.reserve(positions.size());
  for (const auto& p : positions) out.push_back({p.x, p.y, 0.0});
  return out;
}

}  // namespace

RunRecord execute_run(const Scenario& scenario, const RunPlan& plan, RunArtifacts* artifacts,
                      sim::HostRunner* host_runner, const std::function<void(const ProtocolProgress&)>& on_progress) {
  const auto start = std::chrono::steady_clock::now();
  const ScenarioConfig& cfg = scenario.points.at(plan.point).config;
  RunRecord r;
  r.plan = plan;
  r.family = cfg.topology.generator;
  auto finish = [&] {
    r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
  };
  Topology topo;
  try {
    topo = build_topology(cfg.topology.generator, cfg.topology.params, plan.topology_seed, plan.repetition);
  } catch (const std::exception& e) {
    r.status = RunStatus::unsupported;
    r.message = e.what();
    return finish();
  }
  r.topology = topo.name;
  r.topology_note = topo.note;
  r.kind = std::string(core::to_string(topo.kind));
  const core::PlanarGraph& g = topo.graph;
  const std::size_t n = g.num_vertices();
  r.core_nodes = n;
  r.sensors = r.nodes = topo.sensors ? topo.sensors->points.size() : n;
  r.unreachable_sensors = topo.sensors ? topo.sensors->attachment.stray : 0;
  if (!topo.sensors && topo.family == "field") {  // a repaired field without attach: the deployment's size
    const auto& params = cfg.topology.params;
    r.sensors = static_cast<std::size_t>(params.integer("n", static_cast<std::int64_t>(n)));
  }
  r.edges = g.num_edges();
  try {
    ProtocolSetup setup;
    setup.asynchronous = cfg.protocol.asynchronous;
    setup.steps_per_round = cfg.protocol.steps_per_round;
    setup.max_iterations = cfg.protocol.max_iterations;
    setup.root = cfg.protocol.root;
    setup.acceleration = cfg.protocol.acceleration;
    setup.termination = cfg.protocol.termination;
    setup.link.latency = cfg.network.latency;
    setup.link.loss = cfg.network.loss;
    setup.link.duplication = cfg.network.duplication;
    setup.crashes = cfg.network.crashes;
    setup.retransmit_after = cfg.network.retransmit_after;
    setup.seed = plan.seed;
    setup.runner = host_runner;
    setup.on_progress = on_progress;
    ProtocolOutcome po;
    if (cfg.protocol.central) {
      // The same Jacobi iteration, centrally (core::pack), possibly accelerated; no messages.
      core::PackOptions opt;
      opt.stop = core::StopRule::lpd;
      opt.steps_per_check = cfg.protocol.steps_per_round;
      opt.max_iterations = cfg.protocol.max_iterations;
      opt.root = cfg.protocol.root;
      opt.acceleration = cfg.protocol.acceleration;
      opt.termination = cfg.protocol.termination;
      const auto t0 = std::chrono::steady_clock::now();
      core::PackResult pr = core::pack(g, opt);
      po.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      po.circles = std::move(pr.circles);
      po.local = std::move(pr.local);
      po.iterations = static_cast<std::uint32_t>(pr.iterations);
      po.rounds = static_cast<std::uint32_t>(pr.iterations / std::max(1, cfg.protocol.steps_per_round));
      for (const core::LocalCondition lc : po.local) po.holds_nodes += lc == core::LocalCondition::holds;
      po.converged_nodes = pr.status == core::PackStatus::converged ? n : po.holds_nodes;
    } else {
      po = run_packing_protocol(g, topo.positions, setup);
    }
    r.iterations = po.iterations;
    r.rounds = po.rounds;
    r.holds_nodes = po.holds_nodes;
    r.messages = po.messages;
    r.bytes = po.bytes;
    r.messages_per_node = n ? static_cast<double>(po.messages) / static_cast<double>(n) : 0.0;
    r.max_node_messages = po.max_node_messages;
    r.retransmissions = po.reliability.retransmissions;
    r.simulated_seconds = sim::to_seconds(po.simulated_time);
    r.events = po.events;
    if (po.failed_nodes > 0 || po.crashed_nodes > 0) {
      r.status = RunStatus::node_failed;
      r.message = std::to_string(po.failed_nodes) + " surviving node(s) ended with neighbour_failed after " +
                  std::to_string(po.crashed_nodes) + " crash(es); nothing routed";
      if (po.failed_nodes > 0) return finish();
    }
    r.status = po.converged() ? RunStatus::ok : RunStatus::not_converged;
    if (r.status == RunStatus::not_converged)
      r.message = std::to_string(po.converged_nodes) + "/" + std::to_string(n) +
                  " nodes converged (iteration cap); routed on the last layout";
    core::CircleEmbedding phi = std::move(po.circles);
    std::vector<core::LocalCondition> local = std::move(po.local);
    if (cfg.protocol.exact_reference || cfg.protocol.stop == StopSpec::exact) {
      core::PackOptions opt;
      opt.stop = core::StopRule::exact;
      opt.track_all = true;
      opt.steps_per_check = cfg.protocol.steps_per_round;
      opt.max_iterations = cfg.protocol.max_iterations;
      opt.root = cfg.protocol.root;
      core::PackResult pr = core::pack(g, opt);
      r.exact_iterations = pr.status == core::PackStatus::converged ? pr.iterations : -1;
      r.core_lpd_iterations = pr.first_lpd;
      if (cfg.protocol.stop == StopSpec::exact) {
        phi = std::move(pr.circles);
        local = std::move(pr.local);
        if (pr.status != core::PackStatus::converged && r.status == RunStatus::ok) {
          r.status = RunStatus::not_converged;
          r.message = "no exact packing within " + std::to_string(cfg.protocol.max_iterations) + " iterations";
        }
      }
    }
    // The coordinates of the geometric schemes.
    const bool physical = cfg.routing.positions == GeometricPositions::physical ||
                          (cfg.routing.positions == GeometricPositions::automatic && !topo.positions.empty());
    if (physical && topo.positions.empty())
      throw core::InputError("routing.positions", 0, "is physical but " + topo.name + " has no positions");
    const core::CircleEmbedding geo = physical ? point_circles(topo.positions) : core::CircleEmbedding{};
    const core::PairSelection selection{cfg.routing.pairs, plan.seed};
    for (core::Scheme s : cfg.routing.schemes) {
      const bool on_physical = physical && s != core::Scheme::greedy_power;
      const core::RoutingStats st = core::evaluate_routing(g, on_physical ? geo : phi, s, selection);
      SchemeResult sr;
      sr.scheme = s;
      sr.pairs = st.pairs;
      sr.delivered = st.delivered;
      sr.delivery_rate = st.delivery_rate;
      sr.stretch_mean = st.stretch_mean;
      sr.stretch_p95 = st.stretch_p95;
      sr.stretch_max = st.stretch_max;
      sr.hops_mean = st.hops_mean;
      sr.positions = on_physical ? "physical" : "packing";
      // A coordinate per node and per neighbour: a circle (3 doubles) or a position (2).
      const double per_node = n ? static_cast<double>(n + 2 * g.num_edges()) / static_cast<double>(n) : 0.0;
      sr.state_bytes_per_node = (s == core::Scheme::greedy_power ? 24.0 : 16.0) * per_node;
      if (on_physical) {  // no packing needed: each node tells its neighbours its position, once
        sr.setup_messages_per_node = per_node - 1;
        sr.setup_bytes_per_node = 16.0 * (per_node - 1);
      }
      if (s == core::Scheme::hyperbolic) {
        sr.positions = "tree";
        const core::HyperbolicSetupCost cost =
            core::hyperbolic_setup_cost(core::HyperbolicTreeEmbedding(g), g.num_edges());
        // The set-up simulated node by node, on the run's links (reliable: its protocol has no
        // reliability layer), every message counted.
        sim::LinkModel links = setup.link;
        links.loss = links.duplication = 0;
        const HyperbolicSetupOutcome so = run_hyperbolic_setup(g, topo.positions, links, plan.seed);
        if (so.done_nodes != n || so.rejected != 0 || so.inconsistent_tables != 0 ||
            (links.is_deterministic() && so.messages != cost.messages))  // equal to the central tree's
          throw core::InternalError("hyperbolic set-up: " + std::to_string(so.done_nodes) + "/" + std::to_string(n) +
                                    " nodes done, " + std::to_string(so.rejected) + " messages rejected, " +
                                    std::to_string(so.messages) + " messages against " + std::to_string(cost.messages));
        const double nn = n ? static_cast<double>(n) : 1.0;
        sr.setup_messages_per_node = static_cast<double>(so.messages) / nn;
        sr.setup_bytes_per_node = static_cast<double>(so.bytes) / nn;
        sr.state_bytes_per_node = static_cast<double>(so.state_bytes) / nn;
        sr.coordinate_bits_mean = cost.address_bits_mean;
        sr.coordinate_bits_max = static_cast<double>(cost.address_bits_max);
      }
      r.routing.push_back(sr);
    }
    if (topo.sensors) {  // every sensor pair: greedy power with the attachment, the others on the planarization
      const SensorNetwork& net = *topo.sensors;
      const PlanarizationRouter planar(net);
      // One entry per scheme (a scheme added to core::Scheme must say here how it routes all sensors;
      // -Wswitch makes the compiler ask).
      const auto sensor_router = [&](core::Scheme s) -> SensorRouter {
        switch (s) {
          case core::Scheme::greedy_power: return attached_router(net, g, phi);
          case core::Scheme::greedy_euclid:
          case core::Scheme::compass:
          case core::Scheme::gfg:
          case core::Scheme::hyperbolic:  // Kleinberg's embedding of each planarization component's BFS tree
            return planar.router(s);
        }
        throw core::InternalError("no all-sensor router for scheme " + std::string(core::to_string(s)));
      };
      std::vector<SensorRouter> routers;
      for (core::Scheme s : cfg.routing.schemes) routers.push_back(sensor_router(s));
      const std::vector<AllPairsStats> all = evaluate_all_pairs(net, routers, selection);
      for (std::size_t k = 0; k < all.size(); ++k) r.routing[k].all_pairs = all[k];
    }
    if (artifacts) {
      const core::CircleEmbedding& gfg_emb = physical ? geo : phi;
      const auto pairs = core::select_pairs(n, {cfg.routing.sample_routes, splitmix64(plan.seed)});
      for (const auto& [s, t] : pairs) {
        artifacts->greedy_routes.push_back(core::route(g, phi, core::Scheme::greedy_power, s, t).path);
        artifacts->gfg_routes.push_back(core::route(g, gfg_emb, core::Scheme::gfg, s, t).path);
      }
      artifacts->gfg_positions = gfg_emb;
      artifacts->circles = std::move(phi);
      artifacts->local = std::move(local);
      artifacts->topology = std::move(topo);
    }
  } catch (const std::exception& e) {
    r.status = RunStatus::error;
    r.message = e.what();
  }
  return finish();
}

namespace {
void put_text(std::vector<std::byte>& out, const std::string& text) {
  sim::append_bytes(out, static_cast<std::uint64_t>(text.size()));
  for (const char c : text) out.push_back(static_cast<std::byte>(c));
}
std::string get_text(std::span<const std::byte> in, std::size_t& at) {
  const auto size = sim::read_bytes<std::uint64_t>(in, at);
  LAGUERRE_PRECONDITION(size <= in.size() - at, "A run record's text runs past the end of its bytes.");
  std::string text(reinterpret_cast<const char*>(in.data() + at), size);
  at += size;
  return text;
}
}  // namespace

// The fields in declaration order (Runner.hpp); RunnerTest's round trip compares results_json and the
// per-scheme fields of a decoded sweep with the original's.
void encode_record(const RunRecord& r, std::vector<std::byte>& out) {
  using sim::append_bytes;
  append_bytes(out, r.plan);
  append_bytes(out, r.status);
  for (const std::string* t : {&r.message, &r.family, &r.topology, &r.topology_note, &r.kind}) put_text(out, *t);
  append_bytes(out, r.sensors), append_bytes(out, r.nodes), append_bytes(out, r.core_nodes);
  append_bytes(out, r.unreachable_sensors);
  append_bytes(out, r.edges), append_bytes(out, r.iterations), append_bytes(out, r.rounds);
  append_bytes(out, r.holds_nodes), append_bytes(out, r.messages), append_bytes(out, r.bytes);
  append_bytes(out, r.messages_per_node), append_bytes(out, r.max_node_messages), append_bytes(out, r.retransmissions);
  append_bytes(out, r.simulated_seconds), append_bytes(out, r.events), append_bytes(out, r.exact_iterations);
  append_bytes(out, r.core_lpd_iterations);
  append_bytes(out, static_cast<std::uint64_t>(r.routing.size()));
  for (const SchemeResult& x : r.routing) {
    append_bytes(out, x.scheme), append_bytes(out, x.pairs), append_bytes(out, x.delivered);
    append_bytes(out, x.delivery_rate), append_bytes(out, x.stretch_mean), append_bytes(out, x.stretch_p95);
    append_bytes(out, x.stretch_max), append_bytes(out, x.hops_mean);
    put_text(out, x.positions);
    append_bytes(out, x.setup_messages_per_node), append_bytes(out, x.setup_bytes_per_node);
    append_bytes(out, x.state_bytes_per_node), append_bytes(out, x.coordinate_bits_mean);
    append_bytes(out, x.coordinate_bits_max);
    append_bytes(out, x.all_pairs.has_value());
    if (x.all_pairs) append_bytes(out, *x.all_pairs);
  }
  append_bytes(out, r.wall_seconds);
}

RunRecord decode_record(std::span<const std::byte> in, std::size_t& at) {
  using sim::read_bytes;
  RunRecord r;
  r.plan = read_bytes<RunPlan>(in, at);
  r.status = read_bytes<RunStatus>(in, at);
  for (std::string* t : {&r.message, &r.family, &r.topology, &r.topology_note, &r.kind}) *t = get_text(in, at);
  r.sensors = read_bytes<std::size_t>(in, at), r.nodes = read_bytes<std::size_t>(in, at);
  r.core_nodes = read_bytes<std::size_t>(in, at), r.unreachable_sensors = read_bytes<std::size_t>(in, at);
  r.edges = read_bytes<std::size_t>(in, at);
  r.iterations = read_bytes<std::uint32_t>(in, at), r.rounds = read_bytes<std::uint32_t>(in, at);
  r.holds_nodes = read_bytes<std::size_t>(in, at), r.messages = read_bytes<std::uint64_t>(in, at);
  r.bytes = read_bytes<std::uint64_t>(in, at), r.messages_per_node = read_bytes<double>(in, at);
  r.max_node_messages = read_bytes<std::uint64_t>(in, at), r.retransmissions = read_bytes<std::uint64_t>(in, at);
  r.simulated_seconds = read_bytes<double>(in, at), r.events = read_bytes<std::uint64_t>(in, at);
  r.exact_iterations = read_bytes<int>(in, at), r.core_lpd_iterations = read_bytes<int>(in, at);
  r.routing.resize(read_bytes<std::uint64_t>(in, at));
  for (SchemeResult& x : r.routing) {
    x.scheme = read_bytes<core::Scheme>(in, at), x.pairs = read_bytes<std::size_t>(in, at);
    x.delivered = read_bytes<std::size_t>(in, at), x.delivery_rate = read_bytes<double>(in, at);
    x.stretch_mean = read_bytes<double>(in, at), x.stretch_p95 = read_bytes<double>(in, at);
    x.stretch_max = read_bytes<double>(in, at), x.hops_mean = read_bytes<double>(in, at);
    x.positions = get_text(in, at);
    x.setup_messages_per_node = read_bytes<double>(in, at), x.setup_bytes_per_node = read_bytes<double>(in, at);
    x.state_bytes_per_node = read_bytes<double>(in, at), x.coordinate_bits_mean = read_bytes<double>(in, at);
    x.coordinate_bits_max = read_bytes<double>(in, at);
    if (read_bytes<bool>(in, at)) x.all_pairs = read_bytes<AllPairsStats>(in, at);
  }
  r.wall_seconds = read_bytes<double>(in, at);
  return r;
}

ScenarioResults run_scenario(const Scenario& scenario, const RunnerOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<RunPlan> plans = plan_runs(scenario);
  ScenarioResults out;
  out.records.resize(plans.size());
  out.artifacts.resize(plans.size());
  unsigned jobs = options.jobs ? options.jobs : std::max(1u, std::thread::hardware_concurrency());
  jobs = static_cast<unsigned>(std::min<std::size_t>(jobs, std::max<std::size_t>(1, plans.size())));
  if (options.host_runner != nullptr) jobs = 1;  // its collective calls must come in plan order
  LAGUERRE_PRECONDITION(options.split == nullptr || options.host_runner == nullptr,
                        "Runs shared between processes run in each process (no host_runner).");
  // The runs this process executes, in plan order: all, or its share of a RunSplit.
  std::vector<std::size_t> mine;
  for (std::size_t i = 0, dealt = 0; i < plans.size(); ++i) {
    const bool keep = options.keep_artifacts && options.keep_artifacts(plans[i]);
    const std::size_t owner = options.split == nullptr ? 0 : keep ? 0 : dealt++ % options.split->size();
    if (options.split == nullptr || owner == options.split->rank()) mine.push_back(i);
  }
  if (options.split != nullptr) jobs = 1;
  std::atomic<std::size_t> next{0};
  std::size_t done = 0;
  std::mutex lock;
  auto worker = [&] {
    for (std::size_t k = next++; k < mine.size(); k = next++) {
      const std::size_t i = mine[k];
      const bool keep = options.keep_artifacts && options.keep_artifacts(plans[i]);
      RunArtifacts art;
      std::function<void(const ProtocolProgress&)> progress;
      if (options.on_protocol_progress)
        progress = [&, i](const ProtocolProgress& p) {
          std::lock_guard<std::mutex> guard(lock);
          options.on_protocol_progress(plans[i], p);
        };
      RunRecord rec = execute_run(scenario, plans[i], keep ? &art : nullptr, options.host_runner, progress);
      const bool has = keep && (rec.status == RunStatus::ok || rec.status == RunStatus::not_converged);
      std::lock_guard<std::mutex> guard(lock);
      out.records[i] = std::move(rec);
      if (has) out.artifacts[i] = std::move(art);
      ++done;
      if (options.on_progress)
        options.on_progress({done, mine.size(),
                             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
    }
  };
  if (jobs <= 1) {
    worker();
  } else {
    std::vector<std::thread> threads;
    for (unsigned j = 0; j < jobs; ++j) threads.emplace_back(worker);
    for (auto& t : threads) t.join();
  }
  if (options.split != nullptr) {
    std::vector<std::byte> bytes;
    sim::append_bytes(bytes, static_cast<std::uint64_t>(mine.size()));
    for (const std::size_t i : mine) sim::append_bytes(bytes, static_cast<std::uint64_t>(i)), encode_record(out.records[i], bytes);
    const std::vector<std::byte> all = options.split->all_gather(bytes);
    std::size_t at = 0, received = 0;
    for (std::size_t rank = 0; rank < options.split->size(); ++rank)
      for (auto count = sim::read_bytes<std::uint64_t>(all, at); count > 0; --count, ++received) {
        const auto i = sim::read_bytes<std::uint64_t>(all, at);
        LAGUERRE_PRECONDITION(i < plans.size(), "A shared run's index is not a planned run.");
        out.records[i] = decode_record(all, at);
      }
    LAGUERRE_PRECONDITION(received == plans.size() && at == all.size(),
                          "The processes sharing the runs returned " + std::to_string(received) + " records for " +
                              std::to_string(plans.size()) + " runs.");
  }
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace laguerre::scenarios
