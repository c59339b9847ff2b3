#include "laguerre/sim/Trace.hpp"

#include <ostream>

namespace laguerre::sim {

namespace {
template <class T>
std::byte* put_le(std::byte* out, T value) {
  auto bits = static_cast<std::uint64_t>(value);
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    *out++ = static_cast<std::byte>(bits & 0xff);
    bits >>= 8;
  }
  return out;
}
}  // namespace

std::array<std::byte, 38> Trace::encode(const TraceRecord& r) {
  std::array<std::byte, 38> bytes{};
  std::byte* p = bytes.data();
  p = put_le(p, r.time);
  p = put_le(p, r.from);
  p = put_le(p, r.to);
  p = put_le(p, r.phase);
  p = put_le(p, r.size);
  put_le(p, r.digest);
  return bytes;
}

void Trace::add(const TraceRecord& record) {
  if (mode_ == TraceMode::off) return;
  const auto bytes = encode(record);
  hash_ = fnv1a(bytes, hash_);
  ++count_;
  if (mode_ == TraceMode::records) records_.push_back(record);
}

void Trace::write_csv(std::ostream& out) const {
  out << "time_ns,from,to,phase,size,digest\n";
  for (const TraceRecord& r : records_) {
    out << r.time << ',' << r.from << ',' << r.to << ',' << r.phase << ',' << r.size << ','
        << r.digest << '\n';
  }
}

void Trace::write_binary(std::ostream& out) const {
  out.write("LGTRACE1", 8);
  std::array<std::byte, 8> n{};
  put_le(n.data(), static_cast<std::uint64_t>(records_.size()));
  out.write(reinterpret_cast<const char*>(n.data()), 8);
  for (const TraceRecord& r : records_) {
    const auto bytes = encode(r);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }
}

}  // namespace laguerre::sim
