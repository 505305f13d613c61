// GoogleTest entry point for every suite: MPI is initialized once, all ranks run every test, and only rank 0
// reports (a failure on any rank still fails that rank's process, hence the test). Kokkos starts here, not lazily at
// the first Tpetra::Map, so a threaded backend takes its thread count from KOKKOS_NUM_THREADS or --kokkos-threads.
#include <Kokkos_Core.hpp>
#include <Teuchos_GlobalMPISession.hpp>
#include <gtest/gtest.h>

int main(int argc, char** argv)
{
  Teuchos::GlobalMPISession mpi_session(&argc, &argv, nullptr);
  Kokkos::ScopeGuard kokkos_scope(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  if (Teuchos::GlobalMPISession::getRank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  return RUN_ALL_TESTS();
}
