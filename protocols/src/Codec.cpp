#include "laguerre/protocols/Codec.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <iterator>
#include <utility>

namespace laguerre::protocols {

// ---- The layout of every message, once ----------------------------------------------------------
//
// `fields(ar, m)` lists the fields of a message in wire order, with their ranges: `ar(f1, f2, …)`
// visits fields (by their C++ type: u8, u32, u64, f64, bool as u8 ∈ {0, 1}; `code(e, lo, hi)` an enum
// as u8 in [lo, hi]; `counted(v, lo, hi)` a u32 count in [lo, hi] then that many items, bytes or
// structs with their own `fields`), and `require(condition)` states a range that involves several
// fields (only the reader evaluates it). The same description serves SizeArchive (counts bytes),
// WriteArchive (appends them) and ReadArchive (reads and checks them); the first two visit `const`
// messages, the reader mutable ones, hence the parameter `M`.

namespace {

template <class M, class T>
concept Is = std::is_same_v<std::remove_const_t<M>, T>;

template <class E>
struct Code {
  E& value;
  std::remove_const_t<E> lo, hi;
};
template <class E>
Code<E> code(E& value, std::remove_const_t<E> lo, std::remove_const_t<E> hi) {
  return {value, lo, hi};
}

template <class V>
struct Counted {
  V& items;
  std::uint32_t lo, hi;
};
template <class V>
Counted<V> counted(V& items, std::uint32_t lo, std::uint32_t hi) {
  return {items, lo, hi};
}

bool positive(double h) { return h > 0.0; }  // a hyperbolic radius: (0, ∞]; false for NaN
bool zero_bits(double v) { return std::bit_cast<std::uint64_t>(v) == 0; }
bool finite(double a, double b) { return std::isfinite(a) && std::isfinite(b); }

template <class Ar, Is<FaceCircle> M> void fields(Ar& ar, M& c) { ar(c.x, c.y, c.r); }
template <class Ar, Is<DepthMsg> M> void fields(Ar& ar, M& m) {
  ar(m.ack, m.depth, m.parent).require(m.depth <= DepthMsg::max_depth);
}
template <class Ar, Is<ElectionMsg> M> void fields(Ar& ar, M& m) {
  ar(code(m.stage, ElectionStage::report, ElectionStage::final), m.depth, m.id);
}
template <class Ar, Is<StartMsg> M> void fields(Ar& ar, M& m) { ar(m.root, m.first).require(m.root != m.first); }
template <class Ar, Is<WaveMsg> M> void fields(Ar& ar, M& m) { ar(m.seq, m.wave, m.parent).require(m.seq >= 1); }
template <class Ar, Is<RadiusMsg> M> void fields(Ar& ar, M& m) { ar(m.step, m.h).require(positive(m.h)); }
template <class Ar, Is<PlacedMsg> M> void fields(Ar& ar, M& m) {
  ar(m.round, m.h, m.centre_re, m.centre_im, m.cx, m.cy, m.cr).require(positive(m.h));
}
template <class Ar, Is<ReportMsg> M> void fields(Ar& ar, M& m) { ar(m.round, m.ok); }
template <class Ar, Is<DecisionMsg> M> void fields(Ar& ar, M& m) {
  ar(m.round, code(m.verdict, Verdict::next, Verdict::layout));
}
template <class Ar, Is<ShapeMsg> M> void fields(Ar& ar, M& m) { ar(m.down, m.polygon); }
template <class Ar, Is<HeightMsg> M> void fields(Ar& ar, M& m) { ar(m.down, m.height); }
template <class Ar, Is<FaceCirclesMsg> M> void fields(Ar& ar, M& m) {
  ar(m.round, counted(m.circles, 3, max_face_circles));
}
template <class Ar, class M>
  requires(Is<M, RelayMsg> || Is<M, RelayView>)
void fields(Ar& ar, M& m) {
  ar(m.face, m.source, m.target, m.backward, counted(m.payload, 2, max_relay_payload))
      .require(m.source != m.target && (m.face == m.source || m.face == m.target));
}
template <class Ar, Is<DataMsg> M> void fields(Ar& ar, M& m) {
  ar(m.packet, m.source, m.target, m.tx, m.ty, m.tr, m.ttl, m.hops)
      .require(m.hops >= 1 && m.hops <= m.ttl && m.source != m.target && finite(m.tx, m.ty) && std::isfinite(m.tr) &&
               m.tr >= 0);
}
template <class Ar, Is<FrameMsg> M> void fields(Ar& ar, M& m) {
  ar(m.seq, m.ack.next, m.ack.bits, counted(m.payload, 0, max_frame_payload));
}
template <class Ar, Is<AckMsg> M> void fields(Ar& ar, M& m) { ar(m.ack.next, m.ack.bits); }
template <class Ar, Is<FailureMsg> M> void fields(Ar& ar, M& m) { ar(m.suspect); }
template <class Ar, Is<KrylovValueMsg> M> void fields(Ar& ar, M& m) { ar(m.seq, m.value); }
template <class Ar, Is<KrylovSumMsg> M> void fields(Ar& ar, M& m) { ar(m.seq, m.s0, m.s1, m.s2, m.max); }
template <class Ar, Is<GateRadiusMsg> M> void fields(Ar& ar, M& m) { ar(m.step, m.h, m.gate).require(positive(m.h)); }
template <class Ar, Is<KrylovDecisionMsg> M> void fields(Ar& ar, M& m) {
  ar(m.seq, m.action, m.a, m.b).require(m.action <= 4);
}

// A packed address is canonical: its length fits the levels, every side is a side, unused bits are 0.
bool valid_address(const HyperbolicAddressMsg& m) {
  if (m.q < 3) return false;
  const std::size_t width = hyperbolic_address_width(m.q), bits = std::size_t{m.levels} * width;
  if (m.packed.size() != (bits + 7) / 8) return false;
  const std::vector<std::uint32_t> sides = unpack_hyperbolic_address(m.packed, m.levels, m.q);
  for (std::size_t k = 0; k < sides.size(); ++k)
    if (sides[k] >= m.q || (k > 0 && sides[k] == 0)) return false;
  return pack_hyperbolic_address(sides, m.q) == m.packed;
}
template <class Ar, Is<HyperbolicSweepMsg> M> void fields(Ar& ar, M& m) { ar(m.sweep, m.depth, m.parent).require(m.sweep <= 2); }
template <class Ar, Is<HyperbolicEchoMsg> M> void fields(Ar& ar, M& m) {
  ar(m.sweep, m.value, m.id).require(m.sweep <= 2 && (m.sweep < 2 || m.id == 0));
}
template <class Ar, Is<HyperbolicRootMsg> M> void fields(Ar& ar, M& m) {
  ar(m.stage, m.hops_left).require(m.stage <= 1 && (m.stage == 1 || m.hops_left == 0));
}
template <class Ar, Is<HyperbolicAddressMsg> M> void fields(Ar& ar, M& m) {
  // 2^24 levels bound the count before it sizes anything (a tree deeper than that is not a sensor field).
  ar(m.q, m.whose, m.levels, counted(m.packed, 0, 1u << 24));
  ar.require(m.whose <= 1 && m.levels < (1u << 24) && valid_address(m));
}

template <class Ar, Is<RouteMsg> M>
void fields(Ar& ar, M& m) {
  ar(m.packet, m.source, m.target, code(m.scheme, RouteScheme::greedy_euclid, RouteScheme::gfg), m.tx, m.ty, m.ttl,
     m.hops, m.perimeter, m.px, m.py, m.crossed, m.ax, m.ay, m.bx, m.by, m.walk_tail, m.walk_head);
  ar.require(m.hops >= 1 && m.hops <= m.ttl && m.source != m.target && finite(m.tx, m.ty));
  // Canonical: the fields a mode does not use are +0.
  const bool edge_zero = zero_bits(m.ax) && zero_bits(m.ay) && zero_bits(m.bx) && zero_bits(m.by);
  if (!m.perimeter)
    ar.require(zero_bits(m.px) && zero_bits(m.py) && !m.crossed && edge_zero && m.walk_tail == 0 && m.walk_head == 0);
  else
    ar.require(m.scheme == RouteScheme::gfg && finite(m.px, m.py) && m.walk_tail != m.walk_head &&
               (m.crossed ? finite(m.ax, m.ay) && finite(m.bx, m.by) : edge_zero));
}

// ---- Archives -------------------------------------------------------------------------------------

constexpr std::size_t header = 2;

// What every archive does with a list of fields: visit them in order.
template <class Ar>
class Archive {
public:
  template <class... F>
  Ar& operator()(F&&... f) {
    Ar& self = static_cast<Ar&>(*this);
    (self.field(f), ...);
    return self;
  }
};

// Counts bytes.
class SizeArchive : public Archive<SizeArchive> {
public:
  void field(std::uint8_t) { size_ += 1; }
  void field(bool) { size_ += 1; }
  void field(std::uint32_t) { size_ += 4; }
  void field(std::uint64_t) { size_ += 8; }
  void field(double) { size_ += 8; }
  template <class E>
  void field(const Code<E>&) {
    size_ += 1;
  }
  template <class V>
  void field(const Counted<V>& c);
  void require(bool) {}
  std::size_t size() const { return size_; }

private:
  std::size_t size_ = 0;
};

// Bytes of one item of a sequence.
template <class T>
std::size_t item_size() {
  if constexpr (std::is_same_v<T, std::byte>) {
    return 1;
  } else {
    SizeArchive s;
    const T item{};
    fields(s, item);
    return s.size();
  }
}

template <class V>
void SizeArchive::field(const Counted<V>& c) {
  size_ += 4 + c.items.size() * item_size<typename std::remove_const_t<V>::value_type>();
}

// Writes little-endian fields into a buffer SizeArchive has sized (no check, no reallocation).
class WriteArchive : public Archive<WriteArchive> {
public:
  explicit WriteArchive(std::byte* out) : out_(out) {}
  void field(std::uint8_t v) { *out_++ = static_cast<std::byte>(v); }
  void field(bool v) { *out_++ = v ? std::byte{1} : std::byte{0}; }
  void field(std::uint32_t v) { little_endian(v, 4); }
  void field(std::uint64_t v) { little_endian(v, 8); }
  void field(double v) { little_endian(std::bit_cast<std::uint64_t>(v), 8); }
  template <class E>
  void field(const Code<E>& c) {
    field(static_cast<std::uint8_t>(c.value));
  }
  template <class V>
  void field(const Counted<V>& c) {
    field(static_cast<std::uint32_t>(c.items.size()));
    using T = typename std::remove_const_t<V>::value_type;
    if constexpr (std::is_same_v<std::remove_const_t<T>, std::byte>) {
      if (!c.items.empty()) std::memcpy(out_, c.items.data(), c.items.size());
      out_ += c.items.size();
    } else {
      for (const T& item : c.items) fields(*this, item);
    }
  }
  void require(bool) {}

private:
  void little_endian(std::uint64_t v, std::size_t bytes) {
    if constexpr (std::endian::native == std::endian::little) {
      std::memcpy(out_, &v, bytes);
    } else {
      for (std::size_t i = 0; i < bytes; ++i) out_[i] = static_cast<std::byte>((v >> (8 * i)) & 0xffu);
    }
    out_ += bytes;
  }
  std::byte* out_;
};

// Reads little-endian fields, never past the end. The first structural fault (too few bytes, a count
// out of range) stops reading; status() then ranks the faults as `decode` documents.
class ReadArchive : public Archive<ReadArchive> {
public:
  explicit ReadArchive(std::span<const std::byte> in) : in_(in) {}
  void field(std::uint8_t& v) { v = static_cast<std::uint8_t>(take(1)); }
  void field(bool& v) {
    const std::uint64_t b = take(1);
    require(b <= 1);
    v = b == 1;
  }
  void field(std::uint32_t& v) { v = static_cast<std::uint32_t>(take(4)); }
  void field(std::uint64_t& v) { v = take(8); }
  void field(double& v) { v = std::bit_cast<double>(take(8)); }
  template <class E>
  void field(const Code<E>& c) {
    const auto b = static_cast<std::uint8_t>(take(1));
    require(b >= static_cast<std::uint8_t>(c.lo) && b <= static_cast<std::uint8_t>(c.hi));
    c.value = static_cast<E>(b);
  }
  template <class V>
  void field(const Counted<V>& c) {
    using T = typename V::value_type;
    const auto count = static_cast<std::uint32_t>(take(4));
    if (fault_ != DecodeStatus::ok) return;
    if (count < c.lo || count > c.hi) {
      fault_ = DecodeStatus::out_of_range;  // before the count sizes anything
      return;
    }
    if (in_.size() - pos_ < std::size_t{count} * item_size<T>()) {
      fault_ = DecodeStatus::truncated;
      return;
    }
    if constexpr (std::is_same_v<V, std::span<const std::byte>>) {
      c.items = in_.subspan(pos_, count);  // a view: no copy
      pos_ += count;
    } else if constexpr (std::is_same_v<T, std::byte>) {
      const auto first = in_.begin() + static_cast<std::ptrdiff_t>(pos_);
      c.items.assign(first, first + static_cast<std::ptrdiff_t>(count));
      pos_ += count;
    } else {
      c.items.resize(count);
      for (T& item : c.items) fields(*this, item);
    }
  }
  void require(bool condition) { in_range_ = in_range_ && condition; }

  DecodeStatus status() const {
    if (fault_ != DecodeStatus::ok) return fault_;
    if (pos_ < in_.size()) return DecodeStatus::trailing_bytes;
    return in_range_ ? DecodeStatus::ok : DecodeStatus::out_of_range;
  }

private:
  std::uint64_t take(std::size_t bytes) {
    if (fault_ != DecodeStatus::ok) return 0;
    if (in_.size() - pos_ < bytes) {
      fault_ = DecodeStatus::truncated;
      return 0;
    }
    std::uint64_t v = 0;
    if constexpr (std::endian::native == std::endian::little) {
      std::memcpy(&v, in_.data() + pos_, bytes);
    } else {
      for (std::size_t i = 0; i < bytes; ++i) v |= std::uint64_t{std::to_integer<std::uint8_t>(in_[pos_ + i])} << (8 * i);
    }
    pos_ += bytes;
    return v;
  }

  std::span<const std::byte> in_;
  std::size_t pos_ = 0;
  DecodeStatus fault_ = DecodeStatus::ok;
  bool in_range_ = true;
};

// ---- Message sets -----------------------------------------------------------------------------------

// Type code of a message struct: its position in Message, plus one.
template <class T, std::size_t I = 0>
constexpr std::uint8_t code_of() {
  if constexpr (std::is_same_v<T, std::variant_alternative_t<I, Message>>) return static_cast<std::uint8_t>(I + 1);
  else return code_of<T, I + 1>();
}

// Whether message T belongs to set S (S itself, or a variant of sets, to any depth).
template <class T, class S>
struct InSet : std::is_same<T, S> {};
template <class T, class... S>
struct InSet<T, std::variant<S...>> : std::disjunction<InSet<T, S>...> {};

// Stores message `m` in `out`: a T, or a set, in whose first alternative that contains T it goes.
template <class T>
void place(T& out, T&& m) {
  out = std::move(m);
}
template <class T, class... A>
void place(std::variant<A...>& out, T&& m) {
  constexpr std::size_t k = [] {
    constexpr bool contains[] = {InSet<T, A>::value...};
    std::size_t i = 0;
    while (!contains[i]) ++i;
    return i;
  }();
  place(out.template emplace<k>(), std::move(m));
}

// Calls f.template operator()<T>() for the message struct T whose type code is `code` (1 … max_message_type).
template <class F>
void with_message_type(std::uint8_t code, F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    ((code == I + 1 ? f.template operator()<std::variant_alternative_t<I, Message>>() : void()), ...);
  }(std::make_index_sequence<std::variant_size_v<Message>>{});
}

// The header's status (ok: a known type, whose code is then in `code`).
DecodeStatus header_status(std::span<const std::byte> bytes, std::uint8_t& code) {
  if (bytes.size() < header) return DecodeStatus::truncated;
  if (std::to_integer<std::uint8_t>(bytes[0]) != wire_version) return DecodeStatus::bad_version;
  code = std::to_integer<std::uint8_t>(bytes[1]);
  if (code < 1 || code > max_message_type) return DecodeStatus::unknown_type;
  return DecodeStatus::ok;
}

template <class Set>
DecodeStatus decode_set(std::span<const std::byte> bytes, Set& out) {
  std::uint8_t code = 0;
  if (const DecodeStatus h = header_status(bytes, code); h != DecodeStatus::ok) return h;
  DecodeStatus status = DecodeStatus::foreign_type;
  with_message_type(code, [&]<class T>() {
    if constexpr (InSet<T, Set>::value) {
      T m;
      ReadArchive r(bytes.subspan(header));
      fields(r, m);
      status = r.status();
      if (status == DecodeStatus::ok) place(out, std::move(m));
    }
  });
  return status;
}

}  // namespace

// ---- Public interface ---------------------------------------------------------------------------------

std::string_view to_string(MessageType t) {
  static constexpr std::string_view names[] = {"?",      "depth",        "election", "start", "wave",  "radius",
                                               "placed", "report",       "decision", "shape", "face_circles",
                                               "relay",  "data",         "frame",    "ack",   "failure", "route",
                                               "krylov_value", "krylov_sum", "krylov_decision", "gate_radius", "height",
                                               "hyperbolic_sweep", "hyperbolic_echo", "hyperbolic_root",
                                               "hyperbolic_address"};
  static_assert(std::size(names) == max_message_type + 1);
  const auto code = static_cast<std::size_t>(t);
  return code <= max_message_type ? names[code] : names[0];
}

std::string_view to_string(DecodeStatus s) {
  static constexpr std::string_view names[] = {"ok",           "truncated",    "bad_version", "unknown_type",
                                               "trailing_bytes", "out_of_range", "foreign_type"};
  static_assert(std::size(names) == decode_status_count);
  const auto i = static_cast<std::size_t>(s);
  return i < decode_status_count ? names[i] : "?";
}

bool same_bits(const PlacedMsg& a, const PlacedMsg& b) {
  auto eq = [](double u, double v) { return std::bit_cast<std::uint64_t>(u) == std::bit_cast<std::uint64_t>(v); };
  return a.round == b.round && eq(a.h, b.h) && eq(a.centre_re, b.centre_re) && eq(a.centre_im, b.centre_im) &&
         eq(a.cx, b.cx) && eq(a.cy, b.cy) && eq(a.cr, b.cr);
}

bool same_bits(const FaceCirclesMsg& a, const FaceCirclesMsg& b) {
  auto eq = [](double u, double v) { return std::bit_cast<std::uint64_t>(u) == std::bit_cast<std::uint64_t>(v); };
  if (a.round != b.round || a.circles.size() != b.circles.size()) return false;
  for (std::size_t i = 0; i < a.circles.size(); ++i)
    if (!eq(a.circles[i].x, b.circles[i].x) || !eq(a.circles[i].y, b.circles[i].y) || !eq(a.circles[i].r, b.circles[i].r))
      return false;
  return true;
}

MessageType type_of(const Message& m) { return static_cast<MessageType>(m.index() + 1); }

std::size_t encoded_size(MessageType t) {
  std::size_t size = 0;
  with_message_type(static_cast<std::uint8_t>(t), [&]<class T>() {
    SizeArchive s;
    const T empty{};  // variable-size messages: the fixed part, up to and including the count
    fields(s, empty);
    size = header + s.size();
  });
  return size;
}

std::size_t encoded_size(const Message& m) {
  return std::visit(
      [](const auto& msg) {
        SizeArchive s;
        fields(s, msg);
        return header + s.size();
      },
      m);
}

namespace {
// Encodes the fields of `m` under type code `code`, replacing the contents of `out`.
template <class M>
void encode_as(std::uint8_t code, const M& m, std::vector<std::byte>& out) {
  SizeArchive s;
  fields(s, m);
  out.resize(header + s.size());  // keeps the capacity: no allocation once the buffer has grown
  WriteArchive w(out.data());
  w(wire_version, code);
  fields(w, m);
}
}  // namespace

template <class M>
  requires is_message_v<M>
void encode(const M& m, std::vector<std::byte>& out) {
  encode_as(code_of<M>(), m, out);
}

template void encode(const DepthMsg&, std::vector<std::byte>&);
template void encode(const ElectionMsg&, std::vector<std::byte>&);
template void encode(const StartMsg&, std::vector<std::byte>&);
template void encode(const WaveMsg&, std::vector<std::byte>&);
template void encode(const RadiusMsg&, std::vector<std::byte>&);
template void encode(const PlacedMsg&, std::vector<std::byte>&);
template void encode(const ReportMsg&, std::vector<std::byte>&);
template void encode(const DecisionMsg&, std::vector<std::byte>&);
template void encode(const ShapeMsg&, std::vector<std::byte>&);
template void encode(const FaceCirclesMsg&, std::vector<std::byte>&);
template void encode(const RelayMsg&, std::vector<std::byte>&);
template void encode(const DataMsg&, std::vector<std::byte>&);
template void encode(const FrameMsg&, std::vector<std::byte>&);
template void encode(const AckMsg&, std::vector<std::byte>&);
template void encode(const FailureMsg&, std::vector<std::byte>&);
template void encode(const RouteMsg&, std::vector<std::byte>&);
template void encode(const KrylovValueMsg&, std::vector<std::byte>&);
template void encode(const KrylovSumMsg&, std::vector<std::byte>&);
template void encode(const KrylovDecisionMsg&, std::vector<std::byte>&);
template void encode(const GateRadiusMsg&, std::vector<std::byte>&);
template void encode(const HeightMsg&, std::vector<std::byte>&);
template void encode(const HyperbolicSweepMsg&, std::vector<std::byte>&);
template void encode(const HyperbolicEchoMsg&, std::vector<std::byte>&);
template void encode(const HyperbolicRootMsg&, std::vector<std::byte>&);
template void encode(const HyperbolicAddressMsg&, std::vector<std::byte>&);

std::size_t hyperbolic_address_width(std::uint32_t q) {
  std::size_t width = 0;
  while ((std::size_t{1} << width) < q) ++width;
  return width;
}

std::vector<std::byte> pack_hyperbolic_address(std::span<const std::uint32_t> sides, std::uint32_t q) {
  const std::size_t width = hyperbolic_address_width(q);
  std::vector<std::byte> out((sides.size() * width + 7) / 8, std::byte{0});
  for (std::size_t k = 0; k < sides.size(); ++k)
    for (std::size_t b = 0; b < width; ++b)
      if ((sides[k] >> b) & 1u) out[(k * width + b) / 8] |= std::byte{static_cast<std::uint8_t>(1u << ((k * width + b) % 8))};
  return out;
}

std::vector<std::uint32_t> unpack_hyperbolic_address(std::span<const std::byte> packed, std::uint32_t levels,
                                                     std::uint32_t q) {
  const std::size_t width = hyperbolic_address_width(q);
  std::vector<std::uint32_t> sides(levels, 0);
  for (std::size_t k = 0; k < levels; ++k)
    for (std::size_t b = 0; b < width; ++b) {
      const std::size_t bit = k * width + b;
      if (bit / 8 < packed.size() && (std::to_integer<std::uint8_t>(packed[bit / 8]) >> (bit % 8)) & 1u)
        sides[k] |= 1u << b;
    }
  return sides;
}

void encode(const RelayView& m, std::vector<std::byte>& out) { encode_as(code_of<RelayMsg>(), m, out); }

DecodeStatus decode(std::span<const std::byte> bytes, RelayView& out) {
  std::uint8_t code = 0;
  if (const DecodeStatus h = header_status(bytes, code); h != DecodeStatus::ok) return h;
  if (code != code_of<RelayMsg>()) return DecodeStatus::foreign_type;
  RelayView m;
  ReadArchive r(bytes.subspan(header));
  fields(r, m);
  const DecodeStatus status = r.status();
  if (status == DecodeStatus::ok) out = m;
  return status;
}

DecodeStatus decode(std::span<const std::byte> bytes, Message& out) { return decode_set(bytes, out); }
DecodeStatus decode(std::span<const std::byte> bytes, PackingMessage& out) { return decode_set(bytes, out); }
DecodeStatus decode(std::span<const std::byte> bytes, RadiusMsg& out) { return decode_set(bytes, out); }
DecodeStatus decode(std::span<const std::byte> bytes, PackingHop& out) { return decode_set(bytes, out); }
DecodeStatus decode(std::span<const std::byte> bytes, LinkMessage& out) { return decode_set(bytes, out); }
DecodeStatus decode(std::span<const std::byte> bytes, FramePayload& out) { return decode_set(bytes, out); }
DecodeStatus decode(std::span<const std::byte> bytes, ForwardingMessage& out) { return decode_set(bytes, out); }
DecodeStatus decode(std::span<const std::byte> bytes, HyperbolicMessage& out) { return decode_set(bytes, out); }

}  // namespace laguerre::protocols
