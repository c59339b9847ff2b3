#include "Parallel.hpp"

#include <cstdio>
#include <cstdlib>
#include <memory>

#include "laguerre/core/Error.hpp"

#ifdef LAGUERRE_WITH_MPI
#include "laguerre/sim/mpi/Parallel.hpp"
#endif

namespace laguerre::tools {

namespace {
std::unique_ptr<sim::HostRunner> runner;
int world_ranks = 1;

bool launched_by_mpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr ||
         std::getenv("PMIX_RANK") != nullptr;
}
}  // namespace

#ifdef LAGUERRE_WITH_MPI
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
  if (ranks_ > 1) runner = std::make_unique<sim::mpi::MpiHostRunner>();
}

ParallelContext::~ParallelContext() {
  runner.reset();
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

}  // namespace laguerre::tools
