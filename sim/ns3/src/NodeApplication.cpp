// The ns-3 half of the adapter (compiled as C++17): one laguerre node per ns3::Application.
#include "laguerre/ns3/NodeApplication.hpp"

#include <algorithm>
#include <string>

#include "laguerre/core/Error.hpp"
#include "ns3/inet-socket-address.h"
#include "ns3/packet.h"
#include "ns3/simulator.h"
#include "ns3/udp-socket-factory.h"

namespace laguerre::ns3host {

NS_OBJECT_ENSURE_REGISTERED(NodeApplication);

::ns3::TypeId NodeApplication::GetTypeId() {
  static ::ns3::TypeId tid = ::ns3::TypeId("laguerre::ns3host::NodeApplication")
                                 .SetParent<::ns3::Application>()
                                 .SetGroupName("laguerre")
                                 .AddConstructor<NodeApplication>();
  return tid;
}

NodeApplication::NodeApplication() = default;
NodeApplication::~NodeApplication() = default;

void NodeApplication::configure(NodeId self, std::vector<Neighbour> neighbours, std::uint16_t port, std::uint64_t seed) {
  LAGUERRE_PRECONDITION(!configured_ && !running_, "NodeApplication::configure is called once, before the start.");
  self_ = self;
  port_ = port;
  seed_ = seed;
  neighbours_ = std::move(neighbours);
  for (const Neighbour& nb : neighbours_) {
    LAGUERRE_PRECONDITION(nb.id != self, "A node is not its own neighbour.");
    neighbour_ids_.push_back(nb.id);
    by_address_.emplace_back(nb.address.Get(), nb.id);
  }
  std::sort(by_address_.begin(), by_address_.end());
  std::vector<NodeId> ids = neighbour_ids_;
  std::sort(ids.begin(), ids.end());
  LAGUERRE_PRECONDITION(std::adjacent_find(ids.begin(), ids.end()) == ids.end(), "Neighbour ids must be distinct.");
  LAGUERRE_PRECONDITION(std::adjacent_find(by_address_.begin(), by_address_.end(),
                                           [](const auto& a, const auto& b) { return a.first == b.first; }) ==
                            by_address_.end(),
                        "Neighbour addresses must be distinct.");
  configured_ = true;
}

void NodeApplication::host(const HostedFactory& make) {
  LAGUERRE_PRECONDITION(configured_, "NodeApplication::host needs configure first.");
  LAGUERRE_PRECONDITION(!busy_, "NodeApplication::host is not called from inside the hosted node.");
  cancel_all();
  inbox_.clear();
  node_.reset();
  started_ = false;
  node_ = make(*this);
  LAGUERRE_PRECONDITION(node_ != nullptr, "The factory given to NodeApplication::host returned no node.");
  if (running_) ::ns3::Simulator::ScheduleWithContext(GetNode()->GetId(), ::ns3::Seconds(0), &NodeApplication::start_node, this);
}

void NodeApplication::StartApplication() {
  LAGUERRE_PRECONDITION(configured_, "NodeApplication started before configure.");
  socket_ = ::ns3::Socket::CreateSocket(GetNode(), ::ns3::UdpSocketFactory::GetTypeId());
  if (socket_->Bind(::ns3::InetSocketAddress(::ns3::Ipv4Address::GetAny(), port_)) != 0)
    throw core::InputError("ns-3 node " + std::to_string(self_), 0,
                           "cannot bind UDP port " + std::to_string(port_) + " (is it in use by another application?)");
  socket_->SetRecvCallback(::ns3::MakeCallback(&NodeApplication::receive, this));
  running_ = true;
  start_node();
}

void NodeApplication::StopApplication() {
  running_ = false;
  cancel_all();
  inbox_.clear();
  if (socket_) {
    socket_->SetRecvCallback(::ns3::MakeNullCallback<void, ::ns3::Ptr<::ns3::Socket>>());
    socket_->Close();
    socket_ = nullptr;
  }
}

void NodeApplication::DoDispose() {
  StopApplication();
  node_.reset();
  ::ns3::Application::DoDispose();
}

Time NodeApplication::now() const { return ::ns3::Simulator::Now().GetNanoSeconds(); }

void NodeApplication::send(NodeId to, const std::byte* data, std::size_t size) {
  const auto it = std::find(neighbour_ids_.begin(), neighbour_ids_.end(), to);
  LAGUERRE_PRECONDITION(it != neighbour_ids_.end(), "A node sends only to its neighbours.");
  if (size > max_datagram)
    throw core::InputError("ns-3 node " + std::to_string(self_), 0,
                           "a message of " + std::to_string(size) + " bytes to node " + std::to_string(to) +
                               " does not fit in one UDP datagram (at most " + std::to_string(max_datagram) + " bytes)");
  LAGUERRE_PRECONDITION(socket_ != nullptr, "A hosted node sends only while its application runs.");
  const Neighbour& nb = neighbours_[static_cast<std::size_t>(it - neighbour_ids_.begin())];
  const auto packet = ::ns3::Create<::ns3::Packet>(reinterpret_cast<const std::uint8_t*>(data), static_cast<std::uint32_t>(size));
  if (socket_->SendTo(packet, 0, ::ns3::InetSocketAddress(nb.address, port_)) < 0) {
    ++counters_.send_failures;
    return;
  }
  ++counters_.datagrams_sent;
  counters_.bytes_sent += size;
}

TimerHandle NodeApplication::schedule(Duration after, TimerId timer) {
  LAGUERRE_PRECONDITION(after >= 0, "A timer is scheduled after a delay >= 0.");
  const TimerHandle handle = next_handle_++;
  timers_.emplace(handle, ::ns3::Simulator::Schedule(::ns3::NanoSeconds(after), &NodeApplication::fire, this, handle, timer));
  return handle;
}

bool NodeApplication::cancel(TimerHandle handle) {
  const auto it = timers_.find(handle);
  if (it != timers_.end()) {
    it->second.Cancel();
    timers_.erase(it);
    return true;
  }
  // Fired but not yet handed to the node (queued behind other input): still pending for the node.
  const auto queued = std::find_if(inbox_.begin(), inbox_.end(), [&](const Input& in) { return in.is_timer && in.handle == handle; });
  if (queued == inbox_.end()) return false;
  inbox_.erase(queued);
  return true;
}

void NodeApplication::start_node() {
  if (!node_ || started_) return;
  started_ = true;
  busy_ = true;
  last_activity_ = now();
  try {
    node_->start();
  } catch (...) {
    busy_ = false;
    throw;
  }
  busy_ = false;
  dispatch();
}

void NodeApplication::receive(::ns3::Ptr<::ns3::Socket> socket) {
  ::ns3::Address from;
  while (const ::ns3::Ptr<::ns3::Packet> packet = socket->RecvFrom(from)) {
    const std::uint32_t source = ::ns3::InetSocketAddress::ConvertFrom(from).GetIpv4().Get();
    const auto it = std::lower_bound(by_address_.begin(), by_address_.end(), std::make_pair(source, NodeId{0}));
    if (it == by_address_.end() || it->first != source) {
      ++counters_.unknown_sources;
      continue;
    }
    Input in;
    in.from = it->second;
    in.bytes.resize(packet->GetSize());
    packet->CopyData(reinterpret_cast<std::uint8_t*>(in.bytes.data()), packet->GetSize());
    inbox_.push_back(std::move(in));
  }
  dispatch();
}

void NodeApplication::fire(TimerHandle handle, TimerId timer) {
  timers_.erase(handle);
  Input in;
  in.is_timer = true;
  in.timer = timer;
  in.handle = handle;
  inbox_.push_back(std::move(in));
  dispatch();
}

void NodeApplication::dispatch() {
  if (busy_ || !started_) return;  // the running callback's caller drains the queue
  busy_ = true;
  try {
    while (!inbox_.empty()) {
      const Input in = std::move(inbox_.front());
      inbox_.pop_front();
      last_activity_ = now();
      if (in.is_timer) {
        ++counters_.timers_fired;
        node_->timer(in.timer);
      } else {
        ++counters_.datagrams_received;
        counters_.bytes_received += in.bytes.size();
        node_->message(in.from, in.bytes.data(), in.bytes.size());
      }
    }
  } catch (...) {
    busy_ = false;
    throw;
  }
  busy_ = false;
}

void NodeApplication::cancel_all() {
  for (auto& [handle, event] : timers_) event.Cancel();
  timers_.clear();
}

}  // namespace laguerre::ns3host
