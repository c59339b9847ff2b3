#include "Parallel.hpp"

#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>

#include "laguerre/core/Error.hpp"

#ifdef LAGUERRE_WITH_MPI
#include "laguerre/sim/mpi/Parallel.hpp"
#endif

namespace laguerre::tools {

namespace {
std::unique_ptr<sim::HostRunner> runner;
std::unique_ptr<scenarios::RunSplit> split;
int world_ranks = 1;

bool launched_by_mpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr ||
         std::getenv("PMIX_RANK") != nullptr;
}
}  // namespace

#ifdef LAGUERRE_WITH_MPI
namespace {
/// RunSplit over MPI_COMM_WORLD: the sizes, then the bytes, gathered by every rank.
class MpiRunSplit final : public scenarios::RunSplit {
public:
  MpiRunSplit() {
    int r = 0, n = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    MPI_Comm_size(MPI_COMM_WORLD, &n);
    rank_ = static_cast<std::size_t>(r), size_ = static_cast<std::size_t>(n);
  }
  std::size_t rank() const override { return rank_; }
  std::size_t size() const override { return size_; }
  std::vector<std::byte> all_gather(std::span<const std::byte> mine) override {
    if (mine.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw core::InternalError("a rank's run records exceed 2 GiB");
    const int count = static_cast<int>(mine.size());
    std::vector<int> counts(size_), offsets(size_);
    MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    long long total = 0;
    for (std::size_t k = 0; k < size_; ++k) {
      offsets[k] = static_cast<int>(total);
      total += counts[k];
      if (total > std::numeric_limits<int>::max()) throw core::InternalError("the run records exceed 2 GiB");
    }
    std::vector<std::byte> all(static_cast<std::size_t>(total));
    MPI_Allgatherv(mine.data(), count, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, MPI_COMM_WORLD);
    return all;
  }

private:
  std::size_t rank_ = 0, size_ = 1;
};
}  // namespace

ParallelContext::ParallelContext(int& argc, char**& argv) {
  if (!launched_by_mpi()) return;
  MPI_Init(&argc, &argv);
  active_ = true;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
  if (rank != 0) {  // rank 0 prints and writes; the others compute their part quietly
    if (std::freopen("/dev/null", "w", stdout) == nullptr || std::freopen("/dev/null", "w", stderr) == nullptr) {
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
  }
  world_ranks = ranks_;
  if (ranks_ > 1) runner = std::make_unique<sim::mpi::MpiHostRunner>(), split = std::make_unique<MpiRunSplit>();
}

ParallelContext::~ParallelContext() {
  runner.reset();
  split.reset();
  if (active_) MPI_Finalize();
}
#else
ParallelContext::ParallelContext(int&, char**&) {
  if (launched_by_mpi()) {
    std::fprintf(stderr, "laguerre: note: this build has no MPI support (sim/mpi was not built); every rank "
                         "runs the whole command sequentially\n");
  }
}

ParallelContext::~ParallelContext() = default;
#endif

sim::HostRunner* host_runner() { return runner.get(); }

scenarios::RunSplit* run_split() { return split.get(); }

std::vector<std::size_t> metis_workers(const core::PlanarGraph& g, std::size_t parts) {
#ifdef LAGUERRE_WITH_MPI
  const std::vector<int> owner = sim::mpi::metis_partition(sim::network_of(g), static_cast<int>(parts));
  return {owner.begin(), owner.end()};
#else
  (void)g, (void)parts;
  throw core::InputError("--partition", 0, "blocks: this build has no METIS (sim/mpi was not built; install libopenmpi-dev "
                                           "and libmetis-dev), found metis");
#endif
}

int mpi_ranks() { return world_ranks; }

nlohmann::json parallel_summary() {
#ifdef LAGUERRE_WITH_MPI
  const auto* mpi = dynamic_cast<const sim::mpi::MpiHostRunner*>(runner.get());
  if (mpi == nullptr) return nullptr;
  const sim::mpi::ParallelReport& r = mpi->report();
  return {{"ranks", r.ranks},
          {"windows", r.windows},
          {"lookahead_seconds", sim::to_seconds(r.lookahead)},
          {"cut_links", r.cut_links},
          {"remote_copies", r.remote_copies},
          {"remote_bytes", r.remote_bytes},
          {"nodes", r.nodes},
          {"events", r.events},
          {"event_seconds", r.event_seconds},
          {"sync_seconds", r.sync_seconds},
          {"peak_memory_bytes", r.peak_memory_bytes}};
#else
  return nullptr;
#endif
}

}  // namespace laguerre::tools
