#pragma once
/// @file
/// A live host: runs protocols::Node objects over real UDP on 127.0.0.1 (Boost.Asio), many nodes per
/// process, one single-threaded io_context and one socket per process.
///
/// Mapping of the Runtime contract (protocols/Runtime.hpp):
///  - send/broadcast: the bytes are copied; a message to a node of the same process goes to an
///    in-memory FIFO, one to another process into the datagram being filled for that process's port,
///    sent when full and after the current callback. Nothing is delivered during a callback: the FIFO
///    is drained after it returns.
///  - schedule/cancel: a timer heap served by one steady_timer (the steady clock); `now` is the
///    steady clock in nanoseconds since `UdpHostConfig::epoch`.
///  - random_u64: node v's stream RandomStream::of(seed, StreamKind::node, id), as in the simulator.
///  - induced loss (`UdpHostConfig::loss`): decided at the sender, one draw per message from the
///    directed link's stream RandomStream::of(seed, StreamKind::link, sender id, receiver id), for
///    local and remote neighbours alike.
///
/// Datagram (little-endian): an 8-byte header, u8 magic 0x4c, u8 version 1, u8 phase, u8 reserved 0,
/// u32 run tag; then one or more records, each u64 destination node id, u64 source node id, u32
/// length, and that many bytes of message. A datagram whose header does not match (size, magic,
/// version, tag, reserved byte) is counted `malformed`, and so is a truncated record (the rest of its
/// datagram is dropped); a record for a node this process does not host counts `unknown_destination`,
/// one whose source is no neighbour of its destination `not_a_neighbour`, a datagram of an earlier
/// phase `stale_phase`; none of them reaches a node. A datagram of a later phase is held until that
/// phase starts. Kernel drops (receive buffer overflow)
/// are read from the socket (SO_MEMINFO) on demand.

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "laguerre/core/graph/PlanarGraph.hpp"
#include "laguerre/protocols/Runtime.hpp"
#include "laguerre/sim/Metrics.hpp"
#include "laguerre/sim/Random.hpp"

namespace boost::asio {
class io_context;
}

namespace laguerre::sim {

/// Size of the datagram header (see the file comment).
inline constexpr std::size_t udp_header_size = 8;
/// Size of a record's header (destination, source, length) in a datagram.
inline constexpr std::size_t udp_record_header = 20;
/// Largest UDP payload over IPv4: a datagram (header included) never exceeds it.
inline constexpr std::size_t max_udp_payload = 65507;

/// How a UdpHost runs.
struct UdpHostConfig {
  std::uint64_t seed = 1;                      ///< root of every random stream
  double loss = 0;                             ///< probability that a message is dropped at the sender
  std::uint16_t port = 0;                      ///< port on 127.0.0.1 (0: one the kernel picks)
  int socket_buffer = 4 << 20;                 ///< SO_RCVBUF and SO_SNDBUF requested (bytes)
  std::size_t max_datagram = max_udp_payload;  ///< largest datagram, header included (≤ max_udp_payload)
  std::uint32_t run_tag = 0;                   ///< written into and checked on every datagram
  std::int64_t epoch = 0;                      ///< steady-clock nanoseconds of node time 0
};

/// What the host did (datagram counts are wire counts; local deliveries never touch the socket).
struct UdpCounters {
  std::uint64_t datagrams_sent = 0;       ///< datagrams handed to the kernel
  std::uint64_t datagram_bytes_sent = 0;  ///< their bytes, headers included
  std::uint64_t datagrams_received = 0;   ///< datagrams of this run received (header well-formed)
  std::uint64_t datagram_bytes_received = 0;  ///< their bytes
  std::uint64_t local_deliveries = 0;     ///< messages between nodes of this process (in memory)
  std::uint64_t induced_losses = 0;       ///< messages dropped at the sender (UdpHostConfig::loss)
  std::uint64_t malformed = 0;            ///< datagrams with a bad header or a truncated record
  std::uint64_t unknown_destination = 0;  ///< messages for a node this process does not host
  std::uint64_t not_a_neighbour = 0;      ///< messages whose source is no neighbour of the destination
  std::uint64_t stale_phase = 0;          ///< datagrams of an earlier phase
  std::uint64_t send_retries = 0;         ///< sends the kernel refused for a while (queued, sent later)
  std::uint64_t kernel_drops = 0;         ///< datagrams the kernel dropped at this socket (see kernel_drops())
  int receive_buffer = 0;                 ///< SO_RCVBUF the kernel granted (bytes)
  int send_buffer = 0;                    ///< SO_SNDBUF the kernel granted (bytes)

  /// Adds `o` field by field (buffers: the smallest nonzero).
  UdpCounters& operator+=(const UdpCounters& o);
};

/// Every count of UdpCounters (the buffers aside) with its name, in declaration order: the one list
/// that sums and reports them.
inline constexpr std::array<std::pair<std::string_view, std::uint64_t UdpCounters::*>, 12> udp_counter_fields{{
    {"datagrams_sent", &UdpCounters::datagrams_sent},
    {"datagram_bytes_sent", &UdpCounters::datagram_bytes_sent},
    {"datagrams_received", &UdpCounters::datagrams_received},
    {"datagram_bytes_received", &UdpCounters::datagram_bytes_received},
    {"local_deliveries", &UdpCounters::local_deliveries},
    {"induced_losses", &UdpCounters::induced_losses},
    {"malformed", &UdpCounters::malformed},
    {"unknown_destination", &UdpCounters::unknown_destination},
    {"not_a_neighbour", &UdpCounters::not_a_neighbour},
    {"stale_phase", &UdpCounters::stale_phase},
    {"send_retries", &UdpCounters::send_retries},
    {"kernel_drops", &UdpCounters::kernel_drops},
}};

/// Hosts the nodes of one process over a UDP socket bound to 127.0.0.1.
class UdpHost {
public:
  /// Builds the node for vertex `v`, given the runtime it must use (which outlives it).
  using NodeFactory = std::function<std::unique_ptr<protocols::Node>(protocols::Runtime&, core::Vertex)>;
  /// Maps a message's bytes to the phase its traffic is counted under.
  using PhaseOf = std::function<Phase(std::span<const std::byte>)>;

  /// A host on `io` (which must outlive it) for the vertices v of `g` with `process_of[v]` ==
  /// `self`; node ids are g's ids. Binds the socket. Throws core::InputError if the port is in use or
  /// `config` is out of range (loss outside [0, 1], max_datagram above max_udp_payload or not above
  /// the header), std::runtime_error for another socket failure, core::InternalError if
  /// `process_of` does not have one entry per vertex.
  UdpHost(boost::asio::io_context& io, const core::PlanarGraph& g, std::vector<std::size_t> process_of,
          std::size_t self, UdpHostConfig config, PhaseOf phase_of = {});
  UdpHost(const UdpHost&) = delete;
  UdpHost& operator=(const UdpHost&) = delete;
  ~UdpHost();

  /// The port the socket is bound to.
  std::uint16_t port() const;
  /// The port of every process (by process index); needed before any node sends to another process.
  void set_ports(std::vector<std::uint16_t> ports);
  /// Replaces the hosted nodes by those `factory` builds for `phase` (> the previous phase), calls
  /// on_start on each (in vertex order), delivers what they sent and the datagrams held for this
  /// phase. Precondition: idle() but for held datagrams.
  void start_phase(std::uint8_t phase, const NodeFactory& factory);
  /// Delivers the queued messages and what they cause (call after injecting work from outside a
  /// callback, e.g. ForwardingNode::originate; the host drains its queue itself after every event).
  void run_queue();
  /// Starts receiving on the socket (once).
  void start_receiving();
  /// Called after every batch of callbacks the io_context runs (to observe progress).
  void set_after_events(std::function<void()> hook);

  /// The vertices this process hosts, in increasing order.
  const std::vector<core::Vertex>& local_vertices() const { return local_; }
  /// The node of hosted vertex `v`.
  protocols::Node& node(core::Vertex v);
  /// Nothing to do until a datagram arrives: no queued message, no pending timer, no unsent datagram.
  bool idle() const;
  /// Counters (kernel_drops as of the last call of kernel_drops()).
  const UdpCounters& counters() const { return counters_; }
  /// Reads the socket's drop count from the kernel (SO_MEMINFO), stores and returns it.
  std::uint64_t kernel_drops();
  /// Traffic per node (global vertex index) and phase, counted when a node sends (before loss).
  const TrafficMetrics& traffic() const { return traffic_; }
  /// Sends `bytes` as they are to process `process`'s port (tests: malformed input).
  void send_raw(std::size_t process, std::span<const std::byte> bytes);

private:
  class NodeRuntime;
  class Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<core::Vertex> local_;
  UdpCounters counters_;
  TrafficMetrics traffic_;
};

}  // namespace laguerre::sim
