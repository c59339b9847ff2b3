// `laguerre live`: the packing protocol and hop-by-hop forwarding over real UDP on 127.0.0.1, the
// nodes spread over P worker processes (scenarios/LiveRun); prints the summary of `laguerre simulate`.
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "Commands.hpp"
#include "Common.hpp"
#include "Parallel.hpp"
#include "ProtocolSummary.hpp"
#include "ScenarioCli.hpp"
#include "laguerre/core/packing/PackingNames.hpp"
#include "laguerre/scenarios/LiveRun.hpp"
#include "laguerre/scenarios/NetworkModel.hpp"
#include "laguerre/scenarios/Runner.hpp"
#include "laguerre/scenarios/Scenario.hpp"
#include "laguerre/scenarios/Topology.hpp"

namespace laguerre::tools {

namespace {
constexpr CommandHelp live_help{
    "live",
    "Run the packing protocol and forwarding over UDP on 127.0.0.1, the nodes spread over processes.",
    "The launcher forks --processes workers; worker k hosts a part of the nodes (--partition blocks:\n"
    "a contiguous block of indices; metis: a METIS k-way partition, as under mpirun, which cuts fewer\n"
    "links and so sends fewer datagrams) on one UDP socket (127.0.0.1, port --base-port + k, or free ports with 0), messages between nodes\n"
    "of one worker stay in memory. Packing runs first, then every selected pair sends a packet per\n"
    "--scheme, forwarded hop by hop. In sync mode the result is core::pack's bit for bit (--verify),\n"
    "whatever the timing; --loss drops messages at the sender and turns the reliability layer on,\n"
    "which keeps it so. Each phase ends when every worker is idle and no datagram is in flight; a worker\n"
    "that dies or a run past --timeout stops every worker.\n"
    "Exit status: 0 converged, 3 not converged or a node failed, 2 bad input (also a port in use),\n"
    "1 a worker failed or the run timed out.\n"
    "A scenario file (.yaml) stands for the topology of its first run (first sweep point, repetition 0,\n"
    "with its seeds); the protocol options are this command's.\n"
    "--json has the keys of `simulate --json` (simulated_seconds and events are then the packing\n"
    "phase's wall time and the datagrams sent) and a 'live' object: per-phase wall times, datagrams,\n"
    "and per worker its nodes, port, counters, socket buffers, peak memory and CPU time."};

struct LiveArgs {
  GraphArgs graph;
  std::size_t processes = 1;
  std::string partition = "blocks";
  std::uint16_t base_port = 0;
  double loss = 0;
  bool reliable = false;
  std::string mode = "sync";
  std::uint64_t seed = 1;
  double timeout = 60;
  int steps = 1;
  int max_iterations = 100000;
  std::string root = "deepest";
  std::string pairs = "all";
  std::string scheme = "greedy-power";
  std::string retransmit_after;
  bool fixed_rto = false;
  int socket_buffer = 4 << 20;
  bool verify = false;
  bool json = false;
};

bool is_scenario_file(const std::string& path) {
  const auto dot = path.rfind('.');
  return dot != std::string::npos && (path.substr(dot) == ".yaml" || path.substr(dot) == ".yml");
}

// The graph of GRAPH, or of a scenario's first run (as `laguerre run` builds it).
LoadedGraph load_graph_or_scenario(const GraphArgs& args) {
  if (!is_scenario_file(args.path)) return load_graph(args);
  const auto loaded = load_scenarios({args.path}, {});
  if (!loaded) throw core::InputError(args.path, 0, "a valid scenario file (its problems are listed above)");
  const scenarios::Scenario& scenario = loaded->front();
  const scenarios::RunPlan plan = scenarios::plan_runs(scenario).front();
  const scenarios::TopologySpec& spec = scenario.points.at(plan.point).config.topology;
  scenarios::Topology topo;
  try {
    topo = scenarios::build_topology(spec.generator, spec.params, plan.topology_seed, plan.repetition);
  } catch (const std::exception& e) {
    throw core::InputError(args.path, 0, std::string("a topology that can be built: ") + e.what());
  }
  LoadedGraph out;
  out.input.graph = std::move(topo.graph);
  out.input.positions = std::move(topo.positions);
  out.input.name = args.path + ": " + topo.name;
  out.kind = topo.kind;
  return out;
}

int run_live(const LiveArgs& a) {
  const std::vector<core::Scheme> schemes = parse_schemes(a.scheme, "--scheme");
  scenarios::require_forwarding_schemes(schemes);  // before the packing, not after it
  const core::PairSelection selection = parse_pairs(a.pairs, a.seed, "--pairs");
  scenarios::ProtocolSetup setup;
  setup.asynchronous = core::parse_name(scenarios::protocol_mode_names, a.mode, "--mode") == scenarios::ProtocolMode::async;
  setup.steps_per_round = a.steps;
  setup.max_iterations = a.max_iterations;
  setup.root = core::parse_name(core::root_rule_names, a.root, "--root");
  setup.link.loss = a.loss;
  if (!a.retransmit_after.empty())
    setup.retransmit_after = scenarios::parse_duration(a.retransmit_after, "--retransmit-after");
  if (a.reliable && !setup.retransmit_after) setup.retransmit_after = scenarios::LiveSetup{}.assumed_latency * 3;
  setup.adaptive_rto = !a.fixed_rto;
  setup.seed = a.seed;
  scenarios::LiveSetup live;
  live.processes = a.processes;
  live.base_port = a.base_port;
  live.timeout_seconds = a.timeout;
  live.socket_buffer = a.socket_buffer;

  const LoadedGraph loaded = load_graph_or_scenario(a.graph);
  const core::PlanarGraph& g = loaded.input.graph;
  const auto pairs = core::select_pairs(g.num_vertices(), selection);
  if (core::parse_name(scenarios::live_partition_names, a.partition, "--partition") == scenarios::LivePartition::metis)
    live.process_of = metis_workers(g, a.processes);
  const scenarios::LiveOutcome out = scenarios::run_live(g, loaded.input.positions, setup, live, schemes, pairs);
  const std::string verify = a.verify ? scenarios::verify_against_core(g, loaded.kind, setup, out.packing) : "";

  const sim::UdpCounters& c = out.total;
  double wall = 0;
  for (const double s : out.phase_seconds) wall += s;
  std::uint64_t peak = 0;
  for (const sim::WorkerReport& w : out.workers) peak = std::max(peak, w.peak_memory_bytes);
  const double datagram_rate = wall > 0 ? static_cast<double>(c.datagrams_sent) / wall : 0;
  char line[512];
  std::snprintf(line, sizeof line,
                "time         packing %.3f s wall (every node final %.3f s after the launch), forwarding %.3f s; %llu datagrams "
                "(%.3g/s), %llu local deliveries; peak memory %.1f MiB (largest worker)",
                out.phase_seconds.front(), sim::to_seconds(out.packing.finished_at), wall - out.phase_seconds.front(),
                static_cast<unsigned long long>(c.datagrams_sent), datagram_rate,
                static_cast<unsigned long long>(c.local_deliveries), static_cast<double>(peak) / (1024.0 * 1024.0));
  nlohmann::json workers = nlohmann::json::array();
  for (const sim::WorkerReport& w : out.workers) {
    nlohmann::json worker = {{"nodes", w.nodes}, {"first_node", w.first}, {"port", w.port}};
    for (const auto& [name, count] : sim::udp_counter_fields) worker[std::string(name)] = w.counters.*count;
    worker["receive_buffer"] = w.counters.receive_buffer;
    worker["send_buffer"] = w.counters.send_buffer;
    worker["peak_memory_bytes"] = w.peak_memory_bytes;
    worker["cpu_seconds"] = w.cpu_seconds;
    workers.push_back(std::move(worker));
  }
  nlohmann::json extra = {{"live",
                           {{"processes", out.workers.size()},
                            {"phase_wall_seconds", out.phase_seconds},
                            {"wall_seconds", wall},
                            {"datagrams", c.datagrams_sent},
                            {"datagrams_per_second", datagram_rate},
                            {"datagram_bytes", c.datagram_bytes_sent},
                            {"workers", workers}}}};
  const int status = print_protocol_summary(
      {loaded, setup, a.mode, a.graph.outer, out.packing, out.forwarding, schemes, a.verify ? &verify : nullptr, line, extra,
       scenarios::forwarding_blocker(out.packing)}, a.json);
  std::string ports;
  for (const sim::WorkerReport& w : out.workers) ports += (ports.empty() ? "" : ", ") + std::to_string(w.port);
  if (!a.json)
    std::printf("live         %zu process(es) on 127.0.0.1 (ports %s), socket buffers %d/%d bytes; %llu induced "
                "losses; dropped: %llu by the kernel, %llu malformed, %llu unknown destination, %llu not a neighbour, "
                "%llu stale\n",
                out.workers.size(), ports.c_str(), c.receive_buffer, c.send_buffer,
                static_cast<unsigned long long>(c.induced_losses), static_cast<unsigned long long>(c.kernel_drops),
                static_cast<unsigned long long>(c.malformed), static_cast<unsigned long long>(c.unknown_destination),
                static_cast<unsigned long long>(c.not_a_neighbour), static_cast<unsigned long long>(c.stale_phase));
  return status;
}
}  // namespace

Action add_live_command(CLI::App& app) {
  const auto c = add_command<LiveArgs>(app, live_help);
  add_graph_options(*c.cmd, c.args->graph, "graph", "Graph file (edge list, coords or planar_code) or scenario file (.yaml)");
  add_outer_option(*c.cmd, c.args->graph);
  c.cmd->add_option("--processes,-P", c.args->processes, "Worker processes (each hosts a part of the nodes)")
      ->check(CLI::Range(1, 256))->capture_default_str();
  add_choice(*c.cmd, "--partition", c.args->partition, scenarios::live_partition_names,
             "Nodes per worker: blocks of indices, or metis (needs the MPI build's METIS)");
  c.cmd->add_option("--base-port", c.args->base_port, "Worker k binds 127.0.0.1:BASE+k (0: free ports)")
      ->capture_default_str();
  c.cmd->add_option("--loss", c.args->loss, "Loss probability per message, at the sender (turns the reliability layer on)")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  c.cmd->add_flag("--reliable", c.args->reliable, "Run the reliability layer even without --loss (masks kernel drops)");
  const std::string sync_name(core::name_of(scenarios::protocol_mode_names, scenarios::ProtocolMode::sync));
  const std::string async_name(core::name_of(scenarios::protocol_mode_names, scenarios::ProtocolMode::async));
  c.cmd->add_option("--mode", c.args->mode, "Protocol mode: sync (bit for bit with core::pack) or async")
      ->check(CLI::IsMember({sync_name, async_name}))->capture_default_str();
  c.cmd->add_option("--seed", c.args->seed, "Seed of every random stream (and of the pair sample)")
      ->check(seed_validator())->capture_default_str();
  c.cmd->add_option("--timeout", c.args->timeout, "Bound on the whole run, in seconds (workers are killed past it)")
      ->check(CLI::PositiveNumber)->capture_default_str();
  c.cmd->add_option("--steps-per-round,-N", c.args->steps, "Thurston steps per round")
      ->check(CLI::Range(1, 10000))->capture_default_str();
  c.cmd->add_option("--max-iterations", c.args->max_iterations, "Cap on Thurston steps")
      ->check(CLI::Range(1, 100000000))->capture_default_str();
  add_choice(*c.cmd, "--root", c.args->root, core::root_rule_names, "Layout root election: deepest or smallest-id");
  c.cmd->add_option("--pairs", c.args->pairs, "'all' ordered pairs, or a number sampled with --seed")->capture_default_str();
  c.cmd->add_option("--scheme", c.args->scheme, "Forwarding scheme: greedy-power, greedy-euclid, compass, gfg or all")
      ->capture_default_str();
  c.cmd->add_option("--retransmit-after", c.args->retransmit_after,
                    "First retransmission period of the reliability layer (default 3ms)");
  c.cmd->add_flag("--fixed-rto", c.args->fixed_rto, "Keep the retransmission timeout fixed (no round-trip estimation)");
  c.cmd->add_option("--socket-buffer", c.args->socket_buffer, "SO_RCVBUF and SO_SNDBUF to request, in bytes")
      ->check(CLI::Range(4096, 1 << 30))->capture_default_str();
  c.cmd->add_flag("--verify", c.args->verify, "Also run core::pack and check the nodes' circles are identical");
  c.cmd->add_flag("--json", c.args->json, "Machine-readable output");
  return [args = c.args] { return run_live(*args); };
}

}  // namespace laguerre::tools
