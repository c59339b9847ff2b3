#pragma once
// Checks shared by the codec tests.

#include <gtest/gtest.h>

#include <vector>

#include "laguerre/protocols/Codec.hpp"

namespace laguerre::protocols::testing {

// Every proper prefix of each sample's encoding decodes as truncated, and one byte more as trailing_bytes.
inline void expect_every_truncation_and_extension_rejected(const std::vector<Message>& samples) {
  for (const Message& m : samples) {
    std::vector<std::byte> b = encode(m);
    Message out;
    for (std::size_t len = 0; len < b.size(); ++len)
      EXPECT_EQ(decode(std::span(b).first(len), out), DecodeStatus::truncated) << to_string(type_of(m)) << " " << len;
    b.push_back(std::byte{0});
    EXPECT_EQ(decode(b, out), DecodeStatus::trailing_bytes) << to_string(type_of(m));
  }
}

}  // namespace laguerre::protocols::testing
