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
#include "Parallel.hpp"
#include "ProtocolSummary.hpp"
#include "ScenarioCli.hpp"
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
    "On a terminal, stderr shows the progress of the protocol: rounds done, nodes whose check holds,\n"
    "events/s and an estimate of what is left.\n"
    "Exit status: 0 converged, 3 not converged or a node failed, 2 bad input."};

struct SimulateArgs {
  GraphArgs graph;
  std::string mode = "sync";
  std::string accelerate = "plain";
  std::string termination = "layout";
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

scenarios::ProtocolSetup setup_of(const SimulateArgs& a) {
  scenarios::ProtocolSetup setup;
  setup.asynchronous = core::parse_name(scenarios::protocol_mode_names, a.mode, "--mode") == scenarios::ProtocolMode::async;
  setup.steps_per_round = a.steps;
  setup.max_iterations = a.max_iterations;
  setup.root = core::parse_name(core::root_rule_names, a.root, "--root");
  setup.acceleration = core::parse_name(core::acceleration_names, a.accelerate, "--accelerate");
  if (!core::runs_in_network(setup.acceleration))
    throw core::InputError("--accelerate", 0,
                           "found '" + a.accelerate + "', which needs a central solver or global sums per sweep; "
                           "expected plain, chebyshev, local-superstep or newton-krylov (the others run in "
                           "'laguerre pack' only)");
  if (setup.asynchronous && setup.acceleration != core::Acceleration::plain)
    throw core::InputError("--accelerate", 0,
                           "found '" + a.accelerate + "' with --mode async; expected plain (the accelerations need "
                           "consistent synchronous iterates: the local ones extrapolate along them, newton-krylov's "
                           "conjugate gradients combine them in tree sums; use --mode sync)");
  setup.termination = core::parse_name(core::termination_names, a.termination, "--termination");
  if (setup.asynchronous && setup.termination != core::Termination::layout)
    throw core::InputError("--termination", 0,
                           "found '" + a.termination + "' with --mode async; expected layout (radius-only runs in "
                           "--mode sync)");
  if (setup.acceleration == core::Acceleration::newton_krylov && setup.termination != core::Termination::layout)
    throw core::InputError("--termination", 0,
                           "found '" + a.termination + "' with --accelerate newton-krylov; expected layout (a "
                           "Newton step already lays out and checks once per step)");
  setup.link.latency = scenarios::parse_latency(a.latency, "--latency");
  setup.link.loss = a.loss;
  setup.link.duplication = a.dup;
  for (const std::string& c : a.crashes) setup.crashes.push_back(scenarios::parse_crash(c, "--crash"));
  for (const std::string& r : a.recoveries) scenarios::add_recovery(setup.crashes, r, "--recover");
  if (!a.retransmit_after.empty()) setup.retransmit_after = scenarios::parse_duration(a.retransmit_after, "--retransmit-after");
  setup.adaptive_rto = !a.fixed_rto;
  setup.seed = a.seed;
  setup.runner = host_runner();  // the MPI kernel under mpirun (same results)
  return setup;
}

int run_simulate(const SimulateArgs& a) {
  const std::vector<core::Scheme> schemes = parse_schemes(a.scheme, "--scheme");
  scenarios::require_forwarding_schemes(schemes);  // before the packing, not after it
  const core::PairSelection selection = parse_pairs(a.pairs, a.seed, "--pairs");
  scenarios::ProtocolSetup setup = setup_of(a);
  const LoadedGraph loaded = load_graph(a.graph);
  const core::PlanarGraph& g = loaded.input.graph;
  const std::size_t n = g.num_vertices();
  // Progress on a terminal: rounds, nodes that hold, events/s, what is left.
  TerminalLine line;
  ProtocolMeter meter(a.max_iterations, a.steps);
  if (line.active()) setup.on_progress = [&](const scenarios::ProtocolProgress& p) { line.draw(meter.text(p), true); };
  const scenarios::ProtocolOutcome po = scenarios::run_packing_protocol(g, loaded.input.positions, setup);
  line.finish();
  nlohmann::json extra;  // the protocol ran on the parallel kernel: what it did (before forwarding runs)
  if (mpi_ranks() > 1) extra["mpi_ranks"] = mpi_ranks(), extra["mpi"] = parallel_summary();
  const std::string verify = a.verify ? scenarios::verify_against_core(g, loaded.kind, setup, po) : "";

  // Forward packets hop by hop on the final embedding, one simulation per scheme. Greedy power uses
  // the circles; the geometric schemes use the graph's coordinates when the file has them, else the
  // packing's centres (as `laguerre route` does with one embedding).
  const std::string blocker = scenarios::forwarding_blocker(po);
  const auto pairs = blocker.empty() ? core::select_pairs(n, selection) : std::vector<std::pair<core::Vertex, core::Vertex>>{};
  const std::vector<scenarios::ForwardingResult> results =
      scenarios::run_forwarding(g, po.circles, loaded.input.positions, setup.link, a.seed, schemes, pairs);
  return print_protocol_summary(
      {loaded, setup, a.mode, a.graph.outer, po, results, schemes, a.verify ? &verify : nullptr, {}, extra, blocker}, a.json);
}
}  // namespace

Action add_simulate_command(CLI::App& app) {
  const auto c = add_command<SimulateArgs>(app, simulate_help);
  add_graph_options(*c.cmd, c.args->graph, "graph", "Graph file (edge list, coords or planar_code)");
  add_outer_option(*c.cmd, c.args->graph);
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
             "Acceleration the nodes run (sync mode only, bit for bit with core::pack): plain (Thurston's "
             "Jacobi), chebyshev (adaptive second-order iteration on each node's own updates, ~14-17x fewer "
             "steps on 500-node uniform maps), local-superstep (Collins-Stephenson with local ratios) or "
             "newton-krylov (damped Newton steps, each solved by conjugate gradients in the network: one "
             "neighbour exchange plus one sum over the layout tree per CG iteration); --mode async refuses "
             "them all (CG needs consistent iterates); superstep, anderson and newton are central only");
  add_choice(*c.cmd, "--termination", c.args->termination, core::termination_names,
             "Termination test of each round (sync mode, bit for bit with core::pack): layout (layout wave and "
             "exact LPD/GLPD check every round) or radius-only (one radius exchange and the closing gap each "
             "round; the wave and the exact check run only when the gap is small everywhere, and LPD is claimed "
             "only when that check passes; docs/radius-only.md; not with newton-krylov)");
  c.cmd->add_option("--pairs", c.args->pairs, "'all' ordered pairs, or a number sampled with --seed")->capture_default_str();
  c.cmd->add_option("--scheme", c.args->scheme, "Forwarding scheme: greedy-power, greedy-euclid, compass, gfg or all")
      ->capture_default_str();
  c.cmd->add_flag("--verify", c.args->verify, "Also run core::pack and check the nodes' circles are identical");
  c.cmd->add_flag("--json", c.args->json, "Machine-readable output");
  return [args = c.args] { return run_simulate(*args); };
}

}  // namespace laguerre::tools
