#pragma once
// The ns-3 world of the worked example (C++17-clean: no ns-3 and no C++20 laguerre header, so that
// main.cpp, which is C++20, can include it): nodes with an internet stack, one point-to-point link per
// graph edge (a /30 subnet each) or one ad-hoc Wi-Fi channel, and a laguerre NodeApplication on every
// node. Ns3Network.cpp is the only file that includes ns-3.

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "laguerre/ns3/HostPort.hpp"

namespace laguerre::ns3example {

enum class LinkKind { point_to_point, wifi };

struct NetworkSpec {
  LinkKind link = LinkKind::point_to_point;
  std::vector<std::uint64_t> ids;                   // node i's laguerre id
  std::vector<std::vector<std::size_t>> neighbours;  // node i's neighbours (indices; symmetric)
  std::vector<std::array<double, 2>> positions;      // Wi-Fi: node i's position in the graph's units
  std::int64_t delay_ns = 1000000;                   // point-to-point: every link's delay
  std::string data_rate = "100Mbps";                 // point-to-point: every link's rate
  std::uint64_t seed = 1;                            // the nodes' random streams
  std::uint16_t port = 9000;                         // the UDP port of every node
  bool dynamic_arp = false;                          // Wi-Fi: resolve addresses with ARP (else filled up front)
};

struct PhaseReport {
  std::int64_t started_ns = 0;        // simulated time when the phase began
  std::int64_t last_activity_ns = 0;  // last callback of any hosted node (≥ started_ns)
  std::uint64_t events = 0;           // ns-3 events executed in the phase
  double wall_seconds = 0;            // wall-clock time of Simulator::Run
};

class Ns3Network {
public:
  // Builds the world (ns-3's simulator is a process-wide singleton: one Ns3Network at a time).
  // Throws core::InputError for Wi-Fi without positions or with coincident nodes.
  explicit Ns3Network(const NetworkSpec& spec);
  ~Ns3Network();  // Simulator::Destroy
  Ns3Network(const Ns3Network&) = delete;
  Ns3Network& operator=(const Ns3Network&) = delete;

  // One line describing links, addressing and radio.
  std::string description() const;
  // Hosts on node i the node make(i) builds (replacing the current one; see NodeApplication::host).
  void host(const std::function<ns3host::HostedFactory(std::size_t)>& make);
  // Runs f at the current simulated time in node i's context, after the nodes hosted so far started.
  void at_node(std::size_t i, std::function<void()> f);
  // Runs the simulator until no event is left or `limit_ns` of simulated time have passed.
  PhaseReport run(std::int64_t limit_ns);
  // The node hosted on node i.
  ns3host::HostedNode& hosted(std::size_t i);
  // Datagram statistics of all applications.
  ns3host::HostCounters counters() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace laguerre::ns3example
