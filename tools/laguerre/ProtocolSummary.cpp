// What `laguerre simulate` and `laguerre live` print about a protocol run (text or JSON).
#include "ProtocolSummary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"
#include "laguerre/protocols/Codec.hpp"

namespace laguerre::tools {

std::string_view outcome_name(protocols::PackingOutcome o) {
  switch (o) {
    case protocols::PackingOutcome::running: return "running";
    case protocols::PackingOutcome::converged: return "converged";
    case protocols::PackingOutcome::cap: return "cap";
    case protocols::PackingOutcome::neighbour_failed: return "neighbour_failed";
  }
  return "?";
}

int print_protocol_summary(const ProtocolSummary& s, bool json) {
  const LoadedGraph& loaded = s.loaded;
  const scenarios::ProtocolSetup& setup = s.setup;
  const scenarios::ProtocolOutcome& po = s.po;
  const std::vector<scenarios::ForwardingResult>& results = s.results;
  const std::vector<core::Scheme>& schemes = s.schemes;
  const core::PlanarGraph& g = loaded.input.graph;
  const std::size_t n = g.num_vertices();
  const bool input_positions = !loaded.input.positions.empty();
  const std::size_t converged = po.converged_nodes, holds = po.holds_nodes, failed = po.failed_nodes;
  const std::uint32_t steps = po.iterations, rounds = po.rounds;
  const bool lossy = po.lossy;
  const protocols::PackingCounters& rel = po.reliability;
  std::string suspect_list;
  for (const auto& [id, count] : po.suspects)
    suspect_list += (suspect_list.empty() ? "" : ", ") + std::to_string(id) + " (" + std::to_string(count) + " nodes)";

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
  if (json) {
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
                          {"outer_rule", s.outer},
                          {"removed_vertices", loaded.removed},
                          {"converged_nodes", converged},
                          {"local_condition_holds", holds},
                          {"iterations", steps},
                          {"mode", s.mode},
                          {"termination", std::string(core::to_string(setup.termination))},
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
    if (!s.forwarding_skipped.empty()) doc["forwarding_skipped"] = s.forwarding_skipped;
    if (s.verify) doc["verify"] = *s.verify;
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
    if (s.extra.is_object()) doc.update(s.extra);
    std::cout << doc.dump(1) << '\n';
  } else {
    std::printf("graph        %s: %zu nodes, %zu edges, %s\n", loaded.input.name.c_str(), n, g.num_edges(),
                std::string(core::to_string(loaded.kind)).c_str());
    std::fputs(removed_line(loaded.removed).c_str(), stdout);
    std::printf("protocol     %s after %u %s in %u rounds (N = %d); %zu/%zu nodes report %s\n",
                converged == n ? "converged" : "did not converge", steps,
                setup.asynchronous ? "iteration-equivalents (asynchronous)" : "iterations", rounds, setup.steps_per_round, holds, n,
                loaded.kind == core::GraphKind::triangulated_disc ? "LPD" : "GLPD");
    if (setup.termination != core::Termination::layout)
      std::printf("termination  %s: %s; the layout wave ran only where the closing gap allowed, and LPD is "
                  "claimed only on its exact check\n",
                  std::string(core::to_string(setup.termination)).c_str(),
                  setup.termination == core::Termination::radius_flood
                      ? "the gap test's AND travels on the radius exchange (no convergecast per round)"
                      : "rounds end with one radius exchange");
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
    std::printf("\n");
    if (!s.time_line.empty())
      std::printf("%s\n", s.time_line.c_str());
    else
      std::printf("time         %.6f s simulated (every node final at %.6f s), %.3f s wall, %llu events (%.3g events/s), "
                "peak memory %.1f MiB\n",
                sim::to_seconds(po.simulated_time), sim::to_seconds(po.finished_at),
                po.wall_seconds,
                static_cast<unsigned long long>(po.events), po.events_per_second,
                static_cast<double>(po.peak_memory_bytes) / (1024.0 * 1024.0));
    if (s.verify) std::printf("verify       %s\n", s.verify->c_str());
    if (!s.forwarding_skipped.empty())
      std::printf("forwarding   skipped: %s\n", s.forwarding_skipped.c_str());
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

}  // namespace laguerre::tools
