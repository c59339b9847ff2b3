#pragma once
/// @file
/// The messages of the packing protocol, of its reliability layer and of packet forwarding, their
/// message sets, and their byte encoding, identical in every host.
///
/// Wire format (all integers little-endian, every field fixed-size, no padding):
///
///     byte 0      version (wire_version)
///     byte 1      MessageType
///     bytes 2…    the type's fields, in declaration order:
///                   u8 / u32 / u64  unsigned integers, 1 / 4 / 8 bytes, little-endian
///                   f64             the IEEE-754 bits of a double as a u64 (bit-exact, NaN payloads
///                                   and signed zeros included)
///
/// A fixed-size message has exactly `encoded_size(type)` bytes. The three variable-size messages
/// (FaceCirclesMsg, RelayMsg, FrameMsg) have a fixed part of `encoded_size(type)` bytes that ends with a u32
/// count, followed by exactly that many items; the count is range-checked before it is used, so a
/// length never depends on unchecked data. `decode` checks, in this order: at least two bytes (else
/// `truncated`), the version, the type (`unknown_type` for a byte that is no MessageType,
/// `foreign_type` for one outside the message set decoded into), the exact length (`truncated` if
/// short, `trailing_bytes` if long; for a variable-size message first the fixed part, then
/// `out_of_range` if the count is outside its range, then the total), then the ranges each message
/// documents (`out_of_range`). Any byte string is safe to decode; only `DecodeStatus::ok` yields a
/// message. Every valid message has one encoding: a decoded message re-encodes to its bytes.
///
/// Message sets: each receiver decodes only the messages it handles (docs/protocol.md describes the
/// protocols):
///  - PackingMessage (types 1–10 and 17–21): between protocol vertices of the packing protocol;
///  - PackingHop: what a packing node sends a neighbour without the reliability layer, a
///    PackingMessage or a RelayMsg (type 11, an envelope between a face vertex and a face member);
///  - LinkMessage (types 13, 14): the reliability layer's frames and acknowledgements on one link;
///  - FramePayload: what a frame carries, a PackingHop or a FailureMsg (type 15);
///  - ForwardingMessage (types 12, 16): data packets of the forwarding schemes (Forwarding.hpp);
///  - HyperbolicMessage (types 22–25): the set-up of the hyperbolic baseline (HyperbolicSetup.hpp);
///  - Message: any of the 25 types.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

namespace laguerre::protocols {

/// Version of the wire format written into byte 0.
inline constexpr std::uint8_t wire_version = 4;

/// Message types (byte 1 of every message).
enum class MessageType : std::uint8_t {
  depth = 1,     ///< DepthMsg: a depth estimate of the breadth-first search from the boundary, or its acknowledgement
  election = 2,  ///< ElectionMsg: the root election's best key (BFS forest, boundary ring, path down)
  start = 3,     ///< StartMsg: the elected root starts the layout wave (to its neighbours)
  wave = 4,      ///< WaveMsg: a placement estimate of the combinatorial layout wave (set-up)
  radius = 5,    ///< RadiusMsg: a Thurston-step radius exchange
  placed = 6,    ///< PlacedMsg: a node's circle in one round's layout
  report = 7,    ///< ReportMsg: the AND convergecast of local checks
  decision = 8,  ///< DecisionMsg: the root's stop / next-round broadcast
  shape = 9,     ///< ShapeMsg: the layout wave's acknowledgements up, its end and the graph's shape down
  face_circles = 10,  ///< FaceCirclesMsg: a face vertex sends every circle of its face (one round)
  relay = 11,    ///< RelayMsg: an envelope relayed along a face between a face vertex and a face member
  data = 12,     ///< DataMsg: a data packet forwarded greedily (Forwarding.hpp)
  frame = 13,    ///< FrameMsg: a sequence-numbered envelope of the reliability layer (lossy links)
  ack = 14,      ///< AckMsg: the reliability layer's acknowledgement of received frames
  failure = 15,  ///< FailureMsg: a node declared a neighbour failed (flooded, carried in frames)
  route = 16,    ///< RouteMsg: a data packet of a baseline scheme (Euclidean, compass, GFG; Forwarding.hpp)
  krylov_value = 17,     ///< KrylovValueMsg: a Newton–Krylov neighbour exchange (CG vector or trial radius)
  krylov_sum = 18,       ///< KrylovSumMsg: a Newton–Krylov partial sum, up the layout tree
  krylov_decision = 19,  ///< KrylovDecisionMsg: the root's Newton–Krylov decision, down the layout tree
  gate_radius = 20,      ///< GateRadiusMsg: a radius exchange carrying the flooded radius-only gate
  height = 21,           ///< HeightMsg: the layout tree's height (set-up convergecast / broadcast)
  hyperbolic_sweep = 22,    ///< HyperbolicSweepMsg: a BFS flood of the hyperbolic set-up
  hyperbolic_echo = 23,     ///< HyperbolicEchoMsg: its echo up the BFS tree
  hyperbolic_root = 24,     ///< HyperbolicRootMsg: steering along the double sweep's path
  hyperbolic_address = 25,  ///< HyperbolicAddressMsg: a tree address (to a child, or to a neighbour)
};

/// Largest MessageType value (types 1 … max_message_type exist).
inline constexpr std::uint8_t max_message_type = 25;

/// Name of a message type ("depth", "election", …), "?" for values outside the enum.
std::string_view to_string(MessageType t);

/// The event-driven BFS from the boundary (docs/protocol.md, "Set-up"), diffusing depth estimates
/// that only decrease, with Dijkstra–Scholten acknowledgements. Fields: u8 ack ∈ {0, 1}, u32 depth
/// (≤ max_depth), u64 parent.
///  - ack = 0, an estimate: "my depth is at most `depth`"; `parent` is the sender's own id, or, in a
///    correction sent only to a former BFS parent, the sender's new parent (same depth, another one).
///  - ack = 1, the acknowledgement of one estimate, with the sender's current depth; `parent` is the
///    sender's BFS parent at that depth ("you are my parent" iff it is the receiver) when the
///    acknowledged estimate was one it could take its depth from, else the sender's own id (no claim).
struct DepthMsg {
  static constexpr std::uint32_t max_depth = 0x7fffffff;  ///< largest depth (depth + 1 never overflows)
  bool ack = false;          ///< an acknowledgement (else an estimate)
  std::uint32_t depth = 0;   ///< the sender's depth estimate
  std::uint64_t parent = 0;  ///< see above
  friend bool operator==(const DepthMsg&, const DepthMsg&) = default;
};

/// The three legs of the root election and the two ring tokens that end the depth BFS before it
/// (docs/protocol.md, "Set-up").
enum class ElectionStage : std::uint8_t {
  report = 0,  ///< up the BFS forest: the best key of the sender's subtree
  ring = 1,    ///< round the boundary ring: a boundary vertex's best key, forwarded while it is the best seen
  root = 2,    ///< down the BFS forest, towards the vertex whose key it is (the root)
  settled = 3, ///< round the boundary ring, before the election: a boundary vertex whose depth messages
               ///< are all acknowledged (the best id goes on; back at its sender, the BFS has ended)
  final = 4,   ///< both ways round the ring and down the BFS forest: every depth is final
};

/// A key (depth, id) of the root election: larger depth wins, then smaller id (RootRule::deepest;
/// depth 0 for every key under RootRule::smallest_id); (0, 2^64 − 1) is "no key" (a subtree without
/// an interior vertex of G). Fields: u8 stage ∈ {0, …, 4}, u32 depth, u64 id. The `settled` and `final`
/// tokens carry depth 0 and the id of the boundary vertex whose `settled` token it is.
struct ElectionMsg {
  ElectionStage stage = ElectionStage::report;  ///< which leg it travels
  std::uint32_t depth = 0;  ///< the key's depth from the boundary (0 under RootRule::smallest_id)
  std::uint64_t id = 0;     ///< the key's vertex id
  friend bool operator==(const ElectionMsg&, const ElectionMsg&) = default;
};

/// From the elected root to each of its neighbours: the root and its first neighbour, both placed at
/// wave 0 (the root's placement; it starts the layout wave). Fields: u64 root, u64 first; root ≠ first.
struct StartMsg {
  std::uint64_t root = 0;   ///< the root's id
  std::uint64_t first = 0;  ///< the id of the root's first neighbour
  friend bool operator==(const StartMsg&, const StartMsg&) = default;
};

/// The sender's current placement in the layout wave (docs/protocol.md, "Set-up"): placed in wave
/// `wave` from `parent`; an estimate that only decreases (a later message, higher `seq`, replaces an
/// earlier one; the last is final). Fields: u32 seq ≥ 1 (the sender's count of WaveMsg), u32 wave,
/// u64 parent.
struct WaveMsg {
  std::uint32_t seq = 1;     ///< the sender's WaveMsg number (1, 2, …): the highest is the newest
  std::uint32_t wave = 0;    ///< the wave in which the sender is placed
  std::uint64_t parent = 0;  ///< the sender's parent in the layout tree
  friend bool operator==(const WaveMsg&, const WaveMsg&) = default;
};

/// The sender's hyperbolic radius h at Thurston step `step` (before the step's update). Fields:
/// u32 step, f64 h ∈ (0, ∞] (∞: a horocycle).
struct RadiusMsg {
  std::uint32_t step = 0;  ///< global step number (= sweeps done so far)
  double h = 0;            ///< hyperbolic radius
  friend bool operator==(const RadiusMsg&, const RadiusMsg&) = default;
};

/// The sender's circle in the layout of round `round`. Fields: u32 round, f64 h ∈ (0, ∞], f64 centre
/// (real, imaginary), f64 circle (x, y, r). Centre and circle are not range-checked: before
/// convergence a layout may legitimately hold NaNs or infinities, which the checks then reject.
struct PlacedMsg {
  std::uint32_t round = 0;  ///< round number (0 = the check before any sweep)
  double h = 0;             ///< the sender's hyperbolic radius in this round
  double centre_re = 0;     ///< hyperbolic centre or ideal point, real part
  double centre_im = 0;     ///< hyperbolic centre or ideal point, imaginary part
  double cx = 0;            ///< Euclidean circle centre abscissa
  double cy = 0;            ///< Euclidean circle centre ordinate
  double cr = 0;            ///< Euclidean circle radius
};

/// Bitwise equality of two PlacedMsg (NaN-safe, so that round trips can be tested).
bool same_bits(const PlacedMsg& a, const PlacedMsg& b);

/// AND of the local checks in the sender's subtree for round `round`. Fields: u32 round,
/// u8 ok ∈ {0, 1}.
struct ReportMsg {
  std::uint32_t round = 0;  ///< round number
  bool ok = false;          ///< whether LPD holds everywhere in the sender's subtree
  friend bool operator==(const ReportMsg&, const ReportMsg&) = default;
};

/// What the root decided after round `round`.
enum class Verdict : std::uint8_t {
  next = 0,       ///< run another round
  converged = 1,  ///< stop: LPD holds everywhere
  cap = 2,        ///< stop: the iteration cap is reached
  layout = 3,     ///< radius-only termination: the radius-only test held everywhere (or the cap is
                  ///< reached): lay out and check this round exactly, then decide again
};

/// The root's decision, sent down the layout tree. Fields: u32 round, u8 verdict ∈ {0, 1, 2, 3}.
struct DecisionMsg {
  std::uint32_t round = 0;           ///< round number
  Verdict verdict = Verdict::next;   ///< what to do
  friend bool operator==(const DecisionMsg&, const DecisionMsg&) = default;
};

/// Set-up, the layout wave's termination (Dijkstra–Scholten) and the graph's shape: `down` = 0
/// acknowledges one StartMsg or WaveMsg, with `polygon` the OR of "is or touches a face vertex" over
/// the vertices whose work the acknowledgement closes (0 for an immediate one); `down` = 1, from the
/// root down the layout tree once the wave has ended: whether some inner face of G is not a triangle
/// (the graph is then packed as G′, with overlap angles everywhere, and checked with GLPD). Fields:
/// u8 down ∈ {0, 1}, u8 polygon ∈ {0, 1}.
struct ShapeMsg {
  bool down = false;     ///< an acknowledgement (false) or the root's answer (true)
  bool polygon = false;  ///< whether some face vertex exists (in the acknowledged work, or in K)
  friend bool operator==(const ShapeMsg&, const ShapeMsg&) = default;
};

/// Set-up, after the shape broadcast: the largest wave of the sender's subtree of the layout tree
/// (`down` = 0, to its parent) or of K (`down` = 1, the root's answer, to the children); run when the
/// termination needs it (radius-flood: D = 2·height + 2, core::radius_flood_depth). Fields:
/// u8 down ∈ {0, 1}, u32 height.
struct HeightMsg {
  bool down = false;          ///< up the layout tree (false) or down (true)
  std::uint32_t height = 0;   ///< largest wave in the sender's subtree (up) or in K (down)
  friend bool operator==(const HeightMsg&, const HeightMsg&) = default;
};

/// Largest number of circles in a FaceCirclesMsg (the size of a face).
inline constexpr std::uint32_t max_face_circles = 4096;

/// One circle of a face, as carried by FaceCirclesMsg.
struct FaceCircle {
  double x = 0;  ///< centre abscissa
  double y = 0;  ///< centre ordinate
  double r = 0;  ///< radius
};

/// From a face vertex to the vertices of its face: their circles in the layout of round `round`, in
/// the face's counter-clockwise walk starting at the face's host (its smallest id). Not range-checked
/// (as PlacedMsg). Fields: u32 round, u32 count ∈ [3, max_face_circles], count × (f64 x, f64 y, f64 r).
struct FaceCirclesMsg {
  std::uint32_t round = 0;          ///< round number
  std::vector<FaceCircle> circles;  ///< the circles, walk order from the host
};

/// Bitwise equality of two FaceCirclesMsg (NaN-safe).
bool same_bits(const FaceCirclesMsg& a, const FaceCirclesMsg& b);

/// Largest payload of a RelayMsg (an encoded message of another type).
inline constexpr std::uint32_t max_relay_payload = 2 + 8 + 24 * max_face_circles;

/// An envelope for a message between a face vertex (emulated by its host) and a vertex of its face,
/// walked along the face's boundary. `face` names the face vertex (face_vertex_id), `source` and
/// `target` are the ids of the sending and receiving protocol vertices (one of them is `face`), and
/// `backward` says which way round the face it travels: 0 = in the face's counter-clockwise walk
/// direction, 1 = against it. The payload is not decoded by relays. Fields: u64 face, u64 source,
/// u64 target, u8 backward ∈ {0, 1}, u32 count ∈ [2, max_relay_payload], count payload bytes;
/// source ≠ target and face ∈ {source, target}.
struct RelayMsg {
  std::uint64_t face = 0;           ///< the face vertex's id
  std::uint64_t source = 0;         ///< sending protocol vertex
  std::uint64_t target = 0;         ///< receiving protocol vertex
  bool backward = false;            ///< direction round the face
  std::vector<std::byte> payload;   ///< the carried message, encoded
  friend bool operator==(const RelayMsg&, const RelayMsg&) = default;
};

/// A data packet in flight (greedy power forwarding, Forwarding.hpp), as it leaves a node: `hops`
/// counts the hops taken including this one. Fields: u64 packet, u64 source, u64 target, f64 target
/// circle (x, y, r), u32 ttl, u32 hops; 1 ≤ hops ≤ ttl, source ≠ target, the circle finite with r ≥ 0.
struct DataMsg {
  std::uint64_t packet = 0;  ///< packet id (chosen by the source's host)
  std::uint64_t source = 0;  ///< source node id
  std::uint64_t target = 0;  ///< target node id
  double tx = 0;             ///< target circle centre abscissa
  double ty = 0;             ///< target circle centre ordinate
  double tr = 0;             ///< target circle radius
  std::uint32_t ttl = 0;     ///< hop limit
  std::uint32_t hops = 0;    ///< hops taken, this one included
  friend bool operator==(const DataMsg&, const DataMsg&) = default;
};

/// What a receiver of a link has got so far: every sequence number below `next` (the first one
/// missing), and `next + 1 + k` for every bit k set in `bits` (a selective acknowledgement).
struct AckInfo {
  std::uint32_t next = 0;  ///< the first sequence number not yet received
  std::uint64_t bits = 0;  ///< bit k: sequence number next + 1 + k was received
  friend bool operator==(const AckInfo&, const AckInfo&) = default;
};

/// Largest payload of a FrameMsg: any other message, a maximal RelayMsg included.
inline constexpr std::uint32_t max_frame_payload = 31 + max_relay_payload;

/// One message of the per-link reliability layer (docs/protocol.md): sequence number `seq` on the
/// directed link sender → receiver, the sender's acknowledgement of the reverse link, and the carried
/// message, encoded (empty for a liveness probe). Fields: u32 seq, u32 ack.next, u64 ack.bits,
/// u32 count ∈ [0, max_frame_payload], count payload bytes. The payload is decoded by the receiver
/// only once the frame is known not to be a duplicate.
struct FrameMsg {
  std::uint32_t seq = 0;           ///< sequence number on the directed link
  AckInfo ack;                     ///< what the sender has received on the reverse link
  std::vector<std::byte> payload;  ///< the carried message, encoded; empty for a probe
  friend bool operator==(const FrameMsg&, const FrameMsg&) = default;
};

/// An acknowledgement alone (when no frame is going the other way soon). Fields: u32 ack.next,
/// u64 ack.bits.
struct AckMsg {
  AckInfo ack;  ///< what the sender has received on the reverse link
  friend bool operator==(const AckMsg&, const AckMsg&) = default;
};

/// "Node `suspect` stopped answering": flooded to every node (inside frames), which then ends its
/// run with PackingOutcome::neighbour_failed. Fields: u64 suspect.
struct FailureMsg {
  std::uint64_t suspect = 0;  ///< the node declared failed
  friend bool operator==(const FailureMsg&, const FailureMsg&) = default;
};

/// The routing scheme of a RouteMsg; the values are core::Scheme's declaration order (greedy power,
/// 0, travels as DataMsg).
enum class RouteScheme : std::uint8_t {
  greedy_euclid = 1,  ///< greedy Euclidean routing on the nodes' positions
  compass = 2,        ///< compass routing
  gfg = 3,            ///< greedy-face-greedy: greedy Euclidean, face routing at local minima
};

/// A data packet of a baseline scheme in flight, as it leaves a node (`hops` counts this hop), with
/// the perimeter state of greedy-face-greedy routing (Forwarding.hpp explains its use). Fields:
/// u64 packet, u64 source, u64 target, u8 scheme ∈ {1, 2, 3}, f64 target position (tx, ty), u32 ttl,
/// u32 hops, u8 perimeter ∈ {0, 1}, f64 entry point (px, py), u8 crossed ∈ {0, 1}, f64 last crossed
/// edge (ax, ay, bx, by), u64 walk_tail, u64 walk_head.
///
/// Ranges: 1 ≤ hops ≤ ttl, source ≠ target, tx, ty finite. `perimeter` = 1 only for gfg, and then
/// px, py are finite and walk_tail ≠ walk_head; `crossed` = 1 only in perimeter mode, and then the
/// edge is finite. The encoding is canonical: every field that its mode does not use (the perimeter
/// block in greedy mode, the edge when `crossed` = 0) must be +0 (all bits zero), else out_of_range.
struct RouteMsg {
  std::uint64_t packet = 0;                        ///< packet id (chosen by the source's host)
  std::uint64_t source = 0;                        ///< source node id
  std::uint64_t target = 0;                        ///< target node id
  RouteScheme scheme = RouteScheme::greedy_euclid;  ///< routing scheme
  double tx = 0;                                   ///< target position, abscissa
  double ty = 0;                                   ///< target position, ordinate
  std::uint32_t ttl = 0;                           ///< hop limit
  std::uint32_t hops = 0;                          ///< hops taken, this one included
  bool perimeter = false;  ///< gfg: face routing (true) or greedy mode (false)
  double px = 0;           ///< gfg perimeter: position of the node where face routing began (P)
  double py = 0;           ///< gfg perimeter: ordinate of P
  bool crossed = false;    ///< gfg perimeter: the last face change was at an edge crossing (else at P)
  double ax = 0;           ///< gfg perimeter: tail of the edge of the last face change, abscissa
  double ay = 0;           ///< gfg perimeter: its ordinate
  double bx = 0;           ///< gfg perimeter: head of that edge, abscissa
  double by = 0;           ///< gfg perimeter: its ordinate
  std::uint64_t walk_tail = 0;  ///< gfg perimeter: the walk since the last face change began with the
  std::uint64_t walk_head = 0;  ///< edge walk_tail → walk_head
  friend bool operator==(const RouteMsg&, const RouteMsg&) = default;
};

/// Newton–Krylov mode (core/packing/NewtonKrylov.hpp): the value the sender exchanges before tree sum
/// `seq` (its CG vector z, or its trial radius). Fields: u32 seq, f64 value (not range-checked: CG
/// values have any sign; a non-finite one makes the step fail at the root, never here).
struct KrylovValueMsg {
  std::uint32_t seq = 0;  ///< the tree sum it feeds (counted from the start of the run)
  double value = 0;       ///< z or the trial radius
  friend bool operator==(const KrylovValueMsg&, const KrylovValueMsg&) = default;
};

/// Newton–Krylov mode: the sender's subtree partial of tree sum `seq`, to its parent. Fields: u32 seq,
/// f64 s0, s1, s2 (sums), f64 max.
struct KrylovSumMsg {
  std::uint32_t seq = 0;  ///< tree sum number
  double s0 = 0, s1 = 0, s2 = 0;  ///< the three sums
  double max = 0;         ///< the maximum
  friend bool operator==(const KrylovSumMsg&, const KrylovSumMsg&) = default;
};

/// Newton–Krylov mode: the root's decision after tree sum `seq` (core::KrylovDecision), to the
/// children. Fields: u32 seq, u8 action ∈ [0, 4], f64 a, f64 b.
struct KrylovDecisionMsg {
  std::uint32_t seq = 0;  ///< tree sum number
  std::uint8_t action = 0;  ///< core::KrylovAction
  double a = 0, b = 0;    ///< α or t, and β
  friend bool operator==(const KrylovDecisionMsg&, const KrylovDecisionMsg&) = default;
};

/// Termination::radius_flood (docs/radius-only.md §8): the radius exchange of step `step` between all
/// K-neighbours (boundary vertices send h = ∞), with the sender's gate bits: bit j is the AND, over the
/// vertices within (step − s − 1) hops of the sender, of the closing-gap test of the pending tested
/// step s in slot j (1 for a free slot). Fields: u32 step, f64 h ∈ (0, ∞], u64 gate.
struct GateRadiusMsg {
  std::uint32_t step = 0;  ///< global step number
  double h = 0;            ///< hyperbolic radius (∞: a horocycle)
  std::uint64_t gate = 0;  ///< the flooded test bits, one per pending tested step
  friend bool operator==(const GateRadiusMsg&, const GateRadiusMsg&) = default;
};

/// Hyperbolic set-up (HyperbolicSetup.hpp): BFS flood `sweep` (0, 1: the double sweep that picks
/// the root; 2: the tree), the sender's depth and its parent (its own id at the BFS's origin). Sent
/// once to every neighbour per sweep. Fields: u8 sweep ∈ [0, 2], u32 depth, u64 parent.
struct HyperbolicSweepMsg {
  std::uint8_t sweep = 0;    ///< which BFS
  std::uint32_t depth = 0;   ///< the sender's hops from the origin
  std::uint64_t parent = 0;  ///< the sender's parent (itself at the origin)
  friend bool operator==(const HyperbolicSweepMsg&, const HyperbolicSweepMsg&) = default;
};

/// The echo of BFS `sweep` from a child to its parent, once its subtree is done: for sweeps 0 and 1
/// the subtree's farthest node (largest depth, smallest id), for sweep 2 the most tiles' sides a node
/// of the subtree needs (its children, plus one for its parent). Fields: u8 sweep ∈ [0, 2], u32 value,
/// u64 id (0 for sweep 2).
struct HyperbolicEchoMsg {
  std::uint8_t sweep = 0;   ///< which BFS
  std::uint32_t value = 0;  ///< farthest depth (sweeps 0, 1) or sides needed (sweep 2)
  std::uint64_t id = 0;     ///< farthest node (sweeps 0, 1)
  friend bool operator==(const HyperbolicEchoMsg&, const HyperbolicEchoMsg&) = default;
};

/// Steering down the echo's path towards a sweep's farthest node: stage 0 goes to the farthest node of
/// sweep 0, which starts sweep 1; stage 1 goes `hops_left` more hops towards sweep 1's farthest node,
/// where the receiver becomes the root. Fields: u8 stage ∈ {0, 1}, u32 hops_left (0 at stage 0).
struct HyperbolicRootMsg {
  std::uint8_t stage = 0;       ///< 0 or 1
  std::uint32_t hops_left = 0;  ///< stage 1: hops after this one
  friend bool operator==(const HyperbolicRootMsg&, const HyperbolicRootMsg&) = default;
};

/// A tree address (core::HyperbolicTreeEmbedding::address): `levels` child sides of
/// hyperbolic_address_width(q) bits each, packed little-endian from the root's child
/// (pack_hyperbolic_address). whose = 0: the receiver's own address, from its parent; 1: the
/// sender's, for the receiver's neighbour table. Fields: u32 q ≥ 3, u8 whose ∈ {0, 1}, u32 levels,
/// u32 count = ⌈levels·width/8⌉, count bytes; every side < q, sides below the first ≥ 1, unused bits 0.
struct HyperbolicAddressMsg {
  std::uint32_t q = 3;            ///< the tiling degree
  std::uint8_t whose = 0;         ///< 0: the receiver's, 1: the sender's
  std::uint32_t levels = 0;       ///< the address's length (its node's depth)
  std::vector<std::byte> packed;  ///< the sides, packed
  friend bool operator==(const HyperbolicAddressMsg&, const HyperbolicAddressMsg&) = default;
};

/// Bits of one side in a packed address: ⌈log2 q⌉, as core::hyperbolic_side_bits (repeated here: the
/// codec is compiled without core in the fuzzing build, tests/fuzz).
std::size_t hyperbolic_address_width(std::uint32_t q);
/// The sides packed as HyperbolicAddressMsg carries them.
std::vector<std::byte> pack_hyperbolic_address(std::span<const std::uint32_t> sides, std::uint32_t q);
/// The sides of a packed address (`levels` of them); no range checks (decode made them).
std::vector<std::uint32_t> unpack_hyperbolic_address(std::span<const std::byte> packed, std::uint32_t levels,
                                                     std::uint32_t q);

/// Messages between protocol vertices of the packing protocol (types 1–10, 17–21).
using PackingMessage = std::variant<DepthMsg, ElectionMsg, StartMsg, WaveMsg, RadiusMsg, PlacedMsg, ReportMsg,
                                    DecisionMsg, ShapeMsg, FaceCirclesMsg, KrylovValueMsg, KrylovSumMsg, KrylovDecisionMsg,
                                    GateRadiusMsg, HeightMsg>;
/// What a packing node sends a neighbour without the reliability layer (types 1–11, 17–21).
using PackingHop = std::variant<PackingMessage, RelayMsg>;
/// The reliability layer's messages on one link (types 13, 14).
using LinkMessage = std::variant<FrameMsg, AckMsg>;
/// What a FrameMsg carries (types 1–11, 15 and 17–21).
using FramePayload = std::variant<PackingHop, FailureMsg>;
/// Data packets of the forwarding schemes (types 12, 16).
using ForwardingMessage = std::variant<DataMsg, RouteMsg>;
/// The hyperbolic baseline's set-up (types 22–25).
using HyperbolicMessage = std::variant<HyperbolicSweepMsg, HyperbolicEchoMsg, HyperbolicRootMsg, HyperbolicAddressMsg>;
/// Any message; the alternatives are in type-code order (alternative k has type k + 1).
using Message = std::variant<DepthMsg, ElectionMsg, StartMsg, WaveMsg, RadiusMsg, PlacedMsg, ReportMsg, DecisionMsg,
                             ShapeMsg, FaceCirclesMsg, RelayMsg, DataMsg, FrameMsg, AckMsg, FailureMsg, RouteMsg,
                             KrylovValueMsg, KrylovSumMsg, KrylovDecisionMsg, GateRadiusMsg, HeightMsg,
                             HyperbolicSweepMsg,
                             HyperbolicEchoMsg, HyperbolicRootMsg, HyperbolicAddressMsg>;

namespace detail {
template <class T, class Variant>
struct IsAlternative;
template <class T, class... Ts>
struct IsAlternative<T, std::variant<Ts...>> : std::disjunction<std::is_same<T, Ts>...> {};
}  // namespace detail

/// Whether T is one of the message structs.
template <class T>
inline constexpr bool is_message_v = detail::IsAlternative<T, Message>::value;

/// The type byte of a message.
MessageType type_of(const Message& m);

/// Encoded size of a message of type `t`, header included: exact for fixed-size types, the fixed
/// part (up to and including the count) for FaceCirclesMsg, RelayMsg and FrameMsg; 0 for values outside the enum.
std::size_t encoded_size(MessageType t);

/// Exact encoded size of `m`, header included.
std::size_t encoded_size(const Message& m);

/// Outcome of decoding a byte string.
enum class DecodeStatus : std::uint8_t {
  ok,              ///< a valid message
  truncated,       ///< fewer bytes than the header or the type needs
  bad_version,     ///< byte 0 is not wire_version
  unknown_type,    ///< byte 1 is not a MessageType
  trailing_bytes,  ///< more bytes than the type needs
  out_of_range,    ///< a field outside its documented range
  foreign_type,    ///< byte 1 is a MessageType outside the message set decoded into
};

/// Number of DecodeStatus values (for per-status counters).
inline constexpr std::size_t decode_status_count = 7;

/// Name of a decode status ("ok", "truncated", …).
std::string_view to_string(DecodeStatus s);

/// Encodes message `m` (one of the 21 structs), replacing the contents of `out`.
template <class M>
  requires is_message_v<M>
void encode(const M& m, std::vector<std::byte>& out);
/// Encodes the message a message set holds, replacing the contents of `out`.
template <class... Ts>
void encode(const std::variant<Ts...>& m, std::vector<std::byte>& out) {
  std::visit([&](const auto& x) { encode(x, out); }, m);
}
/// Encodes `m` (a message or a message set) into a new buffer.
template <class M>
std::vector<std::byte> encode(const M& m) {
  std::vector<std::byte> out;
  encode(m, out);
  return out;
}

/// Decodes `bytes` as a message of the set; on `DecodeStatus::ok` stores it in `out`, otherwise leaves
/// `out` unchanged.
DecodeStatus decode(std::span<const std::byte> bytes, Message& out);
/// (As above, for a PackingMessage.)
DecodeStatus decode(std::span<const std::byte> bytes, PackingMessage& out);
/// (As above, for the one-message set {RadiusMsg}: the receive path's fast case, read in place with
/// no variant; a message of any other type is `foreign_type`.)
DecodeStatus decode(std::span<const std::byte> bytes, RadiusMsg& out);
/// (As above, for a PackingHop.)
DecodeStatus decode(std::span<const std::byte> bytes, PackingHop& out);
/// (As above, for a LinkMessage.)
DecodeStatus decode(std::span<const std::byte> bytes, LinkMessage& out);
/// (As above, for a FramePayload.)
DecodeStatus decode(std::span<const std::byte> bytes, FramePayload& out);
/// (As above, for a ForwardingMessage.)
DecodeStatus decode(std::span<const std::byte> bytes, ForwardingMessage& out);
/// (As above, for a HyperbolicMessage.)
DecodeStatus decode(std::span<const std::byte> bytes, HyperbolicMessage& out);

/// A RelayMsg whose payload is a view (of the bytes it was decoded from, or of the buffer it is
/// encoded from): how a relay forwards or opens an envelope without copying its payload. Same
/// wire format and ranges as RelayMsg.
struct RelayView {
  std::uint64_t face = 0;               ///< the face vertex's id
  std::uint64_t source = 0;             ///< sending protocol vertex
  std::uint64_t target = 0;             ///< receiving protocol vertex
  bool backward = false;                ///< direction round the face
  std::span<const std::byte> payload;   ///< the carried message, encoded
};
/// Encodes `m` as a RelayMsg (the bytes of encode(RelayMsg) with the same fields), replacing the
/// contents of `out`; `m.payload` must not lie in `out`.
void encode(const RelayView& m, std::vector<std::byte>& out);
/// Decodes `bytes` as a RelayMsg whose payload stays in `bytes`: the status decode(bytes, Message&)
/// gives (foreign_type for a message of another type); on DecodeStatus::ok stores it in `out`,
/// otherwise leaves `out` unchanged.
DecodeStatus decode(std::span<const std::byte> bytes, RelayView& out);

}  // namespace laguerre::protocols
