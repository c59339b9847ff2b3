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
#include "laguerre/core/routing/RoutingMetrics.hpp"
#include "laguerre/scenarios/ProtocolRun.hpp"

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
                      sim::HostRunner* host_runner) {
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
  r.nodes = n;
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
      r.routing.push_back(sr);
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

ScenarioResults run_scenario(const Scenario& scenario, const RunnerOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<RunPlan> plans = plan_runs(scenario);
  ScenarioResults out;
  out.records.resize(plans.size());
  out.artifacts.resize(plans.size());
  unsigned jobs = options.jobs ? options.jobs : std::max(1u, std::thread::hardware_concurrency());
  jobs = static_cast<unsigned>(std::min<std::size_t>(jobs, std::max<std::size_t>(1, plans.size())));
  if (options.host_runner != nullptr) jobs = 1;  // its collective calls must come in plan order
  std::atomic<std::size_t> next{0};
  std::size_t done = 0;
  std::mutex lock;
  auto worker = [&] {
    for (std::size_t i = next++; i < plans.size(); i = next++) {
      const bool keep = options.keep_artifacts && options.keep_artifacts(plans[i]);
      RunArtifacts art;
      RunRecord rec = execute_run(scenario, plans[i], keep ? &art : nullptr, options.host_runner);
      const bool has = keep && (rec.status == RunStatus::ok || rec.status == RunStatus::not_converged);
      std::lock_guard<std::mutex> guard(lock);
      out.records[i] = std::move(rec);
      if (has) out.artifacts[i] = std::move(art);
      ++done;
      if (options.on_progress)
        options.on_progress({done, plans.size(),
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
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace laguerre::scenarios
