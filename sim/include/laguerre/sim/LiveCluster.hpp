#pragma once
/// @file
/// Several live processes on 127.0.0.1: a launcher forks P workers, each hosting a part of the graph's
/// vertices (a contiguous block, or a given partition) on its own UdpHost, and drives them through phases (e.g. packing, then
/// forwarding). Each worker talks to the launcher over a Unix socket pair (control messages and
/// results); nodes talk over UDP only.
///
/// A phase ends when its work is done everywhere and nothing of it is left anywhere: the workers'
/// progress counts (LiveProgram::progress) sum to the phase's goal, every host is idle (no queued
/// message, no pending timer, nothing unsent), and every datagram sent has been received or dropped
/// by a kernel (Σ sent = Σ received + Σ kernel drops), seen twice in a row with the same counts (the
/// four-counter method of termination detection: a worker cannot decide alone, since a node that is
/// done may still owe a neighbour in another process a relay or an acknowledgement). Between phases
/// no datagram is in flight, so a phase's traffic never reaches the next phase's nodes.
///
/// Failures: a worker that exits or is killed, reports an error, or a run past the deadline ends every
/// worker (the launcher kills what does not stop within a second) and throws; nothing hangs. While a
/// phase runs, the launcher also reads the kernel drop counts every 100 ms (LiveConfig::lossless).

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string>
#include <sys/types.h>
#include <type_traits>
#include <vector>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/graph/PlanarGraph.hpp"
#include "laguerre/sim/UdpHost.hpp"

namespace laguerre::sim {

/// Appends the bytes of `x` to `out`: how control messages and results travel between the launcher
/// and its workers (one binary, one machine, so a memory image is the format).
template <class T>
void append_bytes(std::vector<std::byte>& out, const T& x) {
  static_assert(std::is_trivially_copyable_v<T>);
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &x, sizeof(T));
}

/// The T that append_bytes wrote at `at` in `in`; advances `at`. Throws core::InternalError (a broken
/// precondition) if `in` is too short.
template <class T>
T read_bytes(std::span<const std::byte> in, std::size_t& at) {
  static_assert(std::is_trivially_copyable_v<T>);
  LAGUERRE_PRECONDITION(at + sizeof(T) <= in.size(), "a live control message or result is too short");
  T x;
  std::memcpy(&x, in.data() + at, sizeof(T));
  at += sizeof(T);
  return x;
}

/// How a live cluster runs.
struct LiveConfig {
  std::size_t processes = 1;        ///< worker processes (≥ 1, ≤ vertices)
  /// The worker of each vertex (e.g. a METIS partition); empty: contiguous blocks (partition_blocks).
  /// Every worker must host at least one vertex.
  std::vector<std::size_t> process_of;
  std::uint16_t base_port = 0;      ///< worker k binds base_port + k; 0: ports the kernel picks
  UdpHostConfig host;               ///< seed, loss, buffers, datagram size (port, tag, epoch: set per worker)
  double timeout_seconds = 60;      ///< the whole run, from the fork to the last result
  /// The nodes tolerate no loss (no reliability layer): a kernel drop ends the run at once, with an
  /// error, instead of at the deadline.
  bool lossless = false;
  /// Failure injection (tests): this worker exits with status 70 when the first phase starts.
  std::optional<std::size_t> fail_worker;
};

/// The worker half of a live run: its calls run inside each worker process, on that worker's host.
class LiveProgram {
public:
  virtual ~LiveProgram() = default;
  /// Builds and starts the phase's nodes on `host` (UdpHost::start_phase(phase, …)) given the
  /// launcher's `input` for it; may also inject work (e.g. originate packets).
  virtual void start_phase(std::uint8_t phase, std::span<const std::byte> input, UdpHost& host) = 0;
  /// This worker's progress in the current phase (non-decreasing); the phase's work is done when the
  /// sum over the workers reaches its goal.
  virtual std::uint64_t progress(UdpHost& host) = 0;
  /// This worker's result of the phase (its nodes are still hosted).
  virtual std::vector<std::byte> finish_phase(std::uint8_t phase, UdpHost& host) = 0;
};

/// One worker, after the run.
struct WorkerReport {
  std::size_t nodes = 0;                 ///< vertices it hosted
  std::size_t first = 0;                 ///< the smallest of them
  std::uint16_t port = 0;                ///< its UDP port
  UdpCounters counters;                  ///< its host's counters (kernel drops read at the end)
  std::uint64_t peak_memory_bytes = 0;   ///< its peak resident set size (wait4)
  double cpu_seconds = 0;                ///< user + system CPU time
};

/// The launcher's side of P worker processes.
class LiveCluster {
public:
  /// Forks the workers (worker k hosts the vertices v with process_of[v] == k, by default the block
  /// partition_blocks(n, P)[k]) and waits until each has bound its port; `program` is copied into each worker by fork. Throws core::InputError
  /// for a bad configuration or a port in use, std::runtime_error if a process cannot start or a
  /// worker fails.
  LiveCluster(const core::PlanarGraph& g, LiveConfig config, LiveProgram& program, UdpHost::PhaseOf phase_of = {});
  LiveCluster(const LiveCluster&) = delete;
  LiveCluster& operator=(const LiveCluster&) = delete;
  /// Kills the workers still running.
  ~LiveCluster();

  /// Runs the next phase (0, 1, …): every worker starts it with `input`; returns when the phase has
  /// ended (see the file comment) with each worker's result, by worker index. Throws
  /// std::runtime_error (core::InputError for a worker's bad-input error) if a worker fails or the
  /// deadline passes; the workers are then gone.
  std::vector<std::vector<std::byte>> run_phase(std::span<const std::byte> input, std::uint64_t goal);
  /// Wall-clock seconds of each phase run so far.
  const std::vector<double>& phase_seconds() const { return phase_seconds_; }
  /// Ends the workers and returns their reports (by worker index).
  std::vector<WorkerReport> finish();

  /// The contiguous blocks of `n` vertices over `processes` workers: the first n mod P get one
  /// vertex more; entry k is the block's end (block k = [end[k−1], end[k])).
  static std::vector<std::size_t> partition_blocks(std::size_t n, std::size_t processes);

private:
  struct Worker;
  struct Message;
  void send(std::size_t k, std::uint8_t type, std::span<const std::byte> body);
  void broadcast(std::uint8_t type, std::span<const std::byte> body);
  Message wait_message(std::size_t& from, int max_wait_ms);
  [[noreturn]] void fail(const std::string& what, bool input_error = false);
  void stop_all();

  LiveConfig config_;
  std::vector<Worker> workers_;
  std::int64_t deadline_ = 0;
  std::uint8_t phase_ = 0;
  std::vector<double> phase_seconds_;
};

}  // namespace laguerre::sim
