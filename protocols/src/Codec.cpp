#include "laguerre/protocols/Codec.hpp"

#include <bit>
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

bool unit_interval(double x) { return x >= 0.0 && x <= 1.0; }  // false for NaN

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
  return a.round == b.round && eq(a.x, b.x) && eq(a.centre_re, b.centre_re) && eq(a.centre_im, b.centre_im) &&
         eq(a.cx, b.cx) && eq(a.cy, b.cy) && eq(a.cr, b.cr);
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
        else return MessageType::decision;
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
  }
  return 0;
}

void encode(const Message& m, std::vector<std::byte>& out) {
  out.clear();
  const MessageType t = type_of(m);
  out.reserve(encoded_size(t));
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
          w.f64(msg.x);
        } else if constexpr (std::is_same_v<T, PlacedMsg>) {
          w.u32(msg.round);
          w.f64(msg.x);
          w.f64(msg.centre_re);
          w.f64(msg.centre_im);
          w.f64(msg.cx);
          w.f64(msg.cy);
          w.f64(msg.cr);
        } else if constexpr (std::is_same_v<T, ReportMsg>) {
          w.u32(msg.round);
          w.u8(msg.ok ? 1 : 0);
        } else {
          w.u32(msg.round);
          w.u8(static_cast<std::uint8_t>(msg.verdict));
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
  if (type_byte < 1 || type_byte > 8) return DecodeStatus::unknown_type;
  const auto t = static_cast<MessageType>(type_byte);
  const std::size_t size = encoded_size(t);
  if (bytes.size() < size) return DecodeStatus::truncated;
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
      rm.x = r.f64();
      ok = unit_interval(rm.x);
      m = rm;
      break;
    }
    case MessageType::placed: {
      PlacedMsg p;
      p.round = r.u32();
      p.x = r.f64();
      p.centre_re = r.f64();
      p.centre_im = r.f64();
      p.cx = r.f64();
      p.cy = r.f64();
      p.cr = r.f64();
      ok = unit_interval(p.x);
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
  }
  if (!ok) return DecodeStatus::out_of_range;
  out = m;
  return DecodeStatus::ok;
}

}  // namespace laguerre::protocols
