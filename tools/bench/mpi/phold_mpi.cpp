// PHOLD on a torus on the sequential Simulator or the MPI parallel kernel (tools/bench/mpi.sh).
//   phold_mpi --side S [--until SECONDS] [--seed 1] [--population 1] [--sequential 1] [--trace 0|1]
// Rank 0 prints one line of key=value pairs: the run (events, wall, events/s), the windows, copies
// exchanged per window, time in events and in synchronisation (max over ranks), peak memory per rank,
// the lookahead, the cut links of the METIS partition, the measured exchange latency τ (an empty
// window exchange, timed over 200 rounds) and the coupling factor λ = L·E/(τ·P) with
// E = events per simulated second and P = events per wall second of one rank.
#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "laguerre/sim/mpi/Parallel.hpp"
#include "laguerre/sim/mpi/Phold.hpp"

using namespace laguerre::sim;

namespace {

struct Options {
  NodeIndex side = 100;
  double until = 10;
  std::uint64_t seed = 1;
  unsigned population = 1;
  bool sequential = false;
  bool trace = false;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const char* value = argv[i + 1];
    if (key == "--side") o.side = static_cast<NodeIndex>(std::strtoul(value, nullptr, 10));
    else if (key == "--until") o.until = std::strtod(value, nullptr);
    else if (key == "--seed") o.seed = std::strtoull(value, nullptr, 10);
    else if (key == "--population") o.population = static_cast<unsigned>(std::strtoul(value, nullptr, 10));
    else if (key == "--sequential") o.sequential = std::atoi(value) != 0;
    else if (key == "--trace") o.trace = std::atoi(value) != 0;
    else {
      std::fprintf(stderr, "phold_mpi: unknown option '%s' (expected --side, --until, --seed, --population, "
                           "--sequential or --trace)\n", key.c_str());
      std::exit(2);
    }
  }
  if (o.side < 3) {
    std::fprintf(stderr, "phold_mpi: --side must be at least 3, got %u\n", o.side);
    std::exit(2);
  }
  return o;
}

/// Seconds of CPU time this process used so far (the machine may be shared).
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Wall seconds of one empty window exchange (Alltoall of the header + empty Alltoallv), averaged.
double exchange_latency(int ranks) {
  std::vector<std::int64_t> send(4 * static_cast<std::size_t>(ranks)), recv(send.size());
  std::vector<int> zeros(static_cast<std::size_t>(ranks), 0);
  std::byte dummy{};
  constexpr int rounds = 200;
  MPI_Barrier(MPI_COMM_WORLD);
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < rounds; ++i) {
    MPI_Alltoall(send.data(), 4, MPI_INT64_T, recv.data(), 4, MPI_INT64_T, MPI_COMM_WORLD);
    MPI_Alltoallv(&dummy, zeros.data(), zeros.data(), MPI_BYTE, &dummy, zeros.data(), zeros.data(), MPI_BYTE,
                  MPI_COMM_WORLD);
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / rounds;
}

}  // namespace

int main(int argc, char** argv) {
  mpi::Session session(argc, argv);
  const Options o = parse(argc, argv);
  const int rank = session.rank(), ranks = session.size();
  const Time until = static_cast<Time>(o.until * 1e9);
  const std::size_t n = std::size_t{o.side} * o.side;
  const SimConfig config{.seed = o.seed, .trace = o.trace ? TraceMode::hash_only : TraceMode::off};
  if (o.sequential) {
    if (ranks != 1) {
      if (rank == 0) std::fprintf(stderr, "phold_mpi: --sequential 1 runs on one rank\n");
      return 2;
    }
    mpi::Phold model(n, o.population);
    Simulator sim(mpi::torus(o.side, mpi::phold_links()), config, model);
    const double cpu_start = cpu_seconds();
    const RunReport r = sim.run({.until = until});
    const double cpu = cpu_seconds() - cpu_start;
    std::printf("mode=sequential ranks=1 nodes=%zu events=%llu wall_s=%.3f events_per_s=%.0f cpu_s=%.3f "
                "ns_per_event_cpu=%.1f peak_mb=%.1f trace=%016llx\n",
                n, static_cast<unsigned long long>(r.events_processed), r.wall_seconds, r.events_per_second, cpu,
                1e9 * cpu / static_cast<double>(r.events_processed),
                static_cast<double>(r.peak_memory_bytes) / 1e6,
                static_cast<unsigned long long>(sim.trace().hash()));
    return 0;
  }
  // The partition first, then a simulator (and model) of this rank's nodes only.
  Network net = mpi::torus(o.side, mpi::phold_links());
  const auto part_start = std::chrono::steady_clock::now();
  std::vector<int> owner = mpi::metis_partition(net, ranks);
  const double partition_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - part_start).count();
  std::vector<std::uint8_t> held = mpi::owned_flags(owner, rank);
  mpi::Phold model(static_cast<std::size_t>(std::count(held.begin(), held.end(), 1)), o.population);
  Simulator sim(std::move(net), config, model, std::move(held));
  mpi::ParallelRun run(sim, std::move(owner));
  const double tau = exchange_latency(ranks);
  const mpi::ParallelReport r = run.run({.until = until});
  if (rank != 0) return 0;
  const double event_s = *std::max_element(r.event_seconds.begin(), r.event_seconds.end());
  const double sync_s = *std::max_element(r.sync_seconds.begin(), r.sync_seconds.end());
  std::string mem;
  for (const std::uint64_t m : r.peak_memory_bytes) mem += (mem.empty() ? "" : ",") + std::to_string(m / 1000000);
  // λ = L·E/(τ·P): L in simulated s, E events per simulated s, τ wall s per exchange, P events per
  // wall s of one rank while in events.
  const double L = static_cast<double>(r.lookahead) * 1e-9;
  const double E = static_cast<double>(r.run.events_processed) / (static_cast<double>(r.run.simulated_time) * 1e-9);
  const double P = static_cast<double>(r.run.events_processed) / static_cast<double>(ranks) / event_s;
  const double lambda = r.lookahead == time_max ? INFINITY : L * E / (tau * P);  // nothing cut: no coupling
  std::printf("mode=parallel ranks=%d nodes=%zu events=%llu wall_s=%.3f events_per_s=%.0f windows=%llu "
              "copies_per_window=%.1f bytes_per_window=%.0f event_s=%.3f sync_s=%.3f partition_s=%.3f "
              "peak_mb_per_rank=%s lookahead_ns=%lld cut_links=%llu tau_us=%.1f lambda=%.1f trace=%016llx\n",
              ranks, n, static_cast<unsigned long long>(r.run.events_processed), r.run.wall_seconds,
              r.run.events_per_second, static_cast<unsigned long long>(r.windows),
              r.windows ? static_cast<double>(r.remote_copies) / static_cast<double>(r.windows) : 0.0,
              r.windows ? static_cast<double>(r.remote_bytes) / static_cast<double>(r.windows) : 0.0, event_s, sync_s,
              partition_s, mem.c_str(), static_cast<long long>(r.lookahead),
              static_cast<unsigned long long>(r.cut_links), tau * 1e6, lambda,
              static_cast<unsigned long long>(r.trace.hash()));
  return 0;
}
