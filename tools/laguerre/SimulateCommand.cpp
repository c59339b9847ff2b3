// `laguerre simulate`: run the distributed packing protocol on one actor per node in the
// discrete-event simulator, then forward packets hop by hop over the simulated network.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>

#include <nlohmann/json.hpp>

#include "Commands.hpp"
#include "Common.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"
#include "laguerre/protocols/Codec.hpp"
#include "laguerre/protocols/Forwarding.hpp"
#include "laguerre/protocols/PackingNode.hpp"
#include "laguerre/sim/SimHost.hpp"

namespace laguerre::tools {

namespace {
struct SimulateArgs {
  std::string graph;
  std::string format = "automatic";
  std::size_t index = 1;
  std::string mode = "sync";
  std::string latency = "constant:1ms";
  double loss = 0;
  double dup = 0;
  std::uint64_t seed = 1;
  int steps = 1;
  int max_iterations = 100000;
  std::string root = "deepest";
  std::string pairs = "all";
  bool verify = false;
  bool json = false;
};

// "250us", "1ms", "2s", "100" (nanoseconds) → nanoseconds.
sim::Duration parse_duration(const std::string& text) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  const std::string unit = text.substr(used);
  double scale = 0;
  if (unit.empty() || unit == "ns") scale = 1;
  else if (unit == "us") scale = 1e3;
  else if (unit == "ms") scale = 1e6;
  else if (unit == "s") scale = 1e9;
  if (used == 0 || scale == 0 || !(value >= 0))
    throw std::invalid_argument("--latency: expected a non-negative duration such as 250us, 1ms or 2s, found '" +
                                text + "'.");
  return static_cast<sim::Duration>(value * scale + 0.5);
}

// constant:D | uniform:LO:HI | distance:BASE:NS_PER_UNIT[:JITTER]
sim::LatencyModel parse_latency(const std::string& spec) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= spec.size(); ++i)
    if (i == spec.size() || spec[i] == ':') {
      parts.push_back(spec.substr(start, i - start));
      start = i + 1;
    }
  const std::string expected =
      "expected constant:D, uniform:LO:HI or distance:BASE:NS_PER_UNIT[:JITTER] (durations like 1ms)";
  if (parts[0] == "constant" && parts.size() == 2) return sim::LatencyModel::constant(parse_duration(parts[1]));
  if (parts[0] == "uniform" && parts.size() == 3)
    return sim::LatencyModel::uniform(parse_duration(parts[1]), parse_duration(parts[2]));
  if (parts[0] == "distance" && (parts.size() == 3 || parts.size() == 4)) {
    double per_unit = 0;
    try {
      per_unit = std::stod(parts[2]);
    } catch (const std::exception&) {
      throw std::invalid_argument("--latency: NS_PER_UNIT must be a number, found '" + parts[2] + "'.");
    }
    return sim::LatencyModel::distance(parse_duration(parts[1]), per_unit,
                                       parts.size() == 4 ? parse_duration(parts[3]) : 0);
  }
  throw std::invalid_argument("--latency '" + spec + "': " + expected + ".");
}

sim::Network make_network(const core::PlanarGraph& g, const std::vector<core::Point2>& positions,
                          const sim::LinkModel& link) {
  std::vector<sim::Edge> edges;
  for (core::Dart d = 0; d < g.num_darts(); ++d)
    if (g.tail(d) < g.head(d)) edges.emplace_back(g.tail(d), g.head(d));
  sim::Network net(g.num_vertices(), edges);
  net.set_ids(g.ids());
  if (!positions.empty()) {
    std::vector<protocols::Position> pos;
    for (const auto& p : positions) pos.push_back({p.x, p.y});
    net.set_positions(std::move(pos));
  }
  net.set_link_model(link);
  return net;
}

class Collector : public protocols::PacketSink {
public:
  void on_packet_end(const protocols::PacketReport& r) override { reports.push_back(r); }
  std::vector<protocols::PacketReport> reports;
};

int run_simulate(const SimulateArgs& a) {
  if (a.mode != "sync")
    throw std::invalid_argument("--mode " + a.mode +
                                " is not available yet: only the synchronous protocol is implemented.");
  if (a.loss > 0 || a.dup > 0)
    throw std::invalid_argument(
        "--loss and --dup need the fault-tolerant protocol, which is not implemented yet: the synchronous "
        "protocol assumes reliable links (any latency and reordering is fine).");
  const LoadedGraph loaded = load_graph(a.graph, a.format, a.index);
  const core::PlanarGraph& g = loaded.input.graph;
  const std::size_t n = g.num_vertices();
  sim::LinkModel link;
  link.latency = parse_latency(a.latency);
  link.loss = a.loss;
  link.duplication = a.dup;
  link.validate();
  if (link.latency.kind == sim::LatencyKind::distance && loaded.input.positions.empty())
    throw std::invalid_argument("--latency distance:… needs node positions; " + a.graph +
                                " has none (use the coords format).");

  protocols::PackingParams params;
  params.steps_per_check = a.steps;
  params.max_iterations = a.max_iterations;
  params.root = a.root == "smallest-id" ? core::RootRule::smallest_id : core::RootRule::deepest;
  sim::SimConfig config;
  config.seed = a.seed;
  auto phase_of = [](std::span<const std::byte> bytes) -> sim::Phase {
    return bytes.size() >= 2 ? static_cast<sim::Phase>(bytes[1]) : 0;
  };
  sim::SimHost host(
      make_network(g, loaded.input.positions, link), config,
      [&](protocols::Runtime& rt, sim::NodeIndex v) -> std::unique_ptr<protocols::Node> {
        return std::make_unique<protocols::PackingNode>(rt, protocols::local_knowledge(g, v), params);
      },
      phase_of);
  const sim::RunReport report = host.run();

  // Gather the outcome and the embedding the nodes hold.
  core::CircleEmbedding phi(n);
  std::size_t converged = 0, holds = 0;
  std::uint32_t steps = 0, rounds = 0;
  for (core::Vertex v = 0; v < n; ++v) {
    const auto& node = static_cast<const protocols::PackingNode&>(host.node(v));
    phi[v] = node.placement().circle;
    converged += node.outcome() == protocols::PackingOutcome::converged;
    holds += node.local_condition() == core::LocalCondition::holds;
    steps = std::max(steps, node.steps());
    rounds = std::max(rounds, node.round());
  }
  const auto& traffic = host.simulator().traffic();
  const sim::TrafficCounters total = traffic.total();
  std::uint64_t max_msgs = 0, max_bytes = 0;
  for (sim::NodeIndex v = 0; v < n; ++v) {
    const auto t = traffic.node_total(v);
    max_msgs = std::max(max_msgs, t.messages_sent);
    max_bytes = std::max(max_bytes, t.bytes_sent);
  }
  std::string verify;
  if (a.verify) {
    core::PackOptions opt;
    opt.steps_per_check = a.steps;
    opt.max_iterations = a.max_iterations;
    opt.root = params.root;
    const core::PackResult r = core::pack(g, opt);
    bool same = r.iterations == static_cast<int>(steps);
    for (core::Vertex v = 0; v < n && same; ++v)
      same = r.circles[v].x == phi[v].x && r.circles[v].y == phi[v].y && r.circles[v].r == phi[v].r;
    verify = same ? "identical to core::pack, bit for bit" : "DIFFERS from core::pack";
  }

  // Forward packets hop by hop on the final embedding.
  core::PairSelection selection{0, a.seed};
  if (a.pairs != "all") {
    try {
      selection.sample = std::stoull(a.pairs);
    } catch (const std::exception&) {
      throw std::invalid_argument("--pairs expects 'all' or a positive number, found '" + a.pairs + "'.");
    }
  }
  const auto pairs = core::select_pairs(n, selection);
  Collector sink;
  sim::SimHost fwd(
      make_network(g, loaded.input.positions, link), config,
      [&](protocols::Runtime& rt, sim::NodeIndex v) -> std::unique_ptr<protocols::Node> {
        std::vector<protocols::NodeId> nb;
        std::vector<core::Circle> circles;
        for (core::Vertex w : g.neighbours(v)) {
          nb.push_back(g.id(w));
          circles.push_back(phi[w]);
        }
        return std::make_unique<protocols::ForwardingNode>(rt, sink, g.id(v), nb, phi[v], circles);
      },
      phase_of);
  const std::uint32_t ttl = static_cast<std::uint32_t>(4 * n + 16);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto [s, t] = pairs[i];
    static_cast<protocols::ForwardingNode&>(fwd.node(s)).originate({i, g.id(t), phi[t], ttl});
  }
  const sim::RunReport fwd_report = fwd.run();
  std::size_t delivered = 0;
  double hops = 0;
  for (const auto& r : sink.reports)
    if (r.outcome == protocols::PacketOutcome::delivered) {
      ++delivered;
      hops += r.hops;
    }

  const double msgs_mean = static_cast<double>(total.messages_sent) / static_cast<double>(n);
  const double bytes_mean = static_cast<double>(total.bytes_sent) / static_cast<double>(n);
  if (a.json) {
    nlohmann::json phases = nlohmann::json::object();
    for (std::size_t p = 1; p < traffic.phase_count(); ++p) {
      const auto t = traffic.phase_total(static_cast<sim::Phase>(p));
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
                          {"rounds", rounds},
                          {"messages", total.messages_sent},
                          {"bytes", total.bytes_sent},
                          {"messages_per_node_mean", msgs_mean},
                          {"messages_per_node_max", max_msgs},
                          {"bytes_per_node_mean", bytes_mean},
                          {"bytes_per_node_max", max_bytes},
                          {"by_phase", phases},
                          {"simulated_seconds", static_cast<double>(report.simulated_time) * 1e-9},
                          {"wall_seconds", report.wall_seconds},
                          {"events", report.events_processed},
                          {"events_per_second", report.events_per_second},
                          {"peak_memory_bytes", report.peak_memory_bytes},
                          {"packets", pairs.size()},
                          {"delivered", delivered},
                          {"hops_mean", delivered ? hops / static_cast<double>(delivered) : 0.0},
                          {"forwarding_simulated_seconds", static_cast<double>(fwd_report.simulated_time) * 1e-9}};
    if (a.verify) doc["verify"] = verify;
    std::cout << doc.dump(1) << '\n';
  } else {
    std::printf("graph        %s: %zu nodes, %zu edges, %s\n", loaded.input.name.c_str(), n, g.num_edges(),
                std::string(core::to_string(loaded.kind)).c_str());
    std::printf("protocol     %s after %u iterations in %u rounds (N = %d); %zu/%zu nodes report %s\n",
                converged == n ? "converged" : "did not converge", steps, rounds, a.steps, holds, n,
                loaded.kind == core::GraphKind::triangulated_disc ? "LPD" : "GLPD");
    std::printf("messages     %llu (%.1f per node, max %llu); bytes %llu (%.0f per node, max %llu)\n",
                static_cast<unsigned long long>(total.messages_sent), msgs_mean,
                static_cast<unsigned long long>(max_msgs), static_cast<unsigned long long>(total.bytes_sent),
                bytes_mean, static_cast<unsigned long long>(max_bytes));
    std::printf("by phase    ");
    for (std::size_t p = 1; p < traffic.phase_count(); ++p) {
      const auto t = traffic.phase_total(static_cast<sim::Phase>(p));
      if (t.messages_sent)
        std::printf(" %s %llu", std::string(protocols::to_string(static_cast<protocols::MessageType>(p))).c_str(),
                    static_cast<unsigned long long>(t.messages_sent));
    }
    std::printf("\ntime         %.6f s simulated, %.3f s wall, %llu events (%.3g events/s), peak memory %.1f MiB\n",
                static_cast<double>(report.simulated_time) * 1e-9, report.wall_seconds,
                static_cast<unsigned long long>(report.events_processed), report.events_per_second,
                static_cast<double>(report.peak_memory_bytes) / (1024.0 * 1024.0));
    if (a.verify) std::printf("verify       %s\n", verify.c_str());
    std::printf("forwarding   %zu/%zu packets delivered hop by hop (greedy power), %.2f hops on average\n", delivered,
                pairs.size(), delivered ? hops / static_cast<double>(delivered) : 0.0);
  }
  return converged == n ? 0 : 3;
}
}  // namespace

Action add_simulate_command(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Run the distributed packing protocol, one actor per node, in the discrete-event simulator.");
  cmd->footer("Then every selected pair sends a packet, forwarded hop by hop by greedy power routing.\n"
              "Exit status: 0 converged, 3 not converged, 2 bad input.");
  cmd->add_option("graph", args->graph, "Graph file (edge list, coords or planar_code)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--format", args->format, "Input format: automatic, edges, coords, planar_code")->capture_default_str();
  cmd->add_option("--index", args->index, "Which graph of a multi-graph file (from 1)")->capture_default_str();
  cmd->add_option("--mode", args->mode, "Protocol mode: sync (async arrives with the fault-tolerant protocol)")
      ->capture_default_str();
  cmd->add_option("--latency", args->latency, "constant:D, uniform:LO:HI or distance:BASE:NS_PER_UNIT[:JITTER]")
      ->capture_default_str();
  cmd->add_option("--loss", args->loss, "Loss probability per copy")->capture_default_str();
  cmd->add_option("--dup", args->dup, "Duplication probability per message")->capture_default_str();
  cmd->add_option("--seed", args->seed, "Seed of every random stream (and of the pair sample)")->capture_default_str();
  cmd->add_option("--steps-per-round,-N", args->steps, "Thurston steps per round")->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--max-iterations", args->max_iterations, "Cap on Thurston steps")->capture_default_str();
  cmd->add_option("--root", args->root, "Layout root election: deepest or smallest-id")
      ->check(CLI::IsMember({"deepest", "smallest-id"}))->capture_default_str();
  cmd->add_option("--pairs", args->pairs, "'all' ordered pairs, or a number sampled with --seed")->capture_default_str();
  cmd->add_flag("--verify", args->verify, "Also run core::pack and check the nodes' circles are identical");
  cmd->add_flag("--json", args->json, "Machine-readable output");
  return [args] { return run_simulate(*args); };
}

}  // namespace laguerre::tools
