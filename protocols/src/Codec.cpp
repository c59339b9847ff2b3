#include "laguerre/protocols/Codec.hpp"

#include <bit>
#include <cmath>
#include <utility>
#include <type_traits>

namespace laguerre::protocols {

namespace {

// Appends little-endian fields to a byte vector.
class Writer {
public:
  explicit Writer(std::vector<std::byte>& out) : out_(out) {}
  void u8(std::uint8_t v) { out_.push_back(static_cast<std::byte>(v)); }
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out_.push_back(static_cast<std::byte>((v >> (8 * i)) & 0xffu));
  }
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) out_.push_back(static_cast<std::byte>((v >> (8 * i)) & 0xffu));
  }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  void bytes(std::span<const std::byte> b) { out_.insert(out_.end(), b.begin(), b.end()); }

private:
  std::vector<std::byte>& out_;
};

// Reads little-endian fields; the caller has checked the total length, so reads never overrun.
class Reader {
public:
  explicit Reader(std::span<const std::byte> in) : in_(in) {}
  std::uint8_t u8() { return std::to_integer<std::uint8_t>(in_[pos_++]); }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= std::uint32_t{std::to_integer<std::uint8_t>(in_[pos_++])} << (8 * i);
    return v;
  }
  std::uint64_t u64() {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= std::uint64_t{std::to_integer<std::uint8_t>(in_[pos_++])} << (8 * i);
    return v;
  }
  double f64() { return std::bit_cast<double>(u64()); }
  std::span<const std::byte> rest() const { return in_.subspan(pos_); }

private:
  std::span<const std::byte> in_;
  std::size_t pos_ = 0;
};

constexpr std::size_t header = 2;

// A boolean field must be 0 or 1; anything else is out of range.
bool read_bool(Reader& r, bool& ok) {
  const std::uint8_t b = r.u8();
  if (b > 1) ok = false;
  return b == 1;
}

bool hyperbolic_radius(double h) { return h > 0.0; }  // (0, ∞]; false for NaN

}  // namespace

std::string_view to_string(MessageType t) {
  switch (t) {
    case MessageType::depth: return "depth";
    case MessageType::election: return "election";
    case MessageType::start: return "start";
    case MessageType::wave: return "wave";
    case MessageType::radius: return "radius";
    case MessageType::placed: return "placed";
    case MessageType::report: return "report";
    case MessageType::decision: return "decision";
    case MessageType::shape: return "shape";
    case MessageType::face_circles: return "face_circles";
    case MessageType::relay: return "relay";
    case MessageType::data: return "data";
    case MessageType::frame: return "frame";
    case MessageType::ack: return "ack";
    case MessageType::failure: return "failure";
    case MessageType::route: return "route";
  }
  return "?";
}

std::string_view to_string(DecodeStatus s) {
  switch (s) {
    case DecodeStatus::ok: return "ok";
    case DecodeStatus::truncated: return "truncated";
    case DecodeStatus::bad_version: return "bad_version";
    case DecodeStatus::unknown_type: return "unknown_type";
    case DecodeStatus::trailing_bytes: return "trailing_bytes";
    case DecodeStatus::out_of_range: return "out_of_range";
  }
  return "?";
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

MessageType type_of(const Message& m) {
  return std::visit(
      [](const auto& msg) -> MessageType {
        using T = std::decay_t<decltype(msg)>;
        if constexpr (std::is_same_v<T, DepthMsg>) return MessageType::depth;
        else if constexpr (std::is_same_v<T, ElectionMsg>) return MessageType::election;
        else if constexpr (std::is_same_v<T, StartMsg>) return MessageType::start;
        else if constexpr (std::is_same_v<T, WaveMsg>) return MessageType::wave;
        else if constexpr (std::is_same_v<T, RadiusMsg>) return MessageType::radius;
        else if constexpr (std::is_same_v<T, PlacedMsg>) return MessageType::placed;
        else if constexpr (std::is_same_v<T, ReportMsg>) return MessageType::report;
        else if constexpr (std::is_same_v<T, DecisionMsg>) return MessageType::decision;
        else if constexpr (std::is_same_v<T, ShapeMsg>) return MessageType::shape;
        else if constexpr (std::is_same_v<T, FaceCirclesMsg>) return MessageType::face_circles;
        else if constexpr (std::is_same_v<T, RelayMsg>) return MessageType::relay;
        else if constexpr (std::is_same_v<T, DataMsg>) return MessageType::data;
        else if constexpr (std::is_same_v<T, FrameMsg>) return MessageType::frame;
        else if constexpr (std::is_same_v<T, AckMsg>) return MessageType::ack;
        else if constexpr (std::is_same_v<T, FailureMsg>) return MessageType::failure;
        else return MessageType::route;
      },
      m);
}

std::size_t encoded_size(MessageType t) {
  switch (t) {
    case MessageType::depth: return header + 4 + 1;
    case MessageType::election: return header + 4 + 8;
    case MessageType::start: return header + 8 + 8;
    case MessageType::wave: return header + 4 + 1 + 8;
    case MessageType::radius: return header + 4 + 8;
    case MessageType::placed: return header + 4 + 6 * 8;
    case MessageType::report: return header + 4 + 1;
    case MessageType::decision: return header + 4 + 1;
    case MessageType::shape: return header + 1 + 1;
    case MessageType::face_circles: return header + 4 + 4;  // + 24 per circle
    case MessageType::relay: return header + 3 * 8 + 1 + 4;  // + 1 per payload byte
    case MessageType::data: return header + 3 * 8 + 3 * 8 + 4 + 4;
    case MessageType::frame: return header + 4 + 4 + 8 + 4;  // + 1 per payload byte
    case MessageType::ack: return header + 4 + 8;
    case MessageType::failure: return header + 8;
    case MessageType::route: return header + 3 * 8 + 1 + 2 * 8 + 4 + 4 + 1 + 2 * 8 + 1 + 4 * 8 + 2 * 8;
  }
  return 0;
}

std::size_t encoded_size(const Message& m) {
  const std::size_t fixed = encoded_size(type_of(m));
  if (const auto* f = std::get_if<FaceCirclesMsg>(&m)) return fixed + 24 * f->circles.size();
  if (const auto* r = std::get_if<RelayMsg>(&m)) return fixed + r->payload.size();
  if (const auto* f = std::get_if<FrameMsg>(&m)) return fixed + f->payload.size();
  return fixed;
}

void encode(const Message& m, std::vector<std::byte>& out) {
  out.clear();
  const MessageType t = type_of(m);
  out.reserve(encoded_size(m));
  Writer w(out);
  w.u8(wire_version);
  w.u8(static_cast<std::uint8_t>(t));
  std::visit(
      [&](const auto& msg) {
        using T = std::decay_t<decltype(msg)>;
        if constexpr (std::is_same_v<T, DepthMsg>) {
          w.u32(msg.pulse);
          w.u8(msg.final ? 1 : 0);
        } else if constexpr (std::is_same_v<T, ElectionMsg>) {
          w.u32(msg.depth);
          w.u64(msg.id);
        } else if constexpr (std::is_same_v<T, StartMsg>) {
          w.u64(msg.root);
          w.u64(msg.first);
        } else if constexpr (std::is_same_v<T, WaveMsg>) {
          w.u32(msg.pulse);
          w.u8(msg.placed ? 1 : 0);
          w.u64(msg.parent);
        } else if constexpr (std::is_same_v<T, RadiusMsg>) {
          w.u32(msg.step);
          w.f64(msg.h);
        } else if constexpr (std::is_same_v<T, PlacedMsg>) {
          w.u32(msg.round);
          w.f64(msg.h);
          w.f64(msg.centre_re);
          w.f64(msg.centre_im);
          w.f64(msg.cx);
          w.f64(msg.cy);
          w.f64(msg.cr);
        } else if constexpr (std::is_same_v<T, ReportMsg>) {
          w.u32(msg.round);
          w.u8(msg.ok ? 1 : 0);
        } else if constexpr (std::is_same_v<T, DecisionMsg>) {
          w.u32(msg.round);
          w.u8(static_cast<std::uint8_t>(msg.verdict));
        } else if constexpr (std::is_same_v<T, ShapeMsg>) {
          w.u8(msg.down ? 1 : 0);
          w.u8(msg.polygon ? 1 : 0);
        } else if constexpr (std::is_same_v<T, FaceCirclesMsg>) {
          w.u32(msg.round);
          w.u32(static_cast<std::uint32_t>(msg.circles.size()));
          for (const FaceCircle& c : msg.circles) {
            w.f64(c.x);
            w.f64(c.y);
            w.f64(c.r);
          }
        } else if constexpr (std::is_same_v<T, DataMsg>) {
          w.u64(msg.packet);
          w.u64(msg.source);
          w.u64(msg.target);
          w.f64(msg.tx);
          w.f64(msg.ty);
          w.f64(msg.tr);
          w.u32(msg.ttl);
          w.u32(msg.hops);
        } else if constexpr (std::is_same_v<T, FrameMsg>) {
          w.u32(msg.seq);
          w.u32(msg.ack.next);
          w.u64(msg.ack.bits);
          w.u32(static_cast<std::uint32_t>(msg.payload.size()));
          w.bytes(msg.payload);
        } else if constexpr (std::is_same_v<T, AckMsg>) {
          w.u32(msg.ack.next);
          w.u64(msg.ack.bits);
        } else if constexpr (std::is_same_v<T, FailureMsg>) {
          w.u64(msg.suspect);
        } else if constexpr (std::is_same_v<T, RouteMsg>) {
          w.u64(msg.packet);
          w.u64(msg.source);
          w.u64(msg.target);
          w.u8(static_cast<std::uint8_t>(msg.scheme));
          w.f64(msg.tx);
          w.f64(msg.ty);
          w.u32(msg.ttl);
          w.u32(msg.hops);
          w.u8(msg.perimeter ? 1 : 0);
          w.f64(msg.px);
          w.f64(msg.py);
          w.u8(msg.crossed ? 1 : 0);
          w.f64(msg.ax);
          w.f64(msg.ay);
          w.f64(msg.bx);
          w.f64(msg.by);
          w.u64(msg.walk_tail);
          w.u64(msg.walk_head);
        } else {
          w.u64(msg.face);
          w.u64(msg.source);
          w.u64(msg.target);
          w.u8(msg.backward ? 1 : 0);
          w.u32(static_cast<std::uint32_t>(msg.payload.size()));
          w.bytes(msg.payload);
        }
      },
      m);
}

std::vector<std::byte> encode(const Message& m) {
  std::vector<std::byte> out;
  encode(m, out);
  return out;
}

DecodeStatus decode(std::span<const std::byte> bytes, Message& out) {
  if (bytes.size() < header) return DecodeStatus::truncated;
  if (std::to_integer<std::uint8_t>(bytes[0]) != wire_version) return DecodeStatus::bad_version;
  const std::uint8_t type_byte = std::to_integer<std::uint8_t>(bytes[1]);
  if (type_byte < 1 || type_byte > max_message_type) return DecodeStatus::unknown_type;
  const auto t = static_cast<MessageType>(type_byte);
  std::size_t size = encoded_size(t);
  if (bytes.size() < size) return DecodeStatus::truncated;
  if (t == MessageType::face_circles || t == MessageType::relay || t == MessageType::frame) {
    // The count is the last u32 of the fixed part; check its range before it sizes anything.
    Reader c(bytes.subspan(size - 4, 4));
    const std::uint32_t count = c.u32();
    const bool circles = t == MessageType::face_circles;
    const bool in_range = circles                      ? count >= 3 && count <= max_face_circles
                          : t == MessageType::relay    ? count >= 2 && count <= max_relay_payload
                                                       : count <= max_frame_payload;
    if (!in_range) return DecodeStatus::out_of_range;
    size += (circles ? 24 : 1) * std::size_t{count};
    if (bytes.size() < size) return DecodeStatus::truncated;
  }
  if (bytes.size() > size) return DecodeStatus::trailing_bytes;
  Reader r(bytes.subspan(header));
  bool ok = true;
  Message m;
  switch (t) {
    case MessageType::depth: {
      DepthMsg d;
      d.pulse = r.u32();
      d.final = read_bool(r, ok);
      m = d;
      break;
    }
    case MessageType::election: {
      ElectionMsg e;
      e.depth = r.u32();
      e.id = r.u64();
      m = e;
      break;
    }
    case MessageType::start: {
      StartMsg s;
      s.root = r.u64();
      s.first = r.u64();
      ok = s.root != s.first;
      m = s;
      break;
    }
    case MessageType::wave: {
      WaveMsg w;
      w.pulse = r.u32();
      w.placed = read_bool(r, ok);
      w.parent = r.u64();
      if (!w.placed && w.parent != 0) ok = false;
      m = w;
      break;
    }
    case MessageType::radius: {
      RadiusMsg rm;
      rm.step = r.u32();
      rm.h = r.f64();
      ok = hyperbolic_radius(rm.h);
      m = rm;
      break;
    }
    case MessageType::placed: {
      PlacedMsg p;
      p.round = r.u32();
      p.h = r.f64();
      p.centre_re = r.f64();
      p.centre_im = r.f64();
      p.cx = r.f64();
      p.cy = r.f64();
      p.cr = r.f64();
      ok = hyperbolic_radius(p.h);
      m = p;
      break;
    }
    case MessageType::report: {
      ReportMsg rep;
      rep.round = r.u32();
      rep.ok = read_bool(r, ok);
      m = rep;
      break;
    }
    case MessageType::decision: {
      DecisionMsg dm;
      dm.round = r.u32();
      const std::uint8_t v = r.u8();
      if (v > 2) ok = false;
      dm.verdict = static_cast<Verdict>(v);
      m = dm;
      break;
    }
    case MessageType::shape: {
      ShapeMsg sm;
      sm.down = read_bool(r, ok);
      sm.polygon = read_bool(r, ok);
      m = sm;
      break;
    }
    case MessageType::face_circles: {
      FaceCirclesMsg fc;
      fc.round = r.u32();
      fc.circles.resize(r.u32());  // range-checked above
      for (FaceCircle& c : fc.circles) {
        c.x = r.f64();
        c.y = r.f64();
        c.r = r.f64();
      }
      m = std::move(fc);
      break;
    }
    case MessageType::relay: {
      RelayMsg rm;
      rm.face = r.u64();
      rm.source = r.u64();
      rm.target = r.u64();
      rm.backward = read_bool(r, ok);
      const std::uint32_t count = r.u32();  // range-checked above
      const std::span<const std::byte> rest = r.rest();
      rm.payload.assign(rest.begin(), rest.begin() + count);
      if (rm.source == rm.target || (rm.face != rm.source && rm.face != rm.target)) ok = false;
      m = std::move(rm);
      break;
    }
    case MessageType::data: {
      DataMsg d;
      d.packet = r.u64();
      d.source = r.u64();
      d.target = r.u64();
      d.tx = r.f64();
      d.ty = r.f64();
      d.tr = r.f64();
      d.ttl = r.u32();
      d.hops = r.u32();
      ok = d.hops >= 1 && d.hops <= d.ttl && d.source != d.target && std::isfinite(d.tx) && std::isfinite(d.ty) &&
           std::isfinite(d.tr) && d.tr >= 0;
      m = d;
      break;
    }
    case MessageType::frame: {
      FrameMsg f;
      f.seq = r.u32();
      f.ack.next = r.u32();
      f.ack.bits = r.u64();
      const std::uint32_t count = r.u32();  // range-checked above
      const std::span<const std::byte> rest = r.rest();
      f.payload.assign(rest.begin(), rest.begin() + count);
      m = std::move(f);
      break;
    }
    case MessageType::ack: {
      AckMsg a;
      a.ack.next = r.u32();
      a.ack.bits = r.u64();
      m = a;
      break;
    }
    case MessageType::failure: {
      m = FailureMsg{r.u64()};
      break;
    }
    case MessageType::route: {
      RouteMsg d;
      d.packet = r.u64();
      d.source = r.u64();
      d.target = r.u64();
      const std::uint8_t scheme = r.u8();
      d.scheme = static_cast<RouteScheme>(scheme);
      d.tx = r.f64();
      d.ty = r.f64();
      d.ttl = r.u32();
      d.hops = r.u32();
      d.perimeter = read_bool(r, ok);
      d.px = r.f64();
      d.py = r.f64();
      d.crossed = read_bool(r, ok);
      d.ax = r.f64();
      d.ay = r.f64();
      d.bx = r.f64();
      d.by = r.f64();
      d.walk_tail = r.u64();
      d.walk_head = r.u64();
      auto zero = [](double v) { return std::bit_cast<std::uint64_t>(v) == 0; };
      const bool edge_zero = zero(d.ax) && zero(d.ay) && zero(d.bx) && zero(d.by);
      const bool edge_finite = std::isfinite(d.ax) && std::isfinite(d.ay) && std::isfinite(d.bx) && std::isfinite(d.by);
      ok = ok && scheme >= 1 && scheme <= 3 && d.hops >= 1 && d.hops <= d.ttl && d.source != d.target &&
           std::isfinite(d.tx) && std::isfinite(d.ty);
      if (!d.perimeter)
        ok = ok && zero(d.px) && zero(d.py) && !d.crossed && edge_zero && d.walk_tail == 0 && d.walk_head == 0;
      else
        ok = ok && d.scheme == RouteScheme::gfg && std::isfinite(d.px) && std::isfinite(d.py) &&
             d.walk_tail != d.walk_head && (d.crossed ? edge_finite : edge_zero);
      m = d;
      break;
    }
  }
  if (!ok) return DecodeStatus::out_of_range;
  out = std::move(m);
  return DecodeStatus::ok;
}

}  // namespace laguerre::protocols
