#pragma once
// Test helper shared by the forwarding suites: a hop-by-hop outcome as core::route names it.

#include "laguerre/core/routing/Routing.hpp"
#include "laguerre/protocols/Forwarding.hpp"

namespace laguerre::protocols::testing {

/// The core::RouteOutcome of the same name.
inline core::RouteOutcome as_core(PacketOutcome o) {
  switch (o) {
    case PacketOutcome::delivered: return core::RouteOutcome::delivered;
    case PacketOutcome::dead_end: return core::RouteOutcome::dead_end;
    case PacketOutcome::ttl_exceeded: return core::RouteOutcome::ttl_exceeded;
    case PacketOutcome::loop: return core::RouteOutcome::loop;
  }
  return core::RouteOutcome::dead_end;
}

}  // namespace laguerre::protocols::testing
