#pragma once
/// @file
/// The distributed set-up of the hyperbolic baseline (core/routing/HyperbolicEmbedding.hpp,
/// Kleinberg's greedy embedding of a BFS tree): one `HyperbolicSetupNode` per network node, hosted
/// through `Runtime`. docs/hyperbolic-baseline.md ("The set-up as a protocol") has the phases and
/// their message counts; in short:
///  1. unless the root is given, a double sweep: a BFS from the initiator, its echo names the
///     farthest node a, a message steers down the echo's path to a, a BFS from a, its echo names the
///     farthest node b and L = d(a, b), and a message steers ⌈L/2⌉ hops towards b: that node is the root;
///  2. a BFS from the root (the tree), whose echo gives the root q = max(3, most sides a node needs);
///  3. addresses down the tree: each node computes its children's addresses from its own, its depth
///     and its number of children (core::hyperbolic_child_side) and sends each its own;
///  4. each node sends its address over its non-tree edges (its tree neighbours' addresses it already
///     knows): the neighbour table greedy forwarding needs.
///
/// A BFS: the origin sends (depth 0, parent itself) to every neighbour; a node that first hears one
/// waits until every message due at that instant has arrived (a zero-delay timer: the host delivers
/// the copies of an instant before its timers), takes depth = least heard + 1 and as parent the
/// smallest id among the neighbours that announced the least depth, and sends (depth, parent) to every
/// neighbour. A node that has heard every neighbour knows its children (those naming it as parent);
/// once each child has echoed, it echoes its subtree's result to its parent (links need not be FIFO:
/// an echo that overtakes its sender's flood message marks it a child). 2|E| + |V| − 1 messages.
///
/// Guarantees, on a connected graph whose nodes all get the same parameters: every node ends done()
/// with its tree parent, depth, q, address and its neighbours' addresses. With constant link latency
/// (the levels of a BFS arrive at once) they equal core::HyperbolicTreeEmbedding's of the same graph
/// (neighbours listed in its adjacency order, ids increasing with vertex indices, the initiator vertex
/// 0) bit for bit; with variable latency the tree is still a spanning tree whose depths need not be
/// shortest (Kleinberg's embedding delivers on any spanning tree). Reliable links only (no
/// reliability layer). Malformed messages, messages of another set and messages that do not fit the
/// node's state are counted and dropped.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "laguerre/protocols/Codec.hpp"
#include "laguerre/protocols/Runtime.hpp"

namespace laguerre::protocols {

/// Parameters shared by all nodes of a set-up run.
struct HyperbolicSetupParams {
  std::optional<NodeId> root;  ///< a given root (no double sweep); else the sweep picks it
  NodeId initiator = 0;        ///< the node that starts the double sweep (core's vertex 0)
};

/// Per-node message statistics.
struct HyperbolicSetupCounters {
  std::uint64_t received = 0;    ///< messages received
  std::uint64_t rejected = 0;    ///< malformed, of another set, or not fitting the node's state
};

/// One node of the set-up.
class HyperbolicSetupNode final : public Node {
public:
  /// A node with id `id` and neighbours `neighbours` (the order in which its children take their sides:
  /// core's adjacency order for bit-exact agreement); `runtime` must outlive it. Throws
  /// core::InternalError (a broken precondition) for a neighbour list naming the node or a neighbour twice.
  HyperbolicSetupNode(Runtime& runtime, NodeId id, std::vector<NodeId> neighbours, HyperbolicSetupParams params);

  /// The initiator starts the double sweep, a given root the tree's BFS; a node without neighbours is
  /// the root of its one-node tree.
  void on_start() override;
  /// A HyperbolicMessage from a neighbour.
  void on_message(NodeId from, std::span<const std::byte> bytes) override;
  /// The decision of a BFS level (see the file comment).
  void on_timer(TimerId timer) override;
  /// Done: it has its address and every neighbour's.
  bool is_final() const override { return done(); }

  /// Whether the node has its address and every neighbour's.
  bool done() const;
  /// Whether this node is the tree's root.
  bool is_root() const { return root_; }
  /// This node's id.
  NodeId id() const { return id_; }
  /// Tree parent (its own id at the root); meaningful once done().
  NodeId parent() const;
  /// Hops from the root in the tree.
  std::uint32_t depth() const { return depth_; }
  /// The tiling degree q (0 until the address arrives).
  std::uint32_t tiling_degree() const { return q_; }
  /// Its address: the child sides from the root's child down to this node.
  const std::vector<std::uint32_t>& address() const { return address_; }
  /// Neighbour i's address (in the constructor's order); empty until known.
  const std::vector<std::uint32_t>& neighbour_address(std::size_t i) const { return table_[i]; }
  /// The bytes of routing state it holds once done: q, depth and the parent's neighbour index (4 bytes
  /// each), its packed address, and per neighbour a 4-byte length and the packed address.
  std::size_t state_bytes() const;
  /// Message statistics.
  const HyperbolicSetupCounters& counters() const { return counters_; }

private:
  static constexpr std::uint32_t nobody = 0xffffffffu;  // "no index" / "not yet"
  std::size_t index_of(NodeId id) const;
  void begin(std::uint8_t sweep, bool origin);  // a new BFS at this node
  void decide();                                // the level's decision: depth, parent, broadcast
  void try_echo();
  void finish_sweep();                          // at the origin, once its subtree echoed
  void steer(std::uint8_t stage, std::uint32_t hops);  // down the echo's path, or arrive
  void take_address(std::uint32_t q, std::vector<std::uint32_t> address);
  void handle(std::size_t from, const HyperbolicSweepMsg& m);
  void handle(std::size_t from, const HyperbolicEchoMsg& m);
  void handle(std::size_t from, const HyperbolicRootMsg& m);
  void handle(std::size_t from, const HyperbolicAddressMsg& m);
  void send(std::size_t to, const HyperbolicMessage& m);

  Runtime& rt_;
  NodeId id_;
  std::vector<NodeId> neighbours_;
  std::vector<std::pair<NodeId, std::uint32_t>> sorted_;  // for index_of
  HyperbolicSetupParams params_;
  // The current BFS (sweeps run one after the other; a node takes part in one at a time).
  std::uint8_t sweep_ = 0;
  bool active_ = false, origin_ = false, decided_ = false, echoed_ = false, timer_set_ = false;
  std::uint32_t depth_ = 0, parent_ = nobody, heard_ = 0, echoes_ = 0;
  std::uint32_t least_ = nobody, candidate_ = nobody;  // least depth heard, smallest id announcing it
  std::vector<std::uint8_t> heard_from_, child_;  // per neighbour: heard_bit | echo_bit; a child
  std::uint32_t best_value_ = 0, best_from_ = nobody;  // the subtree's result; the child it came from
  NodeId best_id_ = 0;
  // The result.
  bool root_ = false;
  std::uint32_t q_ = 0;
  std::vector<std::uint32_t> address_;
  std::vector<std::vector<std::uint32_t>> table_;
  std::vector<std::uint8_t> known_;  // per neighbour: its address is in table_
  std::size_t known_count_ = 0;
  bool addressed_ = false;
  std::vector<std::byte> buffer_;
  HyperbolicSetupCounters counters_;
};

}  // namespace laguerre::protocols
