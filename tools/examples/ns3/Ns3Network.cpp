// The ns-3 world of the worked example; the only file of the example that includes ns-3 (C++17).
#include "Ns3Network.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>

#include "laguerre/core/Error.hpp"
#include "laguerre/ns3/NodeApplication.hpp"
#include "ns3/core-module.h"
#include "ns3/internet-module.h"
#include "ns3/neighbor-cache-helper.h"
#include "ns3/mobility-module.h"
#include "ns3/network-module.h"
#include "ns3/point-to-point-module.h"
#include "ns3/wifi-module.h"

namespace laguerre::ns3example {

struct Ns3Network::Impl {
  ::ns3::NodeContainer nodes;
  std::vector<::ns3::Ptr<ns3host::NodeApplication>> apps;
  std::string description;
};

namespace {
std::string format(const char* fmt, double a, double b = 0, double c = 0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}
}  // namespace

Ns3Network::Ns3Network(const NetworkSpec& spec) : impl_(std::make_unique<Impl>()) {
  const std::size_t n = spec.ids.size();
  ::ns3::RngSeedManager::SetSeed(1);
  ::ns3::RngSeedManager::SetRun(spec.seed);  // ns-3's own streams (Wi-Fi backoff), one run per seed
  impl_->nodes.Create(static_cast<std::uint32_t>(n));
  ::ns3::InternetStackHelper stack;
  std::vector<std::vector<ns3host::Neighbour>> neighbours(n);
  if (spec.link == LinkKind::point_to_point) {
    // One link per edge, each its own /30 subnet: a node has one interface (and address) per
    // neighbour, and a datagram to the neighbour's address on the shared link leaves through that
    // link (the subnet's connected route), so no routing protocol is needed.
    ::ns3::PointToPointHelper p2p;
    p2p.SetDeviceAttribute("DataRate", ::ns3::StringValue(spec.data_rate));
    p2p.SetChannelAttribute("Delay", ::ns3::TimeValue(::ns3::NanoSeconds(spec.delay_ns)));
    p2p.SetQueue("ns3::DropTailQueue<Packet>", "MaxSize", ::ns3::QueueSizeValue(::ns3::QueueSize("100000p")));
    stack.Install(impl_->nodes);
    ::ns3::Ipv4AddressHelper addresses("10.0.0.0", "255.255.255.252");
    std::map<std::pair<std::size_t, std::size_t>, ::ns3::Ipv4Address> address_of;  // (i, j) → j's address on link ij
    std::size_t links = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (const std::size_t j : spec.neighbours[i]) {
        if (j < i) continue;
        const ::ns3::NetDeviceContainer devices = p2p.Install(impl_->nodes.Get(static_cast<std::uint32_t>(i)),
                                                              impl_->nodes.Get(static_cast<std::uint32_t>(j)));
        const ::ns3::Ipv4InterfaceContainer interfaces = addresses.Assign(devices);
        addresses.NewNetwork();
        address_of[{i, j}] = interfaces.GetAddress(1);
        address_of[{j, i}] = interfaces.GetAddress(0);
        ++links;
      }
    for (std::size_t i = 0; i < n; ++i)
      for (const std::size_t j : spec.neighbours[i]) neighbours[i].push_back({spec.ids[j], address_of.at({i, j})});
    impl_->description = std::to_string(links) + " point-to-point links, one /30 subnet each in 10.0.0.0/8, delay " +
                         format("%.3f ms, ", static_cast<double>(spec.delay_ns) * 1e-6) + spec.data_rate +
                         "; UDP port " + std::to_string(spec.port);
  } else {
    if (spec.positions.size() != n)
      throw core::InputError("--link wifi", 0, "the Wi-Fi mode places the nodes at the graph's coordinates, and this graph has none");
    // Scale the graph so that its longest edge is 100 m; the radio reaches exactly the longest edge
    // (plus a hair): every edge is within range (and some non-edges, which just overhear).
    double longest = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (const std::size_t j : spec.neighbours[i])
        longest = std::max(longest, std::hypot(spec.positions[i][0] - spec.positions[j][0],
                                               spec.positions[i][1] - spec.positions[j][1]));
    if (!(longest > 0) || !std::isfinite(longest))
      throw core::InputError("--link wifi", 0, "the graph's edges must have positive finite lengths for a radio range");
    const double scale = 100.0 / longest, range = 100.0 * (1 + 1e-9);
    std::size_t in_range = 0;  // unordered pairs within radio range
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        in_range += std::hypot(spec.positions[i][0] - spec.positions[j][0], spec.positions[i][1] - spec.positions[j][1]) * scale <= range;
    ::ns3::WifiHelper wifi;
    wifi.SetStandard(::ns3::WIFI_STANDARD_80211a);
    wifi.SetRemoteStationManager("ns3::ConstantRateWifiManager", "DataMode", ::ns3::StringValue("OfdmRate6Mbps"),
                                 "ControlMode", ::ns3::StringValue("OfdmRate6Mbps"));
    ::ns3::YansWifiChannelHelper channel;
    channel.SetPropagationDelay("ns3::ConstantSpeedPropagationDelayModel");
    channel.AddPropagationLoss("ns3::RangePropagationLossModel", "MaxRange", ::ns3::DoubleValue(range));
    ::ns3::YansWifiPhyHelper phy;
    phy.SetChannel(channel.Create());
    ::ns3::WifiMacHelper mac;
    mac.SetType("ns3::AdhocWifiMac");
    const ::ns3::NetDeviceContainer devices = wifi.Install(phy, mac, impl_->nodes);
    ::ns3::MobilityHelper mobility;
    const auto where = ::ns3::CreateObject<::ns3::ListPositionAllocator>();
    for (const auto& p : spec.positions) where->Add(::ns3::Vector(p[0] * scale, p[1] * scale, 0));
    mobility.SetPositionAllocator(where);
    mobility.SetMobilityModel("ns3::ConstantPositionMobilityModel");
    mobility.Install(impl_->nodes);
    stack.Install(impl_->nodes);
    ::ns3::Ipv4AddressHelper addresses("10.0.0.0", "255.0.0.0");
    const ::ns3::Ipv4InterfaceContainer interfaces = addresses.Assign(devices);
    // Dynamic ARP on a busy channel loses its broadcasts, and a failed resolution blackholes the
    // neighbour for ArpCache::DeadTimeout (100 s): by default the caches are filled up front.
    if (!spec.dynamic_arp) ::ns3::NeighborCacheHelper().PopulateNeighborCache(interfaces);
    for (std::size_t i = 0; i < n; ++i)
      for (const std::size_t j : spec.neighbours[i])
        neighbours[i].push_back({spec.ids[j], interfaces.GetAddress(static_cast<std::uint32_t>(j))});
    std::size_t edges = 0;
    for (const auto& nb : spec.neighbours) edges += nb.size();
    impl_->description = "ad-hoc Wi-Fi (802.11a at 6 Mb/s, YansWifi, range propagation) on one channel; positions scaled " +
                         format("x%.4g (longest edge 100 m), range %.1f m: %.0f node pairs in range for ", scale, range,
                                static_cast<double>(in_range)) +
                         std::to_string(edges / 2) + " edges; one subnet 10.0.0.0/8, " + (spec.dynamic_arp ? "dynamic ARP" : "ARP caches filled up front") +
                         "; UDP port " + std::to_string(spec.port);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto app = ::ns3::CreateObject<ns3host::NodeApplication>();
    app->configure(spec.ids[i], std::move(neighbours[i]), spec.port, spec.seed);
    impl_->nodes.Get(static_cast<std::uint32_t>(i))->AddApplication(app);
    app->SetStartTime(::ns3::Seconds(0));
    impl_->apps.push_back(app);
  }
}

Ns3Network::~Ns3Network() {
  impl_->apps.clear();
  ::ns3::Simulator::Destroy();
}

std::string Ns3Network::description() const { return impl_->description; }

void Ns3Network::host(const std::function<ns3host::HostedFactory(std::size_t)>& make) {
  for (std::size_t i = 0; i < impl_->apps.size(); ++i) impl_->apps[i]->host(make(i));
}

void Ns3Network::at_node(std::size_t i, std::function<void()> f) {
  ::ns3::Simulator::ScheduleWithContext(impl_->nodes.Get(static_cast<std::uint32_t>(i))->GetId(), ::ns3::Seconds(0),
                                        std::move(f));
}

PhaseReport Ns3Network::run(std::int64_t limit_ns) {
  PhaseReport r;
  r.started_ns = ::ns3::Simulator::Now().GetNanoSeconds();
  const std::uint64_t events = ::ns3::Simulator::GetEventCount();
  ::ns3::Simulator::Stop(::ns3::NanoSeconds(limit_ns));
  const auto start = std::chrono::steady_clock::now();
  ::ns3::Simulator::Run();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.events = ::ns3::Simulator::GetEventCount() - events;
  r.last_activity_ns = r.started_ns;
  for (const auto& app : impl_->apps) r.last_activity_ns = std::max(r.last_activity_ns, app->last_activity());
  return r;
}

ns3host::HostedNode& Ns3Network::hosted(std::size_t i) { return *impl_->apps.at(i)->hosted(); }

ns3host::HostCounters Ns3Network::counters() const {
  ns3host::HostCounters total;
  for (const auto& app : impl_->apps) total += app->counters();
  return total;
}

}  // namespace laguerre::ns3example
