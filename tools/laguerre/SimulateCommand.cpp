// `laguerre simulate`: run the distributed packing protocol on one actor per node in the
// discrete-event simulator, then forward packets hop by hop over the simulated network. The wiring is
// scenarios/ProtocolRun's; this file parses the options and prints.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "Commands.hpp"
#include "Common.hpp"
#include "laguerre/core/packing/PackingNames.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"
#include "laguerre/protocols/Codec.hpp"
#include "laguerre/scenarios/NetworkModel.hpp"
#include "laguerre/scenarios/ProtocolRun.hpp"
#include "laguerre/scenarios/Scenario.hpp"

namespace laguerre::tools {

namespace {
constexpr CommandHelp simulate_help{
    "simulate",
    "Run the distributed packing protocol, one actor per node, in the discrete-event simulator.",
    "Then every selected pair sends a packet, forwarded hop by hop by the --scheme(s); the geometric\n"
    "schemes use the file's coordinates, or the packing's centres when it has none.\n"
    "With --loss, --dup or --crash the nodes run the reliability layer (acks, retransmissions,\n"
    "duplicate detection, crash detection); a detected crash ends every survivor with neighbour_failed.\n"
    "Forwarding runs over the same lossy links, each node over the reliability layer: every packet\n"
    "takes the hops it takes without loss (only the timing differs).\n"
    "A recovering node keeps its state: an outage shorter than the detection time is masked (the run\n"
    "converges); after a longer one it ends with neighbour_failed as well.\n"
    "Exit status: 0 converged, 3 not converged or a node failed, 2 bad input."};

struct SimulateArgs {
  GraphArgs graph;
  std::string mode = "sync";
  std::string accelerate = "plain";
  std::string latency = "constant:1ms";
  double loss = 0;
  double dup = 0;
  std::uint64_t seed = 1;
  int steps = 1;
  int max_iterations = 100000;
  std::string root = "deepest";
  std::string pairs = "all";
  std::string scheme = "greedy-power";
  std::vector<std::string> crashes;
  std::vector<std::string> recoveries;
  std::string retransmit_after;
  bool fixed_rto = false;
  bool verify = false;
  bool json = false;
};

std::string_view outcome_name(protocols::PackingOutcome o) {
  switch (o) {
    case protocols::PackingOutcome::running: return "running";
    case protocols::PackingOutcome::converged: return "converged";
    case protocols::PackingOutcome::cap: return "cap";
    case protocols::PackingOutcome::neighbour_failed: return "neighbour_failed";
  }
  return "?";
}

scenarios::ProtocolSetup setup_of(const SimulateArgs& a) {
  scenarios::ProtocolSetup setup;
  setup.asynchronous = core::parse_name(scenarios::protocol_mode_names, a.mode, "--mode") == scenarios::ProtocolMode::async;
  setup.steps_per_round = a.steps;
  setup.max_iterations = a.max_iterations;
  setup.root = core::parse_name(core::root_rule_names, a.root, "--root");
  setup.acceleration = core::parse_name(core::acceleration_names, a.accelerate, "--accelerate");
  if (!core::is_local(setup.acceleration))
    throw core::InputError("--accelerate", 0,
                           "found '" + a.accelerate + "', which needs global sums or a central solver; expected plain, "
                           "chebyshev or local-superstep (the others run in 'laguerre pack' only)");
  if (setup.asynchronous && setup.acceleration != core::Acceleration::plain)
    throw core::InputError("--accelerate", 0,
                           "found '" + a.accelerate + "' with --mode async; expected plain (the local accelerations "
                           "extrapolate along consistent synchronous iterates: use --mode sync)");
  setup.link.latency = scenarios::parse_latency(a.latency, "--latency");
  setup.link.loss = a.loss;
  setup.link.duplication = a.dup;
  for (const std::string& c : a.crashes) setup.crashes.push_back(scenarios::parse_crash(c, "--crash"));
  for (const std::string& r : a.recoveries) scenarios::add_recovery(setup.crashes, r, "--recover");
  if (!a.retransmit_after.empty()) setup.retransmit_after = scenarios::parse_duration(a.retransmit_after, "--retransmit-after");
  setup.adaptive_rto = !a.fixed_rto;
  setup.seed = a.seed;
  return setup;
}

int run_simulate(const SimulateArgs& a) {
  const std::vector<core::Scheme> schemes = parse_schemes(a.scheme, "--scheme");
  const core::PairSelection selection = parse_pairs(a.pairs, a.seed, "--pairs");
  const scenarios::ProtocolSetup setup = setup_of(a);
  const LoadedGraph loaded = load_graph(a.graph);
  const core::PlanarGraph& g = loaded.input.graph;
  const std::size_t n = g.num_vertices();
  const scenarios::ProtocolOutcome po = scenarios::run_packing_protocol(g, loaded.input.positions, setup);
  const std::size_t converged = po.converged_nodes, holds = po.holds_nodes, failed = po.failed_nodes;
  const std::uint32_t steps = po.iterations, rounds = po.rounds;
  const bool lossy = po.lossy;
  const protocols::PackingCounters& rel = po.reliability;
  std::string suspect_list;
  for (const auto& [id, count] : po.suspects)
    suspect_list += (suspect_list.empty() ? "" : ", ") + std::to_string(id) + " (" + std::to_string(count) + " nodes)";
  const std::string verify = a.verify ? scenarios::verify_against_core(g, loaded.kind, setup, po) : "";

  // Forward packets hop by hop on the final embedding, one simulation per scheme. Greedy power uses
  // the circles; the geometric schemes use the graph's coordinates when the file has them, else the
  // packing's centres (as `laguerre route` does with one embedding).
  const auto pairs = failed > 0 ? std::vector<std::pair<core::Vertex, core::Vertex>>{} : core::select_pairs(n, selection);
  const bool input_positions = !loaded.input.positions.empty();
  const std::vector<scenarios::ForwardingResult> results =
      scenarios::run_forwarding(g, po.circles, loaded.input.positions, setup.link, a.seed, schemes, pairs);
  std::size_t packets = 0, delivered = 0;
  double hops_total = 0, fwd_seconds = 0;
  for (const scenarios::ForwardingResult& r : results) {
    packets += r.packets;
    delivered += r.delivered;
    hops_total += r.hops_mean * static_cast<double>(r.delivered);
    fwd_seconds += r.simulated_seconds;
  }

  const double msgs_mean = static_cast<double>(po.messages) / static_cast<double>(n);
  const double bytes_mean = static_cast<double>(po.bytes) / static_cast<double>(n);
  if (a.json) {
    nlohmann::json phases = nlohmann::json::object();
    for (std::size_t p = 1; p < po.by_phase.size(); ++p) {
      const auto& t = po.by_phase[p];
      if (t.messages_sent == 0) continue;
      phases[std::string(protocols::to_string(static_cast<protocols::MessageType>(p)))] = {
          {"messages", t.messages_sent}, {"bytes", t.bytes_sent}};
    }
    nlohmann::json doc = {{"graph", loaded.input.name},
                          {"nodes", n},
                          {"edges", g.num_edges()},
                          {"kind", std::string(core::to_string(loaded.kind))},
                          {"converged_nodes", converged},
                          {"local_condition_holds", holds},
                          {"iterations", steps},
                          {"mode", a.mode},
                          {"rounds", rounds},
                          {"messages", po.messages},
                          {"bytes", po.bytes},
                          {"messages_per_node_mean", msgs_mean},
                          {"messages_per_node_max", po.max_node_messages},
                          {"bytes_per_node_mean", bytes_mean},
                          {"bytes_per_node_max", po.max_node_bytes},
                          {"by_phase", phases},
                          {"simulated_seconds", sim::to_seconds(po.simulated_time)},
                          {"finished_seconds", sim::to_seconds(po.finished_at)},
                          {"wall_seconds", po.wall_seconds},
                          {"events", po.events},
                          {"events_per_second", po.events_per_second},
                          {"peak_memory_bytes", po.peak_memory_bytes},
                          {"packets", packets},
                          {"delivered", delivered},
                          {"hops_mean", delivered ? hops_total / static_cast<double>(delivered) : 0.0},
                          {"forwarding_simulated_seconds", fwd_seconds},
                          {"forwarding_positions", input_positions ? "input coordinates" : "packing centres"}};
    nlohmann::json fwd_json = nlohmann::json::array();
    auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); };
    for (const scenarios::ForwardingResult& r : results)
      fwd_json.push_back({{"scheme", std::string(core::to_string(r.scheme))},
                          {"packets", r.packets},
                          {"delivered", r.delivered},
                          {"dead_ends", r.dead_ends},
                          {"loops", r.loops},
                          {"ttl_exceeded", r.ttl_exceeded},
                          {"hops_mean", r.hops_mean},
                          {"stretch_mean", number(r.stretch_mean)},
                          {"stretch_p95", number(r.stretch_p95)},
                          {"stretch_max", number(r.stretch_max)},
                          {"simulated_seconds", r.simulated_seconds}});
    doc["forwarding"] = fwd_json;
    if (a.verify) doc["verify"] = verify;
    if (lossy) {
      doc["reliability"] = {{"frames", rel.frames},
                            {"retransmissions", rel.retransmissions},
                            {"acks", rel.acks},
                            {"duplicates", rel.duplicates},
                            {"probes", rel.probes},
                            {"links_given_up", rel.links_failed},
                            {"retransmit_after_seconds", sim::to_seconds(po.retransmit_after)},
                            {"adaptive_rto", po.adaptive_rto}};
      doc["failed_nodes"] = failed;
      doc["survivors"] = po.survivors();
      nlohmann::json sus = nlohmann::json::object();
      for (const auto& [id, count] : po.suspects) sus[std::to_string(id)] = count;
      doc["suspects"] = sus;
      nlohmann::json outages = nlohmann::json::array();
      for (const scenarios::OutageOutcome& o : po.outages) {
        outages.push_back({{"node", g.id(o.node)},
                           {"crash_seconds", sim::to_seconds(o.spec.at)},
                           {"recover_seconds", o.spec.recover_at ? nlohmann::json(sim::to_seconds(*o.spec.recover_at))
                                                                 : nlohmann::json()},
                           {"outcome", std::string(outcome_name(o.outcome))},
                           {"final", o.final}});
      }
      doc["outages"] = outages;
    }
    std::cout << doc.dump(1) << '\n';
  } else {
    std::printf("graph        %s: %zu nodes, %zu edges, %s\n", loaded.input.name.c_str(), n, g.num_edges(),
                std::string(core::to_string(loaded.kind)).c_str());
    std::printf("protocol     %s after %u %s in %u rounds (N = %d); %zu/%zu nodes report %s\n",
                converged == n ? "converged" : "did not converge", steps,
                setup.asynchronous ? "iteration-equivalents (asynchronous)" : "iterations", rounds, a.steps, holds, n,
                loaded.kind == core::GraphKind::triangulated_disc ? "LPD" : "GLPD");
    if (failed > 0)
      std::printf("failure      %zu/%zu surviving nodes ended with neighbour_failed; suspected: %s\n", failed, po.survivors(),
                  suspect_list.c_str());
    for (const scenarios::OutageOutcome& o : po.outages)
      if (o.spec.recover_at)
        std::printf("outage       node %llu down from %.3f ms to %.3f ms, then ended %s\n",
                    static_cast<unsigned long long>(g.id(o.node)), static_cast<double>(o.spec.at) * 1e-6,
                    static_cast<double>(*o.spec.recover_at) * 1e-6, std::string(outcome_name(o.outcome)).c_str());
    if (lossy)
      std::printf("reliability  %llu frames, %llu retransmissions, %llu acks, %llu duplicates detected, %llu probes, "
                  "%llu links given up (retransmit after %.3f ms, %s)\n",
                  static_cast<unsigned long long>(rel.frames), static_cast<unsigned long long>(rel.retransmissions),
                  static_cast<unsigned long long>(rel.acks), static_cast<unsigned long long>(rel.duplicates),
                  static_cast<unsigned long long>(rel.probes), static_cast<unsigned long long>(rel.links_failed),
                  static_cast<double>(po.retransmit_after) * 1e-6,
                  po.adaptive_rto ? "then adaptive" : "fixed");
    std::printf("messages     %llu (%.1f per node, max %llu); bytes %llu (%.0f per node, max %llu)\n",
                static_cast<unsigned long long>(po.messages), msgs_mean,
                static_cast<unsigned long long>(po.max_node_messages), static_cast<unsigned long long>(po.bytes),
                bytes_mean, static_cast<unsigned long long>(po.max_node_bytes));
    std::printf("by phase    ");
    for (std::size_t p = 1; p < po.by_phase.size(); ++p) {
      const auto& t = po.by_phase[p];
      if (t.messages_sent)
        std::printf(" %s %llu", std::string(protocols::to_string(static_cast<protocols::MessageType>(p))).c_str(),
                    static_cast<unsigned long long>(t.messages_sent));
    }
    std::printf("\ntime         %.6f s simulated (every node final at %.6f s), %.3f s wall, %llu events (%.3g events/s), "
                "peak memory %.1f MiB\n",
                sim::to_seconds(po.simulated_time), sim::to_seconds(po.finished_at),
                po.wall_seconds,
                static_cast<unsigned long long>(po.events), po.events_per_second,
                static_cast<double>(po.peak_memory_bytes) / (1024.0 * 1024.0));
    if (a.verify) std::printf("verify       %s\n", verify.c_str());
    if (failed > 0)
      std::printf("forwarding   skipped: the packing run was abandoned\n");
    else
      for (const scenarios::ForwardingResult& r : results)
        std::printf("forwarding   %-13s %zu/%zu packets delivered hop by hop%s, %.2f hops on average; %zu dead ends, "
                    "%zu loops, %zu TTL exceeded; hop stretch mean %.3f, p95 %.3f, max %.3f\n",
                    std::string(core::to_string(r.scheme)).c_str(), r.delivered, r.packets,
                    setup.link.loss > 0 || setup.link.duplication > 0 ? " (over the lossy links, reliability layer)" : "", r.hops_mean, r.dead_ends, r.loops, r.ttl_exceeded,
                    r.stretch_mean, r.stretch_p95, r.stretch_max);
    if (failed == 0 && std::any_of(schemes.begin(), schemes.end(), [](core::Scheme sc) { return sc != core::Scheme::greedy_power; }))
      std::printf("positions    %s (greedy Euclidean, compass, gfg)\n",
                  input_positions ? "the graph's coordinates" : "the packing's centres");
  }
  return converged == n ? 0 : 3;
}
}  // namespace

Action add_simulate_command(CLI::App& app) {
  const auto c = add_command<SimulateArgs>(app, simulate_help);
  add_graph_options(*c.cmd, c.args->graph, "graph", "Graph file (edge list, coords or planar_code)");
  const std::string sync_name(core::name_of(scenarios::protocol_mode_names, scenarios::ProtocolMode::sync));
  const std::string async_name(core::name_of(scenarios::protocol_mode_names, scenarios::ProtocolMode::async));
  c.cmd->add_option("--mode", c.args->mode, "Protocol mode: sync (bit for bit with core::pack) or async (chaotic updates)")
      ->check(CLI::IsMember({sync_name, async_name}))
      ->capture_default_str();
  c.cmd->add_option("--latency", c.args->latency, "constant:D, uniform:LO:HI or distance:BASE:NS_PER_UNIT[:JITTER]")
      ->capture_default_str();
  c.cmd->add_option("--loss", c.args->loss, "Loss probability per copy (turns the reliability layer on)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  c.cmd->add_option("--dup", c.args->dup, "Duplication probability per message (turns the reliability layer on)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  c.cmd->add_option("--crash", c.args->crashes,
                  "Crash node ID at TIME for good (17@40ms) or until T2 (17@40ms-90ms); repeatable");
  c.cmd->add_option("--recover", c.args->recoveries,
                  "Bring a crashed node back, e.g. 17@90ms (its state survives; repeatable)");
  c.cmd->add_option("--retransmit-after", c.args->retransmit_after,
                  "First retransmission period of the reliability layer (default: 3 × the longest latency)");
  c.cmd->add_flag("--fixed-rto", c.args->fixed_rto,
                "Keep the retransmission timeout at --retransmit-after (no round-trip estimation)");
  c.cmd->add_option("--seed", c.args->seed, "Seed of every random stream (and of the pair sample)")
      ->check(seed_validator())->capture_default_str();
  c.cmd->add_option("--steps-per-round,-N", c.args->steps, "Thurston steps per round")
      ->check(CLI::Range(1, 10000))->capture_default_str();
  c.cmd->add_option("--max-iterations", c.args->max_iterations, "Cap on Thurston steps")
      ->check(CLI::Range(1, 100000000))->capture_default_str();
  add_choice(*c.cmd, "--root", c.args->root, core::root_rule_names, "Layout root election: deepest or smallest-id");
  add_choice(*c.cmd, "--accelerate", c.args->accelerate, core::acceleration_names,
             "Local acceleration each node runs on its own updates (sync mode, bit for bit with core::pack): "
             "plain (Thurston's Jacobi), chebyshev (adaptive second-order iteration, ~14-17x fewer steps on "
             "500-node uniform maps) or local-superstep (Collins-Stephenson with local ratios); superstep, "
             "anderson and newton need global sums and are refused");
  c.cmd->add_option("--pairs", c.args->pairs, "'all' ordered pairs, or a number sampled with --seed")->capture_default_str();
  c.cmd->add_option("--scheme", c.args->scheme, "Forwarding scheme: greedy-power, greedy-euclid, compass, gfg or all")
      ->capture_default_str();
  c.cmd->add_flag("--verify", c.args->verify, "Also run core::pack and check the nodes' circles are identical");
  c.cmd->add_flag("--json", c.args->json, "Machine-readable output");
  return [args = c.args] { return run_simulate(*args); };
}

}  // namespace laguerre::tools
