// The live host over UDP on 127.0.0.1 (sim::UdpHost, sim::LiveCluster, scenarios::run_live): on 1, 2
// and 4 worker processes the packing protocol's circles and iteration count are core::pack's bit for
// bit and every node converges, with and without induced loss; forwarding delivers what the simulator
// delivers with the same hops; malformed datagrams are counted and never reach a node, kernel drops
// are read from the socket and balance the datagrams sent; a port in use,
// a dead worker, a deadline and a datagram too small are clear errors. Every run is bounded by its
// timeout and ends by itself.

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <cstring>
#include <string>
#include <vector>

#include "../../support/BusyUdpPort.hpp"
#include "laguerre/core/Error.hpp"
#include "laguerre/core/graph/GraphIO.hpp"
#include "laguerre/core/graph/GraphKind.hpp"
#include "laguerre/core/packing/Packer.hpp"
#include "laguerre/core/routing/RoutingMetrics.hpp"
#include "laguerre/scenarios/LiveRun.hpp"
#include "laguerre/sim/UdpHost.hpp"

using namespace laguerre;

namespace {

struct Graph {
  core::PlanarGraph g;
  std::vector<core::Point2> positions;
  core::GraphKind kind{};
};

Graph load(const std::string& name) {
  auto inputs = core::read_graphs(std::string(LAGUERRE_TEST_DATA) + "/../../scenarios/graphs/" + name);
  Graph out;
  out.g = core::prepare_for_packing(inputs.front(), &out.kind);
  out.positions = inputs.front().positions;
  return out;
}

scenarios::LiveSetup live_setup(std::size_t processes) {
  scenarios::LiveSetup live;
  live.processes = processes;
  live.timeout_seconds = 30;
  live.assumed_latency = 500'000;
  return live;
}

void expect_core_pack(const Graph& gr, const scenarios::ProtocolSetup& setup, const scenarios::LiveOutcome& out) {
  core::PackOptions opt;
  opt.steps_per_check = setup.steps_per_round;
  opt.max_iterations = setup.max_iterations;
  opt.root = setup.root;
  const core::PackResult r = core::pack(gr.g, opt);
  ASSERT_EQ(out.packing.circles.size(), gr.g.num_vertices());
  EXPECT_EQ(static_cast<int>(out.packing.iterations), r.iterations);
  EXPECT_EQ(out.packing.converged_nodes, gr.g.num_vertices());
  EXPECT_EQ(out.packing.failed_nodes, 0u);
  for (core::Vertex v = 0; v < gr.g.num_vertices(); ++v) {
    // Bit for bit: the same doubles, not merely close ones.
    EXPECT_EQ(std::memcmp(&out.packing.circles[v], &r.circles[v], sizeof(core::Circle)), 0) << "vertex " << v;
  }
  EXPECT_EQ(scenarios::verify_against_core(gr.g, gr.kind, setup, out.packing), "identical to core::pack, bit for bit");
}

TEST(LiveRun, OneTwoAndFourProcessesGiveCorePackAndTheSimulatorsForwarding) {
  const Graph gr = load("delaunay-60.txt");
  scenarios::ProtocolSetup setup;
  const auto pairs = core::select_pairs(gr.g.num_vertices(), core::PairSelection{200, 7});
  const std::vector<core::Scheme> schemes{core::Scheme::greedy_power, core::Scheme::greedy_euclid};
  const scenarios::ProtocolOutcome sim = scenarios::run_packing_protocol(gr.g, gr.positions, setup);
  const auto sim_fwd = scenarios::run_forwarding(gr.g, sim.circles, gr.positions, setup.link, setup.seed, schemes, pairs);
  for (const std::size_t p : {1u, 2u, 4u}) {
    SCOPED_TRACE("processes " + std::to_string(p));
    const scenarios::LiveOutcome out = scenarios::run_live(gr.g, gr.positions, setup, live_setup(p), schemes, pairs);
    expect_core_pack(gr, setup, out);
    ASSERT_EQ(out.workers.size(), p);
    EXPECT_EQ(out.workers.back().first + out.workers.back().nodes, gr.g.num_vertices());
    EXPECT_EQ(out.packing.rounds, sim.rounds);
    // One process never touches the socket; several do, and nothing is lost on the way.
    EXPECT_EQ(out.total.datagrams_sent == 0, p == 1);
    EXPECT_EQ(out.total.datagrams_sent, out.total.datagrams_received);
    EXPECT_EQ(out.total.malformed + out.total.unknown_destination + out.total.not_a_neighbour + out.total.stale_phase, 0u);
    ASSERT_EQ(out.forwarding.size(), sim_fwd.size());
    for (std::size_t s = 0; s < schemes.size(); ++s) {
      EXPECT_EQ(out.forwarding[s].packets, pairs.size());
      EXPECT_EQ(out.forwarding[s].delivered, sim_fwd[s].delivered);
      EXPECT_EQ(out.forwarding[s].dead_ends, sim_fwd[s].dead_ends);
      EXPECT_EQ(out.forwarding[s].hops_mean, sim_fwd[s].hops_mean);
      EXPECT_EQ(out.forwarding[s].stretch_max, sim_fwd[s].stretch_max);
    }
  }
}

TEST(LiveRun, AnyPartitionGivesTheSameResult) {
  // Nodes dealt round-robin over three workers (every link but a few crosses processes, the worst
  // partition): still core::pack bit for bit and the simulator's forwarding.
  const Graph gr = load("delaunay-60.txt");
  scenarios::ProtocolSetup setup;
  const auto pairs = core::select_pairs(gr.g.num_vertices(), core::PairSelection{100, 3});
  const std::vector<core::Scheme> schemes{core::Scheme::greedy_power};
  const scenarios::ProtocolOutcome sim = scenarios::run_packing_protocol(gr.g, gr.positions, setup);
  const auto sim_fwd = scenarios::run_forwarding(gr.g, sim.circles, gr.positions, setup.link, setup.seed, schemes, pairs);
  scenarios::LiveSetup live = live_setup(3);
  for (std::size_t v = 0; v < gr.g.num_vertices(); ++v) live.process_of.push_back(v % 3);
  const scenarios::LiveOutcome out = scenarios::run_live(gr.g, gr.positions, setup, live, schemes, pairs);
  expect_core_pack(gr, setup, out);
  ASSERT_EQ(out.workers.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(out.workers[k].nodes, 20u);
    EXPECT_EQ(out.workers[k].first, k);
  }
  EXPECT_EQ(out.forwarding[0].delivered, sim_fwd[0].delivered);
  EXPECT_EQ(out.forwarding[0].hops_mean, sim_fwd[0].hops_mean);
  // A partition that leaves a worker empty, or does not cover the vertices, is refused before forking.
  live.process_of.assign(gr.g.num_vertices(), 0);
  EXPECT_THROW(scenarios::run_live(gr.g, gr.positions, setup, live, schemes, pairs), core::InputError);
  live.process_of.assign(5, 0);
  EXPECT_THROW(scenarios::run_live(gr.g, gr.positions, setup, live, schemes, pairs), core::InputError);
}

TEST(LiveRun, InducedLossIsMaskedByTheReliabilityLayer) {
  const Graph gr = load("delaunay-60.txt");
  scenarios::ProtocolSetup setup;
  setup.link.loss = 0.2;
  const auto pairs = core::select_pairs(gr.g.num_vertices(), core::PairSelection{100, 3});
  const scenarios::LiveOutcome out =
      scenarios::run_live(gr.g, gr.positions, setup, live_setup(2), {core::Scheme::greedy_power}, pairs);
  expect_core_pack(gr, setup, out);
  EXPECT_GT(out.total.induced_losses, 0u);
  EXPECT_GT(out.packing.reliability.retransmissions, 0u);
  ASSERT_EQ(out.forwarding.size(), 1u);
  const auto sim_fwd = scenarios::run_forwarding(gr.g, out.packing.circles, gr.positions, {}, 1,
                                                 {core::Scheme::greedy_power}, pairs);
  EXPECT_EQ(out.forwarding[0].delivered, sim_fwd[0].delivered);
  EXPECT_EQ(out.forwarding[0].hops_mean, sim_fwd[0].hops_mean);
}

TEST(LiveRun, APortInUseIsABadInputError) {
  const laguerre::testing::BusyUdpPort busy;
  const Graph gr = load("delaunay-60.txt");
  scenarios::LiveSetup live = live_setup(1);
  live.base_port = busy.port();
  try {
    scenarios::run_live(gr.g, gr.positions, {}, live, {}, {});
    ADD_FAILURE() << "no error for a port in use";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:" + std::to_string(live.base_port) + " is in use"), std::string::npos)
        << e.what();
  }
}

TEST(LiveRun, ADeadWorkerEndsTheRunWithAClearError) {
  const Graph gr = load("delaunay-60.txt");
  scenarios::LiveSetup live = live_setup(3);
  live.fail_worker = 1;
  const auto start = std::chrono::steady_clock::now();
  try {
    scenarios::run_live(gr.g, gr.positions, {}, live, {}, {});
    ADD_FAILURE() << "no error for a dead worker";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("worker 1 (20 nodes from vertex 20"), std::string::npos) << what;
    EXPECT_NE(what.find("exited with status 70"), std::string::npos) << what;
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

TEST(LiveRun, TheDeadlineStopsEveryWorker) {
  const Graph gr = load("three-connected-60.txt");
  scenarios::ProtocolSetup setup;
  setup.link.loss = 0.5;  // far too slow for the deadline below
  scenarios::LiveSetup live = live_setup(2);
  live.timeout_seconds = 0.5;
  const auto start = std::chrono::steady_clock::now();
  try {
    scenarios::run_live(gr.g, gr.positions, setup, live, {}, {});
    ADD_FAILURE() << "no error past the deadline";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("timed out after 0.5"), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

TEST(LiveRun, KernelDropsWithoutTheReliabilityLayerEndTheRunAtOnce) {
  // Receive buffers of a few KiB: batched datagrams overflow them (a datagram larger than the buffer
  // is always dropped). Without the reliability layer the run must then stop with a clear error long
  // before its deadline; if the kernel happened to drop nothing, the result is still exact.
  const Graph gr = load("three-connected-60.txt");
  scenarios::LiveSetup live = live_setup(4);
  live.socket_buffer = 1024;
  const auto start = std::chrono::steady_clock::now();
  try {
    const scenarios::LiveOutcome out = scenarios::run_live(gr.g, gr.positions, {}, live, {}, {});
    EXPECT_EQ(out.total.kernel_drops, 0u);
    expect_core_pack(gr, {}, out);
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the kernel dropped"), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

TEST(LiveRun, AMessageLargerThanTheDatagramIsABadInputError) {
  const Graph gr = load("delaunay-60.txt");
  scenarios::LiveSetup live = live_setup(2);
  live.max_datagram = sim::udp_header_size + sim::udp_record_header + 4;  // smaller than any packing message
  EXPECT_THROW(
      {
        try {
          scenarios::run_live(gr.g, gr.positions, {}, live, {}, {});
        } catch (const core::InputError& e) {
          EXPECT_NE(std::string(e.what()).find("too large for a UDP datagram"), std::string::npos) << e.what();
          throw;
        }
      },
      core::InputError);
}

// A node that records what it receives.
struct Recorder final : protocols::Node {
  explicit Recorder(std::vector<protocols::NodeId>& from) : from_(from) {}
  void on_start() override {}
  void on_message(protocols::NodeId from, std::span<const std::byte>) override { from_.push_back(from); }
  void on_timer(protocols::TimerId) override {}
  std::vector<protocols::NodeId>& from_;
};

TEST(UdpHost, MalformedDatagramsAreCountedAndNeverDelivered) {
  const Graph gr = load("delaunay-60.txt");
  const std::size_t n = gr.g.num_vertices();
  // This process hosts vertices 0..29; 30..59 belong to process 1 (which is never started).
  std::vector<std::size_t> process_of(n, 0);
  for (std::size_t v = n / 2; v < n; ++v) process_of[v] = 1;
  boost::asio::io_context io;
  sim::UdpHostConfig config;
  config.run_tag = 0x01020304;
  sim::UdpHost host(io, gr.g, process_of, 0, config);
  host.set_ports({host.port(), host.port()});
  std::vector<protocols::NodeId> received;
  host.start_phase(0, [&](protocols::Runtime&, core::Vertex) { return std::make_unique<Recorder>(received); });
  host.start_receiving();

  // One datagram with one record of 4 bytes (`cut` bytes fewer at the end: a truncated record).
  const auto datagram = [&](std::uint64_t dst, std::uint64_t src, std::uint8_t magic, std::uint32_t tag,
                            std::size_t cut = 0) {
    std::vector<std::byte> d(sim::udp_header_size + sim::udp_record_header + 4, std::byte{0});
    d[0] = std::byte{magic};
    d[1] = std::byte{1};
    const std::size_t r = sim::udp_header_size;
    for (int i = 0; i < 4; ++i) d[4 + i] = static_cast<std::byte>(tag >> (8 * i));
    for (int i = 0; i < 8; ++i) d[r + i] = static_cast<std::byte>(dst >> (8 * i));
    for (int i = 0; i < 8; ++i) d[r + 8 + i] = static_cast<std::byte>(src >> (8 * i));
    d[r + 16] = std::byte{4};
    d.resize(d.size() - cut);
    return d;
  };
  const core::Vertex v = 0;
  const core::Vertex w = gr.g.neighbours(v)[0];
  core::Vertex far = 0;  // a hosted vertex that is no neighbour of v
  for (core::Vertex u = 1; u < n / 2; ++u) {
    const auto nb = gr.g.neighbours(v);
    if (std::find(nb.begin(), nb.end(), u) == nb.end()) {
      far = u;
      break;
    }
  }
  ASSERT_NE(far, 0u);
  const std::vector<std::byte> garbage(3, std::byte{0x4c});
  host.send_raw(0, garbage);                                                    // shorter than a header
  host.send_raw(0, datagram(gr.g.id(v), gr.g.id(w), 0x00, config.run_tag));    // bad magic
  host.send_raw(0, datagram(gr.g.id(v), gr.g.id(w), 0x4c, 0xdeadbeef));       // another run's tag
  host.send_raw(0, datagram(gr.g.id(static_cast<core::Vertex>(n - 1)), gr.g.id(w), 0x4c, config.run_tag));  // not hosted here
  host.send_raw(0, datagram(gr.g.id(v), gr.g.id(far), 0x4c, config.run_tag));  // not a neighbour
  host.send_raw(0, datagram(gr.g.id(v), gr.g.id(w), 0x4c, config.run_tag, 1));  // truncated record
  host.send_raw(0, datagram(gr.g.id(v), gr.g.id(w), 0x4c, config.run_tag, 8));  // truncated record header
  host.send_raw(0, datagram(gr.g.id(v), gr.g.id(w), 0x4c, config.run_tag));    // fine
  for (int i = 0; i < 200 && received.empty(); ++i) io.run_for(std::chrono::milliseconds(5));
  io.run_for(std::chrono::milliseconds(20));
  EXPECT_EQ(host.counters().malformed, 5u);
  EXPECT_EQ(host.counters().unknown_destination, 1u);
  EXPECT_EQ(host.counters().not_a_neighbour, 1u);
  EXPECT_EQ(host.counters().datagrams_received, 5u);  // those with a well-formed header
  ASSERT_EQ(received.size(), 1u);
  EXPECT_EQ(received[0], gr.g.id(w));
  EXPECT_EQ(host.kernel_drops(), 0u);
  EXPECT_TRUE(host.idle());
}

TEST(UdpHost, BadConfigurationIsABadInputError) {
  const Graph gr = load("delaunay-60.txt");
  boost::asio::io_context io;
  sim::UdpHostConfig config;
  config.loss = 1.5;
  EXPECT_THROW(sim::UdpHost(io, gr.g, std::vector<std::size_t>(gr.g.num_vertices(), 0), 0, config), core::InputError);
  config.loss = 0;
  config.max_datagram = sim::max_udp_payload + 1;
  EXPECT_THROW(sim::UdpHost(io, gr.g, std::vector<std::size_t>(gr.g.num_vertices(), 0), 0, config), core::InputError);
}

}  // namespace

namespace {
TEST(UdpHost, KernelDropsAreCountedAndBalanceTheDatagramsSent) {
  const Graph gr = load("delaunay-60.txt");
  boost::asio::io_context io;
  sim::UdpHostConfig config;
  config.run_tag = 7;
  config.socket_buffer = 4096;  // a few datagrams at most: the kernel drops the rest
  sim::UdpHost host(io, gr.g, std::vector<std::size_t>(gr.g.num_vertices(), 0), 0, config);
  host.set_ports({host.port()});
  std::vector<protocols::NodeId> received;
  host.start_phase(0, [&](protocols::Runtime&, core::Vertex) { return std::make_unique<Recorder>(received); });
  // Well-formed datagrams whose single record is for a node nobody hosts, sent before anyone reads.
  std::vector<std::byte> d(sim::udp_header_size + sim::udp_record_header + 1000, std::byte{0});
  d[0] = std::byte{0x4c};
  d[1] = std::byte{1};
  d[4] = std::byte{7};
  for (int i = 0; i < 8; ++i) d[sim::udp_header_size + i] = std::byte{0xff};  // id 2^64 - 1
  d[sim::udp_header_size + 16] = static_cast<std::byte>(1000 & 0xff);
  d[sim::udp_header_size + 17] = static_cast<std::byte>(1000 >> 8);
  constexpr std::uint64_t sent = 200;
  for (std::uint64_t i = 0; i < sent; ++i) host.send_raw(0, d);
  host.start_receiving();
  io.run_for(std::chrono::milliseconds(50));
  const std::uint64_t drops = host.kernel_drops();
  EXPECT_GT(drops, 0u);
  EXPECT_EQ(host.counters().datagrams_received + drops, sent);
  EXPECT_EQ(host.counters().unknown_destination, host.counters().datagrams_received);
  EXPECT_TRUE(received.empty());
}
}  // namespace
