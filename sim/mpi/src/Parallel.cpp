#include "laguerre/sim/mpi/Parallel.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <climits>
#include <cstring>
#include <exception>
#include <numeric>
#include <string>

#include "laguerre/core/Error.hpp"
#include "laguerre/core/random/Random.hpp"
#include "laguerre/sim/LiveCluster.hpp"

// The window loop (see docs/parallel.md for the correctness argument):
//
//   EXCHANGE – every rank sends each other rank the copies its nodes posted to that rank's nodes
//              during the last window (MPI_Alltoall of a header, MPI_Alltoallv of the bytes), and
//              with the header the earliest time it knows of: its next pending event or the
//              earliest copy it posted. Every copy sent is received in the same collective (the
//              header carries the count, checked on arrival), so nothing is in flight afterwards
//              and the minimum over the headers is the global next event time T.
//   DECIDE   – T = ∞ everywhere: the run is over (queue_empty); T > until: time_limit.
//   WINDOW   – each rank runs its Simulator up to T + L − 1, L the lookahead (the smallest
//              latency of a cut link). A copy posted at time t ≥ T reaches another rank at
//              t + latency ≥ T + L, so it lies in a later window: no rank can receive, during a
//              window, an event that precedes one it has processed.
//
// Within a rank, events run in (time, key) order, the keys being partition-independent
// (Simulator.hpp); so each node sees the same events in the same order as in the sequential run,
// and the merged trace sorted by (time, key) is the sequential trace.

namespace laguerre::sim::mpi {

namespace {

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw core::InternalError(std::string("MPI call failed: ") + what);
}

constexpr std::size_t counter_fields = traffic_counter_fields.size();
std::array<std::uint64_t, counter_fields> fields_of(const TrafficCounters& c) {
  std::array<std::uint64_t, counter_fields> f{};
  for (std::size_t k = 0; k < counter_fields; ++k) f[k] = c.*traffic_counter_fields[k].second;
  return f;
}
TrafficCounters counters_of(const std::uint64_t* f) {
  TrafficCounters c;
  for (std::size_t k = 0; k < counter_fields; ++k) c.*traffic_counter_fields[k].second = f[k];
  return c;
}

int to_int_count(std::size_t n, const char* what) {
  if (n > static_cast<std::size_t>(INT_MAX)) {
    throw std::length_error(std::string("An MPI message is too large (over 2^31 units): ") + what);
  }
  return static_cast<int>(n);
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

Session::Session(int& argc, char**& argv) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) {
    check(MPI_Init(&argc, &argv), "MPI_Init");
    owner_ = true;
  }
}

Session::~Session() {
  if (owner_) MPI_Finalize();
}

int Session::rank() const {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int Session::size() const {
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

std::vector<std::uint8_t> owned_flags(std::span<const int> owner, int rank) {
  std::vector<std::uint8_t> held(owner.size());
  for (std::size_t v = 0; v < owner.size(); ++v) held[v] = owner[v] == rank ? 1 : 0;
  return held;
}

Duration cut_lookahead(const Network& network, std::span<const int> owner) {
  LAGUERRE_PRECONDITION(owner.size() == network.node_count(), "cut_lookahead needs one rank per node.");
  Duration lookahead = time_max;
  for (LinkIndex l = 0; l < network.link_count(); ++l) {
    if (owner[network.link_source(l)] == owner[network.link_target(l)]) continue;
    lookahead = std::min(lookahead, network.link_model(l).latency.min_latency(network.link_length(l)));
  }
  return lookahead;
}

ParallelRun::ParallelRun(Simulator& sim, std::vector<int> owner, MPI_Comm comm)
    : sim_(sim), owner_(std::move(owner)), comm_(comm) {
  check(MPI_Comm_rank(comm_, &rank_), "MPI_Comm_rank");
  check(MPI_Comm_size(comm_, &size_), "MPI_Comm_size");
  const Network& net = sim_.network();
  LAGUERRE_PRECONDITION(owner_.size() == net.node_count(), "ParallelRun needs one rank per node.");
  for (const int r : owner_) {
    LAGUERRE_PRECONDITION(r >= 0 && r < size_, "ParallelRun: a node's rank " + std::to_string(r) +
                                                   " lies outside the communicator's " + std::to_string(size_) +
                                                   " ranks.");
  }
  // Every rank must hold the same partition of the same network.
  std::uint64_t h = core::fnv1a64(std::as_bytes(std::span<const int>(owner_)));
  h = core::fnv1a64(std::as_bytes(std::span<const std::uint64_t, 2>({net.node_count(), net.link_count()})), h);
  std::array<std::uint64_t, 2> mine{h, ~h}, all{};
  check(MPI_Allreduce(mine.data(), all.data(), 2, MPI_UINT64_T, MPI_MAX, comm_), "MPI_Allreduce");
  LAGUERRE_PRECONDITION(all[0] == h && all[1] == ~h,
                        "ParallelRun: the ranks were given different networks or partitions.");
  for (LinkIndex l = 0; l < net.link_count(); ++l) {
    const NodeIndex u = net.link_source(l), v = net.link_target(l);
    if (owner_[u] == owner_[v]) continue;
    ++cut_links_;
    const Duration d = net.link_model(l).latency.min_latency(net.link_length(l));
    if (d <= 0) {
      throw core::InputError("Link " + std::to_string(net.id(u)) + " -> " + std::to_string(net.id(v)) +
                             " joins nodes on MPI ranks " + std::to_string(owner_[u]) + " and " +
                             std::to_string(owner_[v]) +
                             " and can have zero latency: the parallel kernel needs a positive lookahead "
                             "(a minimum latency > 0 ns) on every link between ranks. Give that link a "
                             "positive minimum latency, or run sequentially.");
    }
    lookahead_ = std::min(lookahead_, d);
  }
  sim_.partition(owned_flags(owner_, rank_), *this);
  outbox_.resize(static_cast<std::size_t>(size_));
}

void ParallelRun::post(Time at, std::uint64_t key, NodeIndex from, NodeIndex to, Phase phase,
                       std::span<const std::byte> bytes) {
  std::vector<std::byte>& out = outbox_[static_cast<std::size_t>(owner_[to])];
  const std::size_t before = out.size();
  append_bytes(out, at);
  append_bytes(out, key);
  append_bytes(out, from);
  append_bytes(out, to);
  append_bytes(out, phase);
  append_bytes(out, static_cast<std::uint32_t>(bytes.size()));
  out.insert(out.end(), bytes.begin(), bytes.end());
  outbox_min_ = std::min(outbox_min_, at);
  ++posted_;
  posted_bytes_ += out.size() - before;
}

Time ParallelRun::exchange(bool& failed, bool local_failure) {
  const auto start = std::chrono::steady_clock::now();
  const auto n = static_cast<std::size_t>(size_);
  // Header per destination: bytes, copies, the earliest time this rank knows of, failure flag.
  constexpr int header = 4;
  const std::int64_t earliest = std::min(sim_.kernel().next_event_time(), outbox_min_);
  std::vector<std::int64_t> send(n * header), recv(n * header);
  std::vector<std::int64_t> copies(n, 0);
  for (std::size_t r = 0; r < n; ++r) {
    // Count the copies by walking the encoding (cheap next to the exchange, and keeps post() lean).
    const std::span<const std::byte> in(outbox_[r]);
    for (std::size_t at = 0; at < in.size(); ++copies[r]) {
      at += sizeof(Time) + sizeof(std::uint64_t) + 2 * sizeof(NodeIndex) + sizeof(Phase);
      at += read_bytes<std::uint32_t>(in, at);
    }
    send[r * header + 0] = static_cast<std::int64_t>(outbox_[r].size());
    send[r * header + 1] = copies[r];
    send[r * header + 2] = earliest;
    send[r * header + 3] = local_failure ? 1 : 0;
  }
  check(MPI_Alltoall(send.data(), header, MPI_INT64_T, recv.data(), header, MPI_INT64_T, comm_), "MPI_Alltoall");
  Time global_min = time_max;
  failed = false;
  for (std::size_t r = 0; r < n; ++r) {
    global_min = std::min<Time>(global_min, recv[r * header + 2]);
    failed = failed || recv[r * header + 3] != 0;
  }
  if (!failed) {
    std::vector<int> send_counts(n), send_displs(n), recv_counts(n), recv_displs(n);
    std::vector<std::byte> send_buffer, recv_buffer;
    std::size_t total_send = 0, total_recv = 0;
    for (std::size_t r = 0; r < n; ++r) {
      send_counts[r] = to_int_count(outbox_[r].size(), "copies to one rank in one window");
      send_displs[r] = to_int_count(total_send, "copies sent in one window");
      total_send += outbox_[r].size();
      recv_counts[r] = to_int_count(static_cast<std::size_t>(recv[r * header]), "copies from one rank in one window");
      recv_displs[r] = to_int_count(total_recv, "copies received in one window");
      total_recv += static_cast<std::size_t>(recv[r * header]);
    }
    to_int_count(total_send, "copies sent in one window");
    to_int_count(total_recv, "copies received in one window");
    send_buffer.reserve(total_send);
    for (std::size_t r = 0; r < n; ++r) send_buffer.insert(send_buffer.end(), outbox_[r].begin(), outbox_[r].end());
    recv_buffer.resize(total_recv);
    check(MPI_Alltoallv(send_buffer.data(), send_counts.data(), send_displs.data(), MPI_BYTE, recv_buffer.data(),
                        recv_counts.data(), recv_displs.data(), MPI_BYTE, comm_),
          "MPI_Alltoallv");
    for (std::size_t r = 0; r < n; ++r) {
      const auto in = std::span<const std::byte>(recv_buffer).subspan(static_cast<std::size_t>(recv_displs[r]),
                                                                      static_cast<std::size_t>(recv_counts[r]));
      std::int64_t received = 0;
      for (std::size_t at = 0; at < in.size(); ++received) {
        const auto time = read_bytes<Time>(in, at);
        const auto key = read_bytes<std::uint64_t>(in, at);
        const auto from = read_bytes<NodeIndex>(in, at);
        const auto to = read_bytes<NodeIndex>(in, at);
        const auto phase = read_bytes<Phase>(in, at);
        const auto size = read_bytes<std::uint32_t>(in, at);
        LAGUERRE_ASSERT(at + size <= in.size());
        sim_.deliver_remote(time, key, from, to, phase, in.subspan(at, size));
        at += size;
      }
      LAGUERRE_ASSERT(received == recv[r * header + 1]);  // the exchange neither lost nor invented copies
    }
  }
  for (auto& out : outbox_) out.clear();
  outbox_min_ = time_max;
  sync_seconds_ += seconds_since(start);
  return global_min;
}

ParallelReport ParallelRun::run(const RunLimits& limits) {
  LAGUERRE_PRECONDITION(limits.max_events == UINT64_MAX,
                        "A parallel run cannot honour an event budget (RunLimits::max_events): which events "
                        "come first differs across ranks; give a time limit instead.");
  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t events_before = events_;
  std::exception_ptr error;
  bool local_failure = false;
  const auto guarded = [&](Time until) {
    try {
      const RunReport r = sim_.run({.until = until});
      events_ += r.events_processed;
      event_seconds_ += r.wall_seconds;
      LAGUERRE_PRECONDITION(r.reason != StopReason::stop_requested,
                            "A parallel run cannot honour Simulator::request_stop (the other ranks are "
                            "elsewhere in their windows); give a time limit instead.");
    } catch (...) {
      error = std::current_exception();
      local_failure = true;
    }
  };
  guarded(sim_.now() - 1);  // launches the nodes on the first call; processes nothing
  StopReason reason = StopReason::queue_empty;
  for (;;) {
    bool failed = false;
    const Time next = exchange(failed, local_failure);
    if (failed) {
      if (error) std::rethrow_exception(error);
      throw core::InternalError("The parallel run stopped: another MPI rank failed (see its error).");
    }
    if (next == time_max) break;
    if (next > limits.until) {
      reason = StopReason::time_limit;
      guarded(limits.until);  // processes nothing; advances the clock as a sequential run does
      if (error) std::rethrow_exception(error);
      break;
    }
    const Time window_end = next > time_max - lookahead_ ? time_max : next + lookahead_ - 1;
    guarded(std::min(window_end, limits.until));
    ++windows_;
  }

  ParallelReport report;
  report.ranks = size_;
  report.lookahead = lookahead_;
  report.windows = windows_;
  report.cut_links = cut_links_;
  report.run.reason = reason;
  const auto n = static_cast<std::size_t>(size_);
  // Scalars: summed, maxed, gathered.
  std::array<std::uint64_t, 4> sums{events_ - events_before, posted_, posted_bytes_, sim_.timers_dropped()}, total{};
  check(MPI_Allreduce(sums.data(), total.data(), 4, MPI_UINT64_T, MPI_SUM, comm_), "MPI_Allreduce");
  std::int64_t end_time = sim_.now(), global_end = 0;
  check(MPI_Allreduce(&end_time, &global_end, 1, MPI_INT64_T, MPI_MAX, comm_), "MPI_Allreduce");
  report.run.events_processed = total[0];
  report.remote_copies = total[1];
  report.remote_bytes = total[2];
  report.timers_dropped = total[3];
  report.run.simulated_time = reason == StopReason::time_limit ? std::max(limits.until, global_end) : global_end;
  std::uint64_t owned = 0;
  for (const int r : owner_) owned += r == rank_ ? 1 : 0;
  const std::array<double, 2> secs{event_seconds_, sync_seconds_};
  constexpr std::size_t per_rank = 4;
  const std::array<std::uint64_t, per_rank> counts{owned, events_, peak_memory_bytes(), sim_.local_count()};
  std::vector<double> all_secs(2 * n);
  std::vector<std::uint64_t> all_counts(per_rank * n);
  check(MPI_Gather(secs.data(), 2, MPI_DOUBLE, all_secs.data(), 2, MPI_DOUBLE, 0, comm_), "MPI_Gather");
  check(MPI_Gather(counts.data(), per_rank, MPI_UINT64_T, all_counts.data(), per_rank, MPI_UINT64_T, 0, comm_),
        "MPI_Gather");
  if (rank_ == 0) {
    for (std::size_t r = 0; r < n; ++r) {
      const std::uint64_t* c = all_counts.data() + per_rank * r;
      report.event_seconds.push_back(all_secs[2 * r]);
      report.sync_seconds.push_back(all_secs[2 * r + 1]);
      report.nodes.push_back(c[0]);
      report.events.push_back(c[1]);
      report.peak_memory_bytes.push_back(c[2]);
      report.held_nodes.push_back(c[3]);
      report.run.peak_memory_bytes = std::max(report.run.peak_memory_bytes, c[2]);
    }
  }

  // The trace: every rank's records with their keys, merged in (time, key) order on rank 0.
  const TraceMode mode = sim_.config().trace;
  report.trace = Trace(mode);
  if (mode != TraceMode::off) {
    const auto records = sim_.trace().records();
    const auto keys = sim_.trace_keys();
    LAGUERRE_ASSERT(records.size() == keys.size());  // each record of a partitioned run has its key
    const int mine_count = to_int_count(records.size(), "trace records of one rank");
    std::vector<int> record_counts(n), displs(n);
    check(MPI_Gather(&mine_count, 1, MPI_INT, record_counts.data(), 1, MPI_INT, 0, comm_), "MPI_Gather");
    std::size_t all_records = 0;
    std::vector<int> byte_counts(n), byte_displs(n);
    for (std::size_t r = 0; r < n; ++r) {
      displs[r] = to_int_count(all_records, "trace records");
      all_records += static_cast<std::size_t>(record_counts[r]);
    }
    std::vector<std::uint64_t> all_keys(rank_ == 0 ? all_records : 0);
    std::vector<TraceRecord> all(rank_ == 0 ? all_records : 0);
    check(MPI_Gatherv(keys.data(), mine_count, MPI_UINT64_T, all_keys.data(), record_counts.data(), displs.data(),
                      MPI_UINT64_T, 0, comm_),
          "MPI_Gatherv");
    for (std::size_t r = 0; r < n; ++r) {
      byte_counts[r] = to_int_count(static_cast<std::size_t>(record_counts[r]) * sizeof(TraceRecord), "trace bytes");
      byte_displs[r] = to_int_count(static_cast<std::size_t>(displs[r]) * sizeof(TraceRecord), "trace bytes");
    }
    check(MPI_Gatherv(records.data(), to_int_count(records.size() * sizeof(TraceRecord), "trace bytes"), MPI_BYTE,
                      all.data(), byte_counts.data(), byte_displs.data(), MPI_BYTE, 0, comm_),
          "MPI_Gatherv");
    if (rank_ == 0) {
      std::vector<std::size_t> order(all_records);
      std::iota(order.begin(), order.end(), std::size_t{0});
      std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return all[a].time < all[b].time || (all[a].time == all[b].time && all_keys[a] < all_keys[b]);
      });
      for (const std::size_t i : order) report.trace.add(all[i]);
    }
  }

  // Traffic: every node's counters live on its owner (the counters of another rank's node, in a
  // whole simulator, stay zero); summing the ranks' tables merges them, a block of nodes at a time
  // (the buffers stay small next to the per-node state).
  const std::size_t nodes = sim_.network().node_count();
  std::uint64_t phases = sim_.traffic().phase_count(), all_phases = 0;
  check(MPI_Allreduce(&phases, &all_phases, 1, MPI_UINT64_T, MPI_MAX, comm_), "MPI_Allreduce");
  report.traffic = TrafficMetrics(nodes);
  constexpr std::size_t block = std::size_t{1} << 16;  // nodes per reduction
  std::vector<std::uint64_t> table, sum;
  for (std::uint64_t p = 0; p < all_phases; ++p) {
    const auto phase = static_cast<Phase>(p);
    std::size_t i = 0;  // the next held node, by local index (increasing node index)
    for (std::size_t first = 0; first < nodes; first += block) {
      const std::size_t count = std::min(block, nodes - first);
      table.assign(count * counter_fields, 0);
      sum.resize(table.size());
      for (; i < sim_.local_count() && sim_.local_node(i) < first + count; ++i) {
        const auto f = fields_of(sim_.traffic().get(static_cast<std::uint32_t>(i), phase));
        std::copy(f.begin(), f.end(), table.begin() + static_cast<std::ptrdiff_t>((sim_.local_node(i) - first) * counter_fields));
      }
      check(MPI_Allreduce(table.data(), sum.data(), static_cast<int>(table.size()), MPI_UINT64_T, MPI_SUM, comm_),
            "MPI_Allreduce");
      for (std::size_t v = 0; v < count; ++v) {
        report.traffic.add(static_cast<std::uint32_t>(first + v), phase, counters_of(sum.data() + v * counter_fields));
      }
    }
  }
  report.run.wall_seconds = seconds_since(start);
  report.run.events_per_second =
      report.run.wall_seconds > 0 ? static_cast<double>(report.run.events_processed) / report.run.wall_seconds : 0;
  return report;
}

std::vector<std::vector<std::byte>> ParallelRun::gather_nodes(
    const std::function<std::vector<std::byte>(NodeIndex)>& describe) const {
  std::vector<std::byte> mine;
  for (NodeIndex v = 0; v < owner_.size(); ++v) {
    if (owner_[v] != rank_) continue;
    const std::vector<std::byte> bytes = describe(v);
    append_bytes(mine, v);
    append_bytes(mine, static_cast<std::uint64_t>(bytes.size()));
    mine.insert(mine.end(), bytes.begin(), bytes.end());
  }
  const auto n = static_cast<std::size_t>(size_);
  const int count = to_int_count(mine.size(), "node descriptions of one rank");
  std::vector<int> counts(n), displs(n);
  check(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_), "MPI_Allgather");
  std::size_t total = 0;
  for (std::size_t r = 0; r < n; ++r) {
    displs[r] = to_int_count(total, "node descriptions");
    total += static_cast<std::size_t>(counts[r]);
  }
  std::vector<std::byte> all(total);
  check(MPI_Allgatherv(mine.data(), count, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, comm_),
        "MPI_Allgatherv");
  std::vector<std::vector<std::byte>> result(owner_.size());
  const std::span<const std::byte> in(all);
  for (std::size_t at = 0; at < in.size();) {
    const auto v = read_bytes<NodeIndex>(in, at);
    const auto size = static_cast<std::size_t>(read_bytes<std::uint64_t>(in, at));
    LAGUERRE_ASSERT(at + size <= in.size());
    const auto bytes = in.subspan(at, size);
    result[v].assign(bytes.begin(), bytes.end());
    at += size;
  }
  return result;
}

}  // namespace laguerre::sim::mpi

namespace laguerre::sim::mpi {

MpiHostRunner::MpiHostRunner(MPI_Comm comm) : comm_(comm) { check(MPI_Comm_rank(comm_, &rank_), "MPI_Comm_rank"); }

MpiHostRunner::~MpiHostRunner() = default;

std::vector<std::uint8_t> MpiHostRunner::ownership(const Network& network) {
  int size = 1;
  check(MPI_Comm_size(comm_, &size), "MPI_Comm_size");
  next_owner_ = metis_partition(network, size);
  return owned_flags(next_owner_, rank_);
}

RunReport MpiHostRunner::run(SimHost& host, const RunLimits& limits) {
  int size = 1;
  check(MPI_Comm_size(comm_, &size), "MPI_Comm_size");
  const Network& net = host.simulator().network();
  // The partition computed ahead by ownership() (the one a host built for a part needs; Simulator::
  // partition checks it), else this network's.
  std::vector<int> owner = next_owner_.size() == net.node_count() ? std::move(next_owner_) : metis_partition(net, size);
  next_owner_.clear();
  run_ = std::make_unique<ParallelRun>(host.simulator(), std::move(owner), comm_);
  report_ = run_->run(limits);
  return report_.run;
}

}  // namespace laguerre::sim::mpi
