#pragma once
// A Runtime that does nothing: for tests that only construct nodes or feed them messages by hand.

#include "laguerre/protocols/Runtime.hpp"

namespace laguerre::protocols::testing {

/// Ignores every send and timer; self() is 1.
struct NullRuntime final : Runtime {
  NodeId self() const override { return 1; }
  Time now() const override { return 0; }
  void send(NodeId, std::span<const std::byte>) override {}
  void broadcast(std::span<const std::byte>) override {}
  TimerHandle schedule(Duration, TimerId) override { return 1; }
  bool cancel(TimerHandle) override { return false; }
  std::uint64_t random_u64() override { return 4; }
};

}  // namespace laguerre::protocols::testing
