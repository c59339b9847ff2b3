// The live host: nodes over UDP on 127.0.0.1 with Boost.Asio (see UdpHost.hpp for the contract).
#include "laguerre/sim/UdpHost.hpp"

#include <linux/sock_diag.h>
#include <sys/socket.h>

#include <algorithm>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <optional>
#include <queue>
#include <stdexcept>
#include <unordered_set>

#include "laguerre/core/Error.hpp"

namespace laguerre::sim {

namespace asio = boost::asio;
using asio::ip::udp;

UdpCounters& UdpCounters::operator+=(const UdpCounters& o) {
  for (const auto& [name, count] : udp_counter_fields) this->*count += o.*count;
  const auto smallest = [](int a, int b) { return a == 0 ? b : b == 0 ? a : std::min(a, b); };
  receive_buffer = smallest(receive_buffer, o.receive_buffer);
  send_buffer = smallest(send_buffer, o.send_buffer);
  return *this;
}

namespace {
constexpr std::uint8_t magic = 0x4c;
constexpr std::uint8_t header_version = 1;

void put_le(std::byte* p, std::uint64_t x, int bytes) {
  for (int i = 0; i < bytes; ++i) p[i] = static_cast<std::byte>(x >> (8 * i));
}
std::uint64_t get_le(const std::byte* p, int bytes) {
  std::uint64_t x = 0;
  for (int i = 0; i < bytes; ++i) x |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  return x;
}

std::int64_t steady_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

struct Timer {
  protocols::Time due;
  protocols::TimerHandle handle;
  core::Vertex v;
  protocols::TimerId id;
  bool operator>(const Timer& o) const { return due != o.due ? due > o.due : handle > o.handle; }
};

struct Queued {
  core::Vertex to;
  protocols::NodeId from;
  std::vector<std::byte> bytes;
};

// One hosted vertex's static data: its neighbours sorted by id, with the loss stream of each link.
struct LocalNode {
  std::vector<protocols::NodeId> sorted;  // neighbour ids, increasing
  std::vector<core::Vertex> vertex;       // in `sorted` order
  std::vector<RandomStream> loss;         // in `sorted` order
  RandomStream stream;                    // the node's own stream
};
}  // namespace

/// The Runtime of one hosted vertex.
class UdpHost::NodeRuntime final : public protocols::Runtime {
public:
  NodeRuntime(UdpHost::Impl& host, core::Vertex v) : host_(host), v_(v) {}
  protocols::NodeId self() const override;
  protocols::Time now() const override;
  void send(protocols::NodeId to, std::span<const std::byte> bytes) override;
  void broadcast(std::span<const std::byte> bytes) override;
  protocols::TimerHandle schedule(protocols::Duration after, protocols::TimerId timer) override;
  bool cancel(protocols::TimerHandle handle) override;
  std::uint64_t random_u64() override;

private:
  UdpHost::Impl& host_;
  core::Vertex v_;
};

class UdpHost::Impl {
public:
  Impl(UdpHost& owner, asio::io_context& io, const core::PlanarGraph& g, std::vector<std::size_t> process_of,
       std::size_t self, UdpHostConfig config, PhaseOf phase_of)
      : owner_(owner), io_(io), g_(g), process_of_(std::move(process_of)), self_(self), config_(config),
        phase_of_(std::move(phase_of)), socket_(io), timer_(io) {
    LAGUERRE_PRECONDITION(process_of_.size() == g.num_vertices(),
                          "UdpHost needs one process index per vertex.");
    if (!(config_.loss >= 0 && config_.loss <= 1))
      throw core::InputError("--loss", 0, "a probability in [0, 1], found " + std::to_string(config_.loss));
    if (config_.max_datagram > max_udp_payload || config_.max_datagram <= udp_header_size + udp_record_header)
      throw core::InputError("live host", 0,
                             "a datagram size in (" + std::to_string(udp_header_size + udp_record_header) + ", " +
                                 std::to_string(max_udp_payload) + "], found " + std::to_string(config_.max_datagram));
    const std::size_t n = g.num_vertices();
    by_id_.reserve(n);
    for (core::Vertex v = 0; v < n; ++v) by_id_.emplace_back(g.id(v), v);
    std::sort(by_id_.begin(), by_id_.end());
    slot_.assign(n, -1);
    for (core::Vertex v = 0; v < n; ++v)
      if (process_of_[v] == self_) {
        slot_[v] = static_cast<std::int64_t>(owner_.local_.size());
        owner_.local_.push_back(v);
        LocalNode ln;
        std::vector<std::pair<protocols::NodeId, core::Vertex>> nb;
        for (const core::Vertex w : g.neighbours(v)) nb.emplace_back(g.id(w), w);
        std::sort(nb.begin(), nb.end());
        for (const auto& [id, w] : nb) {
          ln.sorted.push_back(id);
          ln.vertex.push_back(w);
          ln.loss.push_back(RandomStream::of(config_.seed, StreamKind::link, g.id(v), id));
        }
        ln.stream = RandomStream::of(config_.seed, StreamKind::node, g.id(v));
        locals_.push_back(std::move(ln));
      }
    open_socket();
  }

  void open_socket() {
    boost::system::error_code ec;
    socket_.open(udp::v4(), ec);
    if (ec) throw std::runtime_error("cannot open a UDP socket: " + ec.message());
    const int fd = socket_.native_handle();
    // SO_RCVBUFFORCE passes net.core.rmem_max when the process may (CAP_NET_ADMIN); else SO_RCVBUF,
    // which the kernel caps there. The kernel reports twice the size it books.
    const int want = config_.socket_buffer;
    if (setsockopt(fd, SOL_SOCKET, SO_RCVBUFFORCE, &want, sizeof want) != 0)
      setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &want, sizeof want);
    if (setsockopt(fd, SOL_SOCKET, SO_SNDBUFFORCE, &want, sizeof want) != 0)
      setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &want, sizeof want);
    socklen_t len = sizeof(int);
    getsockopt(fd, SOL_SOCKET, SO_RCVBUF, &owner_.counters_.receive_buffer, &len);
    len = sizeof(int);
    getsockopt(fd, SOL_SOCKET, SO_SNDBUF, &owner_.counters_.send_buffer, &len);
    socket_.bind(udp::endpoint(asio::ip::address_v4::loopback(), config_.port), ec);
    if (ec == asio::error::address_in_use)
      throw core::InputError("--base-port", 0,
                             "127.0.0.1:" + std::to_string(config_.port) +
                                 " is in use; choose another base port (0: ports the kernel picks)");
    if (ec) throw std::runtime_error("cannot bind UDP 127.0.0.1:" + std::to_string(config_.port) + ": " + ec.message());
    socket_.non_blocking(true);
  }

  std::uint16_t port() const { return socket_.local_endpoint().port(); }

  void set_ports(std::vector<std::uint16_t> ports) {
    peers_.clear();
    for (const std::uint16_t p : ports) peers_.emplace_back(asio::ip::address_v4::loopback(), p);
    batches_.assign(peers_.size(), {});
  }

  void start_phase(std::uint8_t phase, const NodeFactory& factory) {
    LAGUERRE_PRECONDITION(queue_.empty() && live_timers_.empty() && outgoing_.empty(),
                          "UdpHost::start_phase needs an idle host.");
    LAGUERRE_PRECONDITION(phase > phase_ || !started_, "UdpHost phases must increase.");
    nodes_.clear();
    runtimes_.clear();
    started_ = true;
    phase_ = phase;
    for (const core::Vertex v : owner_.local_) {
      runtimes_.push_back(std::make_unique<NodeRuntime>(*this, v));
      nodes_.push_back(factory(*runtimes_.back(), v));
      LAGUERRE_PRECONDITION(nodes_.back() != nullptr, "The node factory returned no node.");
    }
    for (auto& node : nodes_) node->on_start();
    std::vector<std::vector<std::byte>> held;
    held.swap(held_);
    for (auto& d : held) accept(d);
    drain();
  }

  void start_receiving() {
    socket_.async_wait(udp::socket::wait_read, [this](const boost::system::error_code& ec) {
      if (ec) return;
      receive_all();
      start_receiving();
    });
  }

  bool idle() const {
    return queue_.empty() && live_timers_.empty() && outgoing_.empty() && held_.empty() && dirty_.empty();
  }

  std::uint64_t kernel_drops() {
    std::uint32_t info[SK_MEMINFO_VARS] = {};
    socklen_t len = sizeof info;
    if (getsockopt(socket_.native_handle(), SOL_SOCKET, SO_MEMINFO, info, &len) == 0 &&
        len >= sizeof(std::uint32_t) * (SK_MEMINFO_DROPS + 1))
      owner_.counters_.kernel_drops = info[SK_MEMINFO_DROPS];
    return owner_.counters_.kernel_drops;
  }

  void send_raw(std::size_t process, std::span<const std::byte> bytes) {
    LAGUERRE_PRECONDITION(process < peers_.size(), "UdpHost::send_raw: no such process.");
    socket_.send_to(asio::buffer(bytes.data(), bytes.size()), peers_[process]);
  }

  // --- the runtime side ---
  protocols::NodeId id(core::Vertex v) const { return g_.id(v); }
  protocols::Time now() const { return steady_ns() - config_.epoch; }

  void send(core::Vertex v, protocols::NodeId to, std::span<const std::byte> bytes) {
    LocalNode& ln = locals_[static_cast<std::size_t>(slot_[v])];
    const auto it = std::lower_bound(ln.sorted.begin(), ln.sorted.end(), to);
    LAGUERRE_PRECONDITION(it != ln.sorted.end() && *it == to, "Node " + std::to_string(g_.id(v)) +
                                                                   " cannot send to node " + std::to_string(to) +
                                                                   ": not a neighbour.");
    const auto k = static_cast<std::size_t>(it - ln.sorted.begin());
    put(v, ln.vertex[k], to, ln.loss[k], bytes);
  }

  void broadcast(core::Vertex v, std::span<const std::byte> bytes) {
    LocalNode& ln = locals_[static_cast<std::size_t>(slot_[v])];
    for (std::size_t k = 0; k < ln.sorted.size(); ++k) put(v, ln.vertex[k], ln.sorted[k], ln.loss[k], bytes);
  }

  protocols::TimerHandle schedule(core::Vertex v, protocols::Duration after, protocols::TimerId timer) {
    LAGUERRE_PRECONDITION(after >= 0, "A timer needs a delay >= 0.");
    const protocols::TimerHandle h = next_handle_++;
    timers_.push({now() + after, h, v, timer});
    live_timers_.insert(h);
    arm_timer();
    return h;
  }

  bool cancel(protocols::TimerHandle handle) { return live_timers_.erase(handle) > 0; }

  std::uint64_t random_u64(core::Vertex v) { return locals_[static_cast<std::size_t>(slot_[v])].stream.next_u64(); }

  void set_after_events(std::function<void()> hook) { after_events_ = std::move(hook); }

  protocols::Node& node_at(std::size_t i) { return *nodes_[i]; }

private:
  Phase phase_of(std::span<const std::byte> bytes) const { return phase_of_ ? phase_of_(bytes) : Phase{0}; }

  // One message from hosted vertex v to neighbour w (id `to`).
  void put(core::Vertex v, core::Vertex w, protocols::NodeId to, RandomStream& loss, std::span<const std::byte> bytes) {
    const Phase phase = phase_of(bytes);
    owner_.traffic_.add_sent(static_cast<std::uint32_t>(v), phase, bytes.size());
    if (udp_header_size + udp_record_header + bytes.size() > config_.max_datagram)
      throw core::InputError("node " + std::to_string(g_.id(v)), 0,
                             "messages that fit a datagram of " + std::to_string(config_.max_datagram) +
                                 " bytes, but one has " + std::to_string(bytes.size()) +
                                 " bytes (+" + std::to_string(udp_header_size + udp_record_header) +
                                 " of headers): the graph is too large for a UDP datagram (degree " +
                                 std::to_string(g_.degree(v)) + ")");
    if (config_.loss > 0 && loss.bernoulli(config_.loss)) {
      ++owner_.counters_.induced_losses;
      owner_.traffic_.add_lost(static_cast<std::uint32_t>(v), phase, bytes.size());
      return;
    }
    if (slot_[w] >= 0) {
      ++owner_.counters_.local_deliveries;
      queue_.push_back({w, g_.id(v), std::vector<std::byte>(bytes.begin(), bytes.end())});
      return;
    }
    // Into the batch for w's process, flushed when full and after the current callback.
    const std::size_t process = process_of_[w];
    LAGUERRE_PRECONDITION(process < peers_.size(), "UdpHost: the ports of the other processes are not set.");
    std::vector<std::byte>& b = batches_[process];
    if (!b.empty() && b.size() + udp_record_header + bytes.size() > config_.max_datagram) flush(process);
    if (b.empty()) {
      b.resize(udp_header_size);
      b[0] = std::byte{magic};
      b[1] = std::byte{header_version};
      b[2] = std::byte{phase_};
      b[3] = std::byte{0};
      put_le(&b[4], config_.run_tag, 4);
      dirty_.push_back(process);
    }
    const std::size_t at = b.size();
    b.resize(at + udp_record_header + bytes.size());
    put_le(&b[at], to, 8);
    put_le(&b[at + 8], g_.id(v), 8);
    put_le(&b[at + 16], bytes.size(), 4);
    std::memcpy(b.data() + at + udp_record_header, bytes.data(), bytes.size());
  }

  // Sends process's batch as one datagram (or queues it while the kernel has no room).
  void flush(std::size_t process) {
    std::vector<std::byte> d;
    d.swap(batches_[process]);
    if (d.empty()) return;
    if (outgoing_.empty() && try_send(process, d)) return;
    outgoing_.push_back({process, std::move(d)});
    if (outgoing_.size() == 1) wait_writable();
  }

  void flush_all() {
    for (const std::size_t p : dirty_) flush(p);
    dirty_.clear();
  }

  bool try_send(std::size_t process, const std::vector<std::byte>& d) {
    boost::system::error_code ec;
    socket_.send_to(asio::buffer(d), peers_[process], 0, ec);
    if (ec == asio::error::would_block || ec == asio::error::no_buffer_space) {
      ++owner_.counters_.send_retries;
      return false;
    }
    if (ec) throw std::runtime_error("UDP send to 127.0.0.1:" + std::to_string(peers_[process].port()) + " failed: " + ec.message());
    ++owner_.counters_.datagrams_sent;
    owner_.counters_.datagram_bytes_sent += d.size();
    return true;
  }

  void wait_writable() {
    socket_.async_wait(udp::socket::wait_write, [this](const boost::system::error_code& ec) {
      if (ec) return;
      while (!outgoing_.empty() && try_send(outgoing_.front().first, outgoing_.front().second)) outgoing_.pop_front();
      if (!outgoing_.empty()) {
        // ENOBUFS does not make the socket unwritable: back off a little instead of spinning.
        retry_timer_.emplace(io_, std::chrono::microseconds(200));
        retry_timer_->async_wait([this](const boost::system::error_code& e) {
          if (!e) wait_writable();
        });
      }
      after_batch();
    });
  }

  void receive_all() {
    for (int batch = 0; batch < 256; ++batch) {
      boost::system::error_code ec;
      udp::endpoint from;
      const std::size_t got = socket_.receive_from(asio::buffer(buffer_), from, 0, ec);
      if (ec == asio::error::would_block) break;
      if (ec) {
        if (ec == asio::error::connection_refused) continue;  // an ICMP error of an earlier send
        throw std::runtime_error("UDP receive failed: " + ec.message());
      }
      std::vector<std::byte> d(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(got));
      if (got < udp_header_size || d[0] != std::byte{magic} || d[1] != std::byte{header_version} || d[3] != std::byte{0} ||
          get_le(&d[4], 4) != config_.run_tag) {
        ++owner_.counters_.malformed;
        continue;
      }
      ++owner_.counters_.datagrams_received;
      owner_.counters_.datagram_bytes_received += got;
      const auto phase = static_cast<std::uint8_t>(d[2]);
      if (started_ && phase < phase_) {
        ++owner_.counters_.stale_phase;
        continue;
      }
      if (!started_ || phase > phase_) {
        held_.push_back(std::move(d));
        continue;
      }
      accept(d);
    }
    drain();
  }

  // A datagram of the current phase: its records checked, then queued for their nodes.
  void accept(const std::vector<std::byte>& d) {
    std::size_t at = udp_header_size;
    while (at < d.size()) {
      if (d.size() - at < udp_record_header || d.size() - at - udp_record_header < get_le(&d[at + 16], 4)) {
        ++owner_.counters_.malformed;  // a truncated record: the rest of the datagram is not trusted
        return;
      }
      const protocols::NodeId dst = get_le(&d[at], 8), src = get_le(&d[at + 8], 8);
      const std::size_t begin = at + udp_record_header, end = begin + get_le(&d[at + 16], 4);
      at = end;
      const auto it = std::lower_bound(by_id_.begin(), by_id_.end(), std::make_pair(dst, core::Vertex{0}));
      if (it == by_id_.end() || it->first != dst || slot_[it->second] < 0) {
        ++owner_.counters_.unknown_destination;
        continue;
      }
      const LocalNode& ln = locals_[static_cast<std::size_t>(slot_[it->second])];
      if (!std::binary_search(ln.sorted.begin(), ln.sorted.end(), src)) {
        ++owner_.counters_.not_a_neighbour;
        continue;
      }
      queue_.push_back({it->second, src,
                        std::vector<std::byte>(d.begin() + static_cast<std::ptrdiff_t>(begin),
                                               d.begin() + static_cast<std::ptrdiff_t>(end))});
    }
  }

public:
  // Delivers queued messages (and what they cause) until none is left; never inside a callback.
  void drain() {
    while (!queue_.empty()) {
      Queued q = std::move(queue_.front());
      queue_.pop_front();
      nodes_[static_cast<std::size_t>(slot_[q.to])]->on_message(q.from, q.bytes);
    }
    flush_all();
    after_batch();
  }

private:
  void after_batch() {
    if (after_events_) after_events_();
  }

  void arm_timer() {
    while (!timers_.empty() && !live_timers_.count(timers_.top().handle)) timers_.pop();
    if (timers_.empty()) return;
    const protocols::Time due = timers_.top().due;
    if (armed_ && armed_due_ <= due) return;
    armed_ = true;
    armed_due_ = due;
    timer_.expires_at(std::chrono::steady_clock::time_point(std::chrono::nanoseconds(due + config_.epoch)));
    timer_.async_wait([this](const boost::system::error_code& ec) {
      if (ec == asio::error::operation_aborted) return;
      armed_ = false;
      fire_timers();
    });
  }

  void fire_timers() {
    const protocols::Time t = now();
    while (!timers_.empty() && timers_.top().due <= t) {
      const Timer top = timers_.top();
      timers_.pop();
      if (live_timers_.erase(top.handle) == 0) continue;
      nodes_[static_cast<std::size_t>(slot_[top.v])]->on_timer(top.id);
      drain();
    }
    arm_timer();
    after_batch();
  }

  UdpHost& owner_;
  asio::io_context& io_;
  const core::PlanarGraph& g_;
  std::vector<std::size_t> process_of_;
  std::size_t self_;
  UdpHostConfig config_;
  PhaseOf phase_of_;
  udp::socket socket_;
  asio::steady_timer timer_;
  std::optional<asio::steady_timer> retry_timer_;
  bool armed_ = false;
  protocols::Time armed_due_ = 0;
  std::vector<std::pair<protocols::NodeId, core::Vertex>> by_id_;
  std::vector<std::int64_t> slot_;  // vertex → index in locals_/nodes_, or -1
  std::vector<LocalNode> locals_;
  std::vector<udp::endpoint> peers_;
  std::vector<std::unique_ptr<NodeRuntime>> runtimes_;
  std::vector<std::unique_ptr<protocols::Node>> nodes_;
  std::deque<Queued> queue_;
  std::priority_queue<Timer, std::vector<Timer>, std::greater<>> timers_;
  std::unordered_set<protocols::TimerHandle> live_timers_;
  protocols::TimerHandle next_handle_ = 1;
  std::deque<std::pair<std::size_t, std::vector<std::byte>>> outgoing_;
  std::vector<std::vector<std::byte>> batches_;  // per process: the datagram being filled
  std::vector<std::size_t> dirty_;               // processes whose batch is not empty
  std::vector<std::vector<std::byte>> held_;
  std::vector<std::byte> buffer_ = std::vector<std::byte>(65536);
  std::uint8_t phase_ = 0;
  bool started_ = false;
  std::function<void()> after_events_;

public:
  ~Impl() {
    nodes_.clear();  // nodes go first: they hold references to their runtimes
  }
};

protocols::NodeId UdpHost::NodeRuntime::self() const { return host_.id(v_); }
protocols::Time UdpHost::NodeRuntime::now() const { return host_.now(); }
void UdpHost::NodeRuntime::send(protocols::NodeId to, std::span<const std::byte> bytes) { host_.send(v_, to, bytes); }
void UdpHost::NodeRuntime::broadcast(std::span<const std::byte> bytes) { host_.broadcast(v_, bytes); }
protocols::TimerHandle UdpHost::NodeRuntime::schedule(protocols::Duration after, protocols::TimerId timer) {
  return host_.schedule(v_, after, timer);
}
bool UdpHost::NodeRuntime::cancel(protocols::TimerHandle handle) { return host_.cancel(handle); }
std::uint64_t UdpHost::NodeRuntime::random_u64() { return host_.random_u64(v_); }

UdpHost::UdpHost(asio::io_context& io, const core::PlanarGraph& g, std::vector<std::size_t> process_of,
                 std::size_t self, UdpHostConfig config, PhaseOf phase_of)
    : traffic_(g.num_vertices()) {
  impl_ = std::make_unique<Impl>(*this, io, g, std::move(process_of), self, config, std::move(phase_of));
}

UdpHost::~UdpHost() = default;

std::uint16_t UdpHost::port() const { return impl_->port(); }
void UdpHost::set_ports(std::vector<std::uint16_t> ports) { impl_->set_ports(std::move(ports)); }
void UdpHost::start_phase(std::uint8_t phase, const NodeFactory& factory) { impl_->start_phase(phase, factory); }
void UdpHost::start_receiving() { impl_->start_receiving(); }
void UdpHost::run_queue() { impl_->drain(); }
void UdpHost::set_after_events(std::function<void()> hook) { impl_->set_after_events(std::move(hook)); }
bool UdpHost::idle() const { return impl_->idle(); }
std::uint64_t UdpHost::kernel_drops() { return impl_->kernel_drops(); }
void UdpHost::send_raw(std::size_t process, std::span<const std::byte> bytes) { impl_->send_raw(process, bytes); }

protocols::Node& UdpHost::node(core::Vertex v) {
  const auto& l = local_;
  const auto it = std::lower_bound(l.begin(), l.end(), v);
  LAGUERRE_PRECONDITION(it != l.end() && *it == v, "UdpHost::node: vertex " + std::to_string(v) + " is not hosted here.");
  return impl_->node_at(static_cast<std::size_t>(it - l.begin()));
}

}  // namespace laguerre::sim
