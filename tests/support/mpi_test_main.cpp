// GoogleTest entry point for every suite: MPI is initialized once, all ranks run every test, and only rank 0
// reports (a failure on any rank still fails that rank's process, hence the test).
#include <Teuchos_GlobalMPISession.hpp>
#include <gtest/gtest.h>

int main(int argc, char** argv)
{
  Teuchos::GlobalMPISession mpi_session(&argc, &argv, nullptr);
  ::testing::InitGoogleTest(&argc, argv);
  if (Teuchos::GlobalMPISession::getRank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  return RUN_ALL_TESTS();
}
