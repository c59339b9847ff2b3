// The entry point of sim_mpi_tests: MPI first, then GoogleTest on every rank (the tests are
// collective, so every rank runs the same ones in the same order); only rank 0 prints, and the
// exit status is the worst over the ranks.
#include <gtest/gtest.h>

#include "laguerre/sim/mpi/Parallel.hpp"

int main(int argc, char** argv) {
  laguerre::sim::mpi::Session session(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  if (session.rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  int status = RUN_ALL_TESTS();
  int worst = 0;
  MPI_Allreduce(&status, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return worst;
}
