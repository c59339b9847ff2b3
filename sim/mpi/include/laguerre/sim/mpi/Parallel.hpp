#pragma once
/// @file
/// The conservative parallel kernel: one Simulator per MPI rank, each owning a part of the nodes
/// (a METIS partition), run in time windows so that the result is the sequential run's, bit for bit.
///
/// Contract (docs/parallel.md has the argument): with the same Network, SimConfig and NodeHandler
/// on every rank, ParallelRun::run gives on rank 0 the trace (hash and records), the traffic
/// metrics, the timer drops, the event count and the end time that Simulator::run gives
/// sequentially, for any number of ranks and any partition, because the Simulator orders equal
/// times by event keys that do not depend on the partition (Simulator.hpp). What a run needs:
///  - every link whose endpoints lie on different ranks has a positive minimum latency (the
///    lookahead is the smallest such latency; zero is refused with core::InputError);
///  - handlers touch only the state of the node they serve and send through the Simulator (no
///    request_stop, no extra kernel handlers, no shared state across nodes);
///  - RunLimits::max_events is unlimited (an event budget has no partition-independent meaning).

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <mpi.h>

#include "laguerre/sim/Simulator.hpp"

namespace laguerre::sim::mpi {

/// Initializes MPI for the lifetime of the object if nobody did (and finalizes it then).
class Session {
public:
  /// Calls MPI_Init unless MPI is already initialized.
  Session(int& argc, char**& argv);
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  /// Calls MPI_Finalize if this object initialized MPI.
  ~Session();
  /// This process's rank in MPI_COMM_WORLD.
  int rank() const;
  /// The number of ranks in MPI_COMM_WORLD.
  int size() const;

private:
  bool owner_ = false;
};

/// A rank per node: METIS k-way with vertex weight 1 + degree (≈ events) and unit edge weights
/// (≈ a uniform message rate), seeded, so every rank computes the same answer. `parts` 1 (or a
/// network without links) gives rank 0 everywhere. Requires parts ≥ 1.
std::vector<int> metis_partition(const Network& network, int parts);

/// The flags of the nodes `rank` owns in `owner` (held[v] = owner[v] == rank), for building a
/// Simulator or SimHost of that part only.
std::vector<std::uint8_t> owned_flags(std::span<const int> owner, int rank);

/// The smallest minimum latency over directed links u → v with owner[u] != owner[v] (time_max if
/// there is none). Requires owner.size() == node_count().
Duration cut_lookahead(const Network& network, std::span<const int> owner);

/// What a parallel run measured (per-rank figures on rank 0), and its merged results.
struct ParallelReport {
  RunReport run;                  ///< as Simulator::run's: events summed, end time, wall time
  int ranks = 1;                  ///< MPI ranks
  Duration lookahead = 0;         ///< the window width (time_max when no link is cut)
  std::uint64_t windows = 0;      ///< windows processed (this and the figures per rank: over every run call so far)
  std::uint64_t cut_links = 0;    ///< directed links between ranks
  std::uint64_t remote_copies = 0;  ///< copies sent between ranks (all ranks, all calls)
  std::uint64_t remote_bytes = 0;   ///< their encoded size (all calls)
  // Per rank (index = rank), gathered on rank 0:
  std::vector<std::uint64_t> nodes;           ///< nodes owned
  std::vector<std::uint64_t> held_nodes;      ///< nodes whose state the rank's Simulator holds (local_count)
  std::vector<std::uint64_t> events;          ///< events processed (all calls)
  std::vector<double> event_seconds;          ///< wall time inside Simulator::run
  std::vector<double> sync_seconds;           ///< wall time in the exchanges and reductions
  std::vector<std::uint64_t> peak_memory_bytes;  ///< peak resident set size
  // Merged results:
  Trace trace;                    ///< rank 0: the delivered copies in the sequential order (the config's mode)
  TrafficMetrics traffic;         ///< every rank: every node's counters
  std::uint64_t timers_dropped = 0;  ///< every rank: summed over ranks
};

/// Drives one rank's part of a partitioned run. Every rank of `comm` constructs one, with the same
/// network, configuration, handler logic and `owner`, and calls the same methods in the same order
/// (they are collective).
class ParallelRun final : private RemoteOutbox {
public:
  /// Makes `sim` (not run yet) this rank's part: owner[v] is the rank of node v. `sim` is whole, or
  /// built for this part (Simulator's `held`: owner[v] == rank, e.g. by owned_flags), which holds only
  /// the part's node and link state. Computes the
  /// lookahead; throws core::InputError (on every rank alike) if a cut link can have zero latency.
  /// Throws core::InternalError (a broken precondition) if owner has the wrong size or names a rank
  /// outside the communicator.
  ParallelRun(Simulator& sim, std::vector<int> owner, MPI_Comm comm = MPI_COMM_WORLD);
  ParallelRun(const ParallelRun&) = delete;
  ParallelRun& operator=(const ParallelRun&) = delete;

  /// Runs windows until no event is left anywhere or the next one lies after limits.until; returns
  /// the report. An exception in a handler on one rank is rethrown there
  /// and reported as core::InternalError on the others, after the window (no rank hangs). Throws
  /// core::InternalError (a broken precondition) for a finite max_events or after request_stop.
  ParallelReport run(const RunLimits& limits = {});

  /// Gathers per-node bytes on every rank: result[v] = describe(v) evaluated on v's owner. For
  /// reading protocol results node by node.
  std::vector<std::vector<std::byte>> gather_nodes(
      const std::function<std::vector<std::byte>(NodeIndex)>& describe) const;

  /// The rank of node v.
  int owner(NodeIndex v) const { return owner_[v]; }
  /// This process's rank.
  int rank() const { return rank_; }

private:
  void post(Time at, std::uint64_t key, NodeIndex from, NodeIndex to, Phase phase,
            std::span<const std::byte> bytes) override;
  /// Sends the window's outboxes, delivers what arrived, and returns the global minimum of the
  /// next event times; `failed` is raised if any rank reports a failure.
  Time exchange(bool& failed, bool local_failure);

  Simulator& sim_;
  std::vector<int> owner_;
  MPI_Comm comm_;
  int rank_ = 0;
  int size_ = 1;
  Duration lookahead_ = time_max;
  std::uint64_t cut_links_ = 0;
  std::vector<std::vector<std::byte>> outbox_;  // encoded copies per destination rank
  Time outbox_min_ = time_max;
  std::uint64_t windows_ = 0;
  std::uint64_t posted_ = 0;
  std::uint64_t posted_bytes_ = 0;
  double sync_seconds_ = 0;
  double event_seconds_ = 0;
  std::uint64_t events_ = 0;
};

}  // namespace laguerre::sim::mpi

#include <memory>

#include "laguerre/sim/HostRunner.hpp"

namespace laguerre::sim::mpi {

/// The parallel HostRunner: each run partitions the host's network with METIS over `comm`, runs
/// it with a ParallelRun, and keeps the merged traffic; rank 0 is the root. `ownership` computes the
/// partition ahead, so that each rank's host holds only its own nodes; the next run uses it.
class MpiHostRunner final : public HostRunner {
public:
  /// A runner over `comm` (every rank must make the same calls).
  explicit MpiHostRunner(MPI_Comm comm = MPI_COMM_WORLD);
  ~MpiHostRunner() override;
  std::vector<std::uint8_t> ownership(const Network& network) override;
  RunReport run(SimHost& host, const RunLimits& limits) override;
  const TrafficMetrics& traffic() const override { return report_.traffic; }
  std::vector<std::vector<std::byte>> gather(const Describe& describe) override { return run_->gather_nodes(describe); }
  bool is_root() const override { return rank_ == 0; }
  /// The last run's report (merged results on rank 0).
  const ParallelReport& report() const { return report_; }

private:
  MPI_Comm comm_;
  int rank_ = 0;
  std::unique_ptr<ParallelRun> run_;
  ParallelReport report_;
  std::vector<int> next_owner_;  // the partition `ownership` computed, for the next run
};

}  // namespace laguerre::sim::mpi
