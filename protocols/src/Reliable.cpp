// The reliability layer (docs/protocol.md, "Loss, duplication and crashes"). Per link: sequence
// numbers, a selective acknowledgement (first missing number + a 64-bit window) carried by every frame
// or sent alone after ack_delay, retransmission of everything unacknowledged with exponential backoff
// and a Jacobson/Karels timeout (Karn's rule), probes of silent neighbours, and after
// max_retransmissions without progress a flooded failure notice.
//
// Call order matters for bit-for-bit reproduction: within one callback the layer sends and schedules
// exactly in the order of the inner node's calls, and flushes owed acks only after the inner node's
// callback returned (a frame leaving in the meantime carries the ack).
#include "laguerre/protocols/Reliable.hpp"
#include "laguerre/core/Error.hpp"

#include <algorithm>
#include <deque>
#include <stdexcept>
#include <string>

#include "Neighbours.hpp"

namespace laguerre::protocols {

namespace detail {

std::vector<std::pair<NodeId, std::uint32_t>> sorted_neighbours(NodeId self, const std::vector<NodeId>& neighbours) {
  const std::string who = "Node " + std::to_string(self);
  if (neighbours.empty()) throw core::InternalError(who + " has no neighbours.");
  if (neighbours.size() >= 0xffffffffu) throw core::InternalError(who + " has too many neighbours.");
  std::vector<std::pair<NodeId, std::uint32_t>> sorted;
  for (std::size_t i = 0; i < neighbours.size(); ++i) {
    if (neighbours[i] == self) throw core::InternalError(who + " lists itself as a neighbour.");
    sorted.emplace_back(neighbours[i], static_cast<std::uint32_t>(i));
  }
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 1; i < sorted.size(); ++i)
    if (sorted[i].first == sorted[i - 1].first)
      throw core::InternalError(who + " lists neighbour " + std::to_string(sorted[i].first) + " twice.");
  return sorted;
}

std::size_t neighbour_index(const std::vector<std::pair<NodeId, std::uint32_t>>& sorted, NodeId id) {
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), std::make_pair(id, std::uint32_t{0}));
  return it != sorted.end() && it->first == id ? it->second : sorted.size();
}

}  // namespace detail

void validate(const ReliableParams& params) {
  if (params.retransmit_after < 0 || params.ack_delay < 0 || params.probe_after < 0)
    throw core::InternalError("retransmit_after, ack_delay and probe_after must not be negative.");
  if (params.backoff_cap < 1 || params.max_retransmissions < 1)
    throw core::InternalError("backoff_cap and max_retransmissions must be at least 1.");
  if (params.rto_min < 0) throw core::InternalError("rto_min must not be negative.");
}

ReliableCounters& ReliableCounters::operator+=(const ReliableCounters& o) {
  sent += o.sent;
  bytes_sent += o.bytes_sent;
  received += o.received;
  for (std::size_t i = 0; i < decode.size(); ++i) decode[i] += o.decode[i];
  not_a_neighbour += o.not_a_neighbour;
  unexpected += o.unexpected;
  bad_payload += o.bad_payload;
  frames += o.frames;
  retransmissions += o.retransmissions;
  acks += o.acks;
  duplicates += o.duplicates;
  out_of_window += o.out_of_window;
  probes += o.probes;
  links_failed += o.links_failed;
  return *this;
}

ReliableParams lossy_link_params(Duration max_latency) {
  const Duration l = std::max<Duration>(max_latency, 1);
  ReliableParams p;
  p.ack_delay = l / 2;
  p.retransmit_after = 3 * l;
  return p;
}

struct ReliableNode::Link {
  struct Pending {  // a frame not yet acknowledged
    std::uint32_t seq = 0;
    std::vector<std::byte> payload;
    Time sent_at = 0;            // first transmission
    bool retransmitted = false;  // Karn: no RTT sample from it
  };
  std::uint32_t next_seq = 0;  // next sequence number to send
  std::deque<Pending> unacked;  // by seq
  TimerHandle retransmit_timer = 0;
  Duration period = 0;  // current retransmission period
  Duration rto = 0;     // current timeout (backoff resets to it)
  Duration srtt = 0;    // smoothed round trip (ns)
  Duration rttvar = 0;  // its mean deviation (ns)
  bool has_rtt = false;  // a sample was taken
  int attempts = 0;      // retransmissions since progress
  AckInfo received;      // what we have of the reverse link
  bool ack_pending = false;
  TimerHandle ack_timer = 0;
  Time last_heard = 0;
  bool dead = false;
};

namespace {
// Timer ids: kind in the top byte, neighbour index below; kind 0 is the inner node's.
constexpr TimerId timer_retransmit = TimerId{1} << 56;
constexpr TimerId timer_ack = TimerId{2} << 56;
constexpr TimerId timer_probe = TimerId{3} << 56;
constexpr TimerId timer_kind = TimerId{0xff} << 56;

/// Serial-number order of 32-bit sequence numbers (RFC 1982): a is before b iff b − a, taken mod 2^32,
/// lies in [1, 2^31).
bool seq_before(std::uint32_t a, std::uint32_t b) { return a != b && static_cast<std::uint32_t>(b - a) < (1u << 31); }
}  // namespace

ReliableNode::ReliableNode(Runtime& runtime, std::vector<NodeId> neighbours, ReliableParams params,
                           const InnerFactory& make_inner)
    : rt_(runtime), params_(params), neighbours_(std::move(neighbours)) {
  sorted_ids_ = detail::sorted_neighbours(rt_.self(), neighbours_);
  validate(params);
  if (params.retransmit_after == 0) throw core::InternalError("retransmit_after must be positive.");
  if (params_.probe_after == 0) params_.probe_after = 32 * params_.retransmit_after;
  if (params_.rto_min == 0) params_.rto_min = std::max<Duration>(1, params_.retransmit_after / 4);
  links_.assign(neighbours_.size(), Link{});
  for (Link& l : links_) {
    l.period = l.rto = params_.retransmit_after;
    l.next_seq = params_.initial_seq;
    l.received.next = params_.initial_seq;
  }
  inner_ = make_inner(*this);
  if (!inner_) throw core::InternalError("ReliableNode: the factory returned no inner node.");
}

ReliableNode::~ReliableNode() = default;

std::size_t ReliableNode::index_of(NodeId id) const { return detail::neighbour_index(sorted_ids_, id); }

Duration ReliableNode::rto(std::size_t i) const { return links_.at(i).rto; }

// ---- The runtime served to the inner node -----------------------------------------------------------

void ReliableNode::send(NodeId to, std::span<const std::byte> bytes) {
  const std::size_t i = index_of(to);
  if (i == neighbours_.size())
    throw core::InternalError("Node " + std::to_string(self()) + " sent to non-neighbour " + std::to_string(to) + ".");
  send_frame(i, bytes);
}

void ReliableNode::broadcast(std::span<const std::byte> bytes) {
  for (std::size_t i = 0; i < neighbours_.size(); ++i) send_frame(i, bytes);
}

TimerHandle ReliableNode::schedule(Duration after, TimerId timer) {
  if ((timer & timer_kind) != 0) throw core::InternalError("ReliableNode: inner timer ids must stay below 2^56.");
  return rt_.schedule(after, timer);
}

// ---- Callbacks from the host -------------------------------------------------------------------------

void ReliableNode::on_start() {
  inner_->on_start();
  if (params_.probes) probe_timer_ = rt_.schedule(params_.probe_after, timer_probe);
}

void ReliableNode::on_message(NodeId from, std::span<const std::byte> bytes) {
  ++counters_.received;
  const std::size_t i = index_of(from);
  if (i == neighbours_.size()) {
    ++counters_.not_a_neighbour;
    return;
  }
  LinkMessage m;  // everything travels in frames
  const DecodeStatus s = decode(bytes, m);
  ++counters_.decode[static_cast<std::size_t>(s)];
  if (s != DecodeStatus::ok) return;
  links_[i].last_heard = rt_.now();
  if (auto* f = std::get_if<FrameMsg>(&m)) handle_frame(i, *f);
  else handle_ack(i, std::get<AckMsg>(m).ack);
  flush_acks();
}

void ReliableNode::on_timer(TimerId timer) {
  const TimerId kind = timer & timer_kind;
  if (kind == 0) {
    inner_->on_timer(timer);
    return;
  }
  const std::size_t i = static_cast<std::size_t>(timer & ~timer_kind);
  if (kind != timer_probe && i >= links_.size()) {
    ++counters_.unexpected;
    return;
  }
  if (kind == timer_retransmit) {
    links_[i].retransmit_timer = 0;
    on_retransmit(i);
  } else if (kind == timer_ack) {
    links_[i].ack_timer = 0;
    if (links_[i].ack_pending && !links_[i].dead) send_ack(i);
  } else if (kind == timer_probe) {
    probe_timer_ = 0;
    on_probe();
  } else {
    ++counters_.unexpected;
  }
}

void ReliableNode::on_recover() {
  // Timers that fell in the outage are gone; those due later are still live. Cancel-then-schedule
  // is right in both cases (cancelling a dead handle is a no-op).
  for (std::size_t i = 0; i < links_.size(); ++i) {
    Link& l = links_[i];
    if (l.dead) continue;
    if (!l.unacked.empty()) arm_retransmit(i);
    if (l.ack_timer != 0) rt_.cancel(l.ack_timer);
    l.ack_timer = 0;
    if (l.ack_pending) ack_owed_.push_back(i);
  }
  if (probe_timer_ != 0) rt_.cancel(probe_timer_);
  probe_timer_ = params_.probes && !is_final() ? rt_.schedule(params_.probe_after, timer_probe) : 0;
  flush_acks();
  inner_->on_recover();
}

// ---- Frames and acknowledgements ---------------------------------------------------------------------

void ReliableNode::raw_send(std::size_t i, std::span<const std::byte> bytes) {
  rt_.send(neighbours_[i], bytes);
  ++counters_.sent;
  counters_.bytes_sent += bytes.size();
}

void ReliableNode::send_ack(std::size_t i) {
  links_[i].ack_pending = false;
  encode(AckMsg{links_[i].received}, buffer_);
  raw_send(i, buffer_);
  ++counters_.acks;
}

void ReliableNode::send_frame(std::size_t i, std::span<const std::byte> payload) {
  Link& l = links_[i];
  if (l.dead) return;  // its neighbour is suspected: the run is ending anyway
  const std::uint32_t seq = l.next_seq++;
  l.unacked.push_back({seq, std::vector<std::byte>(payload.begin(), payload.end()), rt_.now(), false});
  ++counters_.frames;
  put_frame(i, seq, payload);
  if (l.retransmit_timer == 0) arm_retransmit(i);
}

void ReliableNode::put_frame(std::size_t i, std::uint32_t seq, std::span<const std::byte> payload) {
  Link& l = links_[i];
  // The frame carries our acknowledgement of the reverse link: no standalone ack is owed any more.
  FrameMsg f{seq, l.received, {payload.begin(), payload.end()}};
  encode(f, buffer_);
  raw_send(i, buffer_);
  l.ack_pending = false;
  if (l.ack_timer != 0) {
    rt_.cancel(l.ack_timer);
    l.ack_timer = 0;
  }
}

void ReliableNode::arm_retransmit(std::size_t i) {
  Link& l = links_[i];
  if (l.retransmit_timer != 0) rt_.cancel(l.retransmit_timer);
  l.retransmit_timer = rt_.schedule(l.period, timer_retransmit | i);
}

void ReliableNode::on_retransmit(std::size_t i) {
  Link& l = links_[i];
  if (l.dead || l.unacked.empty()) return;
  if (l.attempts >= params_.max_retransmissions) {
    give_up(i);
    return;
  }
  ++l.attempts;
  for (Link::Pending& p : l.unacked) {
    put_frame(i, p.seq, p.payload);
    p.retransmitted = true;
    ++counters_.retransmissions;
  }
  l.period = std::min(2 * l.period, params_.backoff_cap * params_.retransmit_after);
  arm_retransmit(i);
}

void ReliableNode::handle_ack(std::size_t i, const AckInfo& a) {
  // Drop every frame the neighbour proves it has: below a.next, or flagged in the bitmap above it.
  Link& l = links_[i];
  const std::size_t before = l.unacked.size();
  bool timed = false;  // Karn: the newest newly acknowledged frame sent only once gives the sample
  Time timed_at = 0;
  std::erase_if(l.unacked, [&](const Link::Pending& e) {
    const std::uint32_t k = e.seq - a.next;  // mod 2^32
    const bool acked = seq_before(e.seq, a.next) || (k >= 1 && k <= 64 && ((a.bits >> (k - 1)) & 1u) != 0);
    if (acked && !e.retransmitted && (!timed || e.sent_at > timed_at)) {
      timed = true;
      timed_at = e.sent_at;
    }
    return acked;
  });
  if (l.unacked.size() == before) return;
  if (timed && params_.adaptive_rto) sample_rtt(l, rt_.now() - timed_at);
  // Progress: the link is alive; start the backoff again (or stop the timer if nothing is left).
  l.attempts = 0;
  l.period = l.rto;
  if (l.unacked.empty()) {
    if (l.retransmit_timer != 0) rt_.cancel(l.retransmit_timer);
    l.retransmit_timer = 0;
  } else {
    arm_retransmit(i);
  }
}

void ReliableNode::sample_rtt(Link& l, Duration r) {
  // Jacobson/Karels in integer nanoseconds (docs/protocol.md, "Adaptive timeout").
  r = std::max<Duration>(r, 0);
  if (!l.has_rtt) {
    l.srtt = r;
    l.rttvar = r / 2;
    l.has_rtt = true;
  } else {
    const Duration err = l.srtt > r ? l.srtt - r : r - l.srtt;
    l.rttvar = (3 * l.rttvar + err) / 4;
    l.srtt = (7 * l.srtt + r) / 8;
  }
  l.rto = std::clamp<Duration>(l.srtt + 4 * l.rttvar, params_.rto_min,
                               std::max<Duration>(params_.rto_min, params_.backoff_cap * params_.retransmit_after));
}

void ReliableNode::handle_frame(std::size_t i, FrameMsg& f) {
  Link& l = links_[i];
  handle_ack(i, f.ack);
  // Every copy re-arms our ack: if the copy is a retransmission, our earlier ack was lost.
  if (!l.ack_pending) {
    l.ack_pending = true;
    ack_owed_.push_back(i);
  }
  AckInfo& r = l.received;
  bool fresh = false;
  if (f.seq == r.next) {
    // Advance past every sequence number already held (bit k ↔ r.next + 1 + k).
    fresh = true;
    for (;;) {
      ++r.next;
      const bool have = (r.bits & 1u) != 0;
      r.bits >>= 1;
      if (!have) break;
    }
  } else if (seq_before(r.next, f.seq)) {
    const std::uint32_t k = f.seq - r.next - 1;  // mod 2^32
    if (k >= 64) {
      ++counters_.out_of_window;
      return;
    }
    fresh = ((r.bits >> k) & 1u) == 0;
    r.bits |= std::uint64_t{1} << k;
  }
  if (!fresh) {
    ++counters_.duplicates;
    return;
  }
  deliver(i, f.payload);
}

void ReliableNode::deliver(std::size_t i, std::span<const std::byte> payload) {
  if (payload.empty()) return;  // a probe: its only purpose was the ack
  if (payload.size() >= 2 && payload[1] == static_cast<std::byte>(MessageType::failure)) {
    Message m;
    if (decode(payload, m) != DecodeStatus::ok) {
      ++counters_.bad_payload;
      return;
    }
    declare_failure(std::get<FailureMsg>(m).suspect, i);
    return;
  }
  if (failed_) return;  // the run is abandoned: the inner node gets nothing more
  inner_->on_message(neighbours_[i], payload);
}

void ReliableNode::flush_acks() {
  // After a callback: acks still owed (no frame to that neighbour carried them) go alone, at once or
  // after ack_delay in case a frame leaves first.
  for (std::size_t i : ack_owed_) {
    Link& l = links_[i];
    if (!l.ack_pending || l.dead) continue;
    if (params_.ack_delay == 0) send_ack(i);
    else if (l.ack_timer == 0) l.ack_timer = rt_.schedule(params_.ack_delay, timer_ack | i);
  }
  ack_owed_.clear();
}

// ---- Crash detection ---------------------------------------------------------------------------------

void ReliableNode::on_probe() {
  if (is_final()) return;  // a finished node no longer probes: the queue may drain
  const Time now = rt_.now();
  for (std::size_t i = 0; i < links_.size(); ++i) {
    Link& l = links_[i];
    if (l.dead || !l.unacked.empty() || now - l.last_heard < params_.probe_after) continue;
    ++counters_.probes;
    send_frame(i, {});
  }
  probe_timer_ = rt_.schedule(params_.probe_after, timer_probe);
}

void ReliableNode::give_up(std::size_t i) {
  Link& l = links_[i];
  l.dead = true;
  l.unacked.clear();
  l.ack_pending = false;
  if (l.ack_timer != 0) rt_.cancel(l.ack_timer);
  l.ack_timer = 0;
  ++counters_.links_failed;
  declare_failure(neighbours_[i], links_.size());
}

void ReliableNode::declare_failure(NodeId suspect, std::size_t except) {
  if (failed_) return;  // the notice already went out from here: the flood stops
  failed_ = true;
  suspect_ = suspect;
  if (probe_timer_ != 0) rt_.cancel(probe_timer_);
  probe_timer_ = 0;
  const std::vector<std::byte> notice = encode(FailureMsg{suspect});
  for (std::size_t j = 0; j < links_.size(); ++j)
    if (j != except) send_frame(j, notice);
  inner_->on_failure(suspect);
}

}  // namespace laguerre::protocols
