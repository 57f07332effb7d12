// GoogleTest main for tests that run LAMMPS in-process: MPI around the tests, and only rank 0
// reports, so that mpirun -np N prints one result. Each run works in a directory of its own
// (ctest runs tests side by side, and decks write files with fixed names), removed at the end.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdlib>
#include <filesystem>
#include <string>

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  int me = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  if (me != 0) {
    auto &listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }

  namespace fs = std::filesystem;
  const fs::path home = fs::current_path();
  char scratch[4096] = "";
  if (me == 0) {
    std::string pattern = (home / "scratch-XXXXXX").string();
    if (mkdtemp(pattern.data())) pattern.copy(scratch, sizeof(scratch) - 1);
  }
  MPI_Bcast(scratch, sizeof(scratch), MPI_CHAR, 0, MPI_COMM_WORLD);
  if (scratch[0] == '\0') {
    if (me == 0) fprintf(stderr, "cannot create a scratch directory in %s\n", home.c_str());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  fs::current_path(scratch);

  int rc = RUN_ALL_TESTS();
  // A failure on any rank fails the run.
  int worst = rc;
  MPI_Allreduce(&rc, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  fs::current_path(home);
  if (me == 0) fs::remove_all(scratch);
  MPI_Finalize();
  return worst;
}
