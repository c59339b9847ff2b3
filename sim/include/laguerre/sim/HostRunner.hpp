#pragma once
/// @file
/// How a SimHost is run to its end and its results read back: in place (InPlaceRunner), or split
/// across MPI ranks (sim/mpi's MpiHostRunner), behind one interface so that the wiring code
/// (scenarios/ProtocolRun) does not depend on MPI.

#include <cstddef>
#include <functional>
#include <vector>

#include "laguerre/sim/SimHost.hpp"

namespace laguerre::sim {

/// Runs hosts and reads back every node's traffic and results (on every process).
class HostRunner {
public:
  /// Per-node result bytes, evaluated where the node lives.
  using Describe = std::function<std::vector<std::byte>(NodeIndex)>;
  virtual ~HostRunner() = default;
  /// Which nodes of `network` this process will run next (one flag per node; empty: every node), so
  /// that the host of the next run builds only those (SimHost's `held`). Optional: a host built
  /// whole runs too. The default: every node.
  virtual std::vector<std::uint8_t> ownership(const Network& /*network*/) { return {}; }
  /// Runs `host` (not run yet) until `limits`; `traffic` and `gather` then describe that run.
  virtual RunReport run(SimHost& host, const RunLimits& limits) = 0;
  /// Every node's counters for the last run (on every process).
  virtual const TrafficMetrics& traffic() const = 0;
  /// describe(v) for every node v of the last run, evaluated where v lives (on every process).
  virtual std::vector<std::vector<std::byte>> gather(const Describe& describe) = 0;
  /// Whether this process prints and writes the outputs (the others stay quiet).
  virtual bool is_root() const = 0;
};

/// The sequential runner: SimHost::run, results read in place.
class InPlaceRunner final : public HostRunner {
public:
  RunReport run(SimHost& host, const RunLimits& limits) override {
    host_ = &host;
    return host.run(limits);
  }
  const TrafficMetrics& traffic() const override { return host_->simulator().traffic(); }
  std::vector<std::vector<std::byte>> gather(const Describe& describe) override {
    std::vector<std::vector<std::byte>> out(host_->simulator().network().node_count());  // a whole host
    for (NodeIndex v = 0; v < out.size(); ++v) out[v] = describe(v);
    return out;
  }
  bool is_root() const override { return true; }

private:
  SimHost* host_ = nullptr;
};

}  // namespace laguerre::sim
