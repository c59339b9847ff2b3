// Fuzz harness: the message codec (protocols/Codec.hpp). Any byte string must decode safely; a decoded
// message must encode back to the same bytes with its documented size, and so must the messages that
// relays and frames carry.
#include <cstring>
#include <span>
#include <variant>
#include <vector>

#include "FuzzTarget.hpp"
#include "laguerre/protocols/Codec.hpp"

namespace {

using laguerre::protocols::DecodeStatus;
using laguerre::protocols::Message;

void check(std::span<const std::byte> bytes, int depth) {
  Message m;
  const DecodeStatus status = laguerre::protocols::decode(bytes, m);
  LAGUERRE_FUZZ_CHECK(static_cast<std::size_t>(status) < laguerre::protocols::decode_status_count);
  LAGUERRE_FUZZ_CHECK(!laguerre::protocols::to_string(status).empty());
  if (status != DecodeStatus::ok) return;
  const std::vector<std::byte> again = laguerre::protocols::encode(m);
  LAGUERRE_FUZZ_CHECK(again.size() == bytes.size() && std::memcmp(again.data(), bytes.data(), bytes.size()) == 0);
  LAGUERRE_FUZZ_CHECK(laguerre::protocols::encoded_size(m) == bytes.size());
  LAGUERRE_FUZZ_CHECK(static_cast<std::uint8_t>(laguerre::protocols::type_of(m)) == static_cast<std::uint8_t>(bytes[1]));
  if (depth > 0) return;
  if (const auto* relay = std::get_if<laguerre::protocols::RelayMsg>(&m)) check(relay->payload, depth + 1);
  if (const auto* frame = std::get_if<laguerre::protocols::FrameMsg>(&m)) check(frame->payload, depth + 1);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  check({reinterpret_cast<const std::byte*>(data), size}, 0);
  return 0;
}
