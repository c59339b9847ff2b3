// The hyperbolic baseline's set-up, one node's share (HyperbolicSetup.hpp; docs/hyperbolic-baseline.md).
#include "laguerre/protocols/HyperbolicSetup.hpp"

#include <algorithm>
#include <utility>

#include "laguerre/core/routing/HyperbolicEmbedding.hpp"
#include "Neighbours.hpp"

namespace laguerre::protocols {

namespace {
constexpr std::uint8_t tree_sweep = 2;  // sweeps 0 and 1 choose the root, sweep 2 builds the tree
constexpr std::uint8_t heard_bit = 1, echo_bit = 2;  // per neighbour and sweep: its flood message, its echo
}  // namespace

HyperbolicSetupNode::HyperbolicSetupNode(Runtime& runtime, NodeId id, std::vector<NodeId> neighbours,
                                         HyperbolicSetupParams params)
    : rt_(runtime), id_(id), neighbours_(std::move(neighbours)), params_(params) {
  if (!neighbours_.empty()) sorted_ = detail::sorted_neighbours(id_, neighbours_);
  table_.resize(neighbours_.size());
  known_.assign(neighbours_.size(), 0);
}

std::size_t HyperbolicSetupNode::index_of(NodeId id) const { return detail::neighbour_index(sorted_, id); }

void HyperbolicSetupNode::on_start() {
  if (neighbours_.empty()) {  // a one-node network: its own root, the empty address
    root_ = true;
    q_ = 3;
    addressed_ = true;
    return;
  }
  if (params_.root ? *params_.root == id_ : params_.initiator == id_) begin(params_.root ? tree_sweep : 0, true);
}

void HyperbolicSetupNode::begin(std::uint8_t sweep, bool origin) {
  sweep_ = sweep;
  active_ = true;
  origin_ = origin;
  decided_ = echoed_ = timer_set_ = false;
  depth_ = 0;
  parent_ = least_ = candidate_ = best_from_ = nobody;
  heard_ = echoes_ = 0;
  heard_from_.assign(neighbours_.size(), 0);
  child_.assign(neighbours_.size(), 0);
  if (origin) {
    if (sweep == tree_sweep) root_ = true;
    decide();
  }
}

void HyperbolicSetupNode::decide() {
  decided_ = true;
  if (!origin_) {
    depth_ = least_ + 1;
    parent_ = candidate_;
  }
  // The subtree's result starts with the node itself: as the farthest node, or the sides it needs
  // (the latter once its children are known, in try_echo).
  best_value_ = sweep_ == tree_sweep ? 0 : depth_;
  best_id_ = id_;
  best_from_ = nobody;
  buffer_.clear();
  encode(HyperbolicSweepMsg{sweep_, depth_, origin_ ? id_ : neighbours_[parent_]}, buffer_);
  rt_.broadcast(buffer_);
  try_echo();
}

void HyperbolicSetupNode::on_timer(TimerId timer) {
  if (!active_ || decided_ || timer != sweep_) {
    ++counters_.rejected;
    return;
  }
  decide();
}

void HyperbolicSetupNode::on_message(NodeId from, std::span<const std::byte> bytes) {
  ++counters_.received;
  const std::size_t i = index_of(from);
  HyperbolicMessage m;
  if (i >= neighbours_.size() || decode(bytes, m) != DecodeStatus::ok) {
    ++counters_.rejected;
    return;
  }
  std::visit([&](const auto& x) { handle(i, x); }, m);
}

void HyperbolicSetupNode::handle(std::size_t from, const HyperbolicSweepMsg& m) {
  if (!active_ || m.sweep > sweep_) {
    // A new BFS reaches this node only after the previous one's echo passed it (its origin starts it
    // once every subtree has echoed): anything else does not fit.
    if (active_ && !echoed_) {
      ++counters_.rejected;
      return;
    }
    begin(m.sweep, false);
  } else if (m.sweep < sweep_ || (heard_from_[from] & heard_bit)) {
    ++counters_.rejected;
    return;
  }
  heard_from_[from] |= heard_bit;
  ++heard_;
  if (m.parent == id_) child_[from] = 1;
  else if (child_[from]) ++counters_.rejected;  // it echoed to us, so it is our child: it must say so
  if (!decided_) {
    if (m.depth < least_ || (m.depth == least_ && neighbours_[from] < neighbours_[candidate_])) {
      least_ = m.depth;
      candidate_ = static_cast<std::uint32_t>(from);
    }
    if (!timer_set_) {
      timer_set_ = true;
      rt_.schedule(0, sweep_);  // after every copy due now
    }
  }
  try_echo();
}

void HyperbolicSetupNode::handle(std::size_t from, const HyperbolicEchoMsg& m) {
  // Links need not be FIFO: a child's echo may overtake its flood message (which names us as its
  // parent); only a child echoes to us, so an echo also makes its sender a child.
  if (!active_ || !decided_ || m.sweep != sweep_ || echoed_ || (heard_from_[from] & echo_bit) ||
      ((heard_from_[from] & heard_bit) && !child_[from])) {
    ++counters_.rejected;
    return;
  }
  heard_from_[from] |= echo_bit;
  child_[from] = 1;
  if (sweep_ == tree_sweep) {
    best_value_ = std::max(best_value_, m.value);
  } else if (m.value > best_value_ || (m.value == best_value_ && m.id < best_id_)) {
    best_value_ = m.value;
    best_id_ = m.id;
    best_from_ = static_cast<std::uint32_t>(from);
  }
  ++echoes_;
  try_echo();
}

void HyperbolicSetupNode::try_echo() {
  if (!decided_ || echoed_ || heard_ < neighbours_.size()) return;
  const auto children = static_cast<std::uint32_t>(std::count(child_.begin(), child_.end(), 1));
  if (echoes_ < children) return;
  echoed_ = true;
  if (sweep_ == tree_sweep) best_value_ = std::max(best_value_, children + (origin_ ? 0u : 1u));
  if (origin_) {
    finish_sweep();
    return;
  }
  send(parent_, HyperbolicEchoMsg{sweep_, best_value_, sweep_ == tree_sweep ? 0 : best_id_});
}

void HyperbolicSetupNode::finish_sweep() {
  if (sweep_ == 0) {
    steer(0, 0);  // to the farthest node, which starts sweep 1
  } else if (sweep_ == 1) {
    steer(1, (best_value_ + 1) / 2);  // ⌈L/2⌉ hops towards the farthest node: the root
  } else {
    take_address(std::max(3u, best_value_), {});
  }
}

// Stage 0: on to the child the farthest node's echo came from, or start sweep 1 there. Stage 1: `hops`
// more hops along sweep 1's echo path; the node reached with none left is the root.
void HyperbolicSetupNode::steer(std::uint8_t stage, std::uint32_t hops) {
  if (stage == 0 ? best_from_ == nobody : hops == 0) {
    begin(stage == 0 ? 1 : tree_sweep, true);
    return;
  }
  send(best_from_, HyperbolicRootMsg{stage, stage == 0 ? 0 : hops - 1});
}

void HyperbolicSetupNode::handle(std::size_t, const HyperbolicRootMsg& m) {
  // It travels the path of the echo that just ended: the sweep it steers along must be done here.
  if (!active_ || sweep_ != m.stage || !echoed_ || origin_) {
    ++counters_.rejected;
    return;
  }
  steer(m.stage, m.hops_left);
}

void HyperbolicSetupNode::take_address(std::uint32_t q, std::vector<std::uint32_t> address) {
  q_ = q;
  address_ = std::move(address);
  addressed_ = true;
  const std::size_t deg = neighbours_.size();
  const auto children = static_cast<std::uint32_t>(std::count(child_.begin(), child_.end(), 1));
  std::vector<std::uint32_t> word = address_;
  word.push_back(0);
  for (std::size_t i = 0, rank = 0; i < deg; ++i) {
    if (child_[i]) {  // its address: ours and its side
      word.back() = core::hyperbolic_child_side(q_, root_, depth_, static_cast<std::uint32_t>(++rank), children);
      table_[i] = word;
      send(i, HyperbolicAddressMsg{q_, 0, depth_ + 1, pack_hyperbolic_address(word, q_)});
    } else if (!root_ && i == parent_) {  // the parent's: ours without its last side
      table_[i].assign(address_.begin(), address_.end() - 1);
    } else {
      send(i, HyperbolicAddressMsg{q_, 1, depth_, pack_hyperbolic_address(address_, q_)});
      continue;
    }
    known_[i] = 1;
    ++known_count_;
  }
}

void HyperbolicSetupNode::handle(std::size_t from, const HyperbolicAddressMsg& m) {
  const bool tree_done = active_ && sweep_ == tree_sweep && echoed_;
  if (m.whose == 0) {  // ours, from the parent
    if (!tree_done || root_ || from != parent_ || addressed_ || m.levels != depth_) {
      ++counters_.rejected;
      return;
    }
    take_address(m.q, unpack_hyperbolic_address(m.packed, m.levels, m.q));
    return;
  }
  // A neighbour's, over a non-tree edge (it may come before our own address).
  if (!tree_done || child_[from] || (!root_ && from == parent_) || known_[from]) {
    ++counters_.rejected;
    return;
  }
  table_[from] = unpack_hyperbolic_address(m.packed, m.levels, m.q);
  known_[from] = 1;
  ++known_count_;
}

bool HyperbolicSetupNode::done() const { return addressed_ && known_count_ == neighbours_.size(); }

NodeId HyperbolicSetupNode::parent() const { return root_ || parent_ == nobody ? id_ : neighbours_[parent_]; }

std::size_t HyperbolicSetupNode::state_bytes() const {
  const std::size_t width = hyperbolic_address_width(q_ == 0 ? 3 : q_);
  std::size_t bytes = 12 + (address_.size() * width + 7) / 8;
  for (const auto& a : table_) bytes += 4 + (a.size() * width + 7) / 8;
  return bytes;
}

void HyperbolicSetupNode::send(std::size_t to, const HyperbolicMessage& m) {
  encode(m, buffer_);
  rt_.send(neighbours_[to], buffer_);
}

}  // namespace laguerre::protocols
