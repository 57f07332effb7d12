// Walking rods give the same speeds on 1, 2 and 4 ranks: rank 0 runs the system alone
// (MPI_COMM_SELF) as the reference, then all ranks run it.
#include "lammps_fixture.h"
#include "rod_walking.h"

#include <cmath>
#include <cstdio>
#include <utility>

using namespace rod_walking;


// Speeds of 4 rods (rod k = molecule k): serial reference against all ranks.
class RodRanksTest : public LammpsTest {
 public:
  // Speeds of rods 1..nrods: rank 0 alone, then all ranks.
  std::pair<std::vector<double>, std::vector<double>> run_both(std::map<std::string, std::string> vars, int nrods);
  void compare(std::map<std::string, std::string> vars, double rod_tol, double mean_tol);
};

// Rods at x, y = 10 and 30 mm in a 40 mm box: inside the sub-domains of 2 and 4 ranks (they
// walk about 6 mm), but with the rigid-body and contact machinery running on every rank.
TEST_F(RodRanksTest, RodsInsideSubdomains)
{
  // Contact order differs with the decomposition and the bouncing is chaotic: single rods
  // differ by up to ~10%, the mean of four by ~2%.
  compare({{"shift", "0"}, {"dt", "5e-5"}, {"nside", "2"}}, 0.15, 0.05);
}

// Rods at x, y = 0 and 20 mm: on periodic edges and on the sub-domain boundaries of 2 and 4
// ranks, split between ranks. pair gran/impulse solves all contacts of a rod on one rank, so a
// split rod gets one impulse solution per step (before: one per rank that owned some of its
// atoms, 15% slower on 2 ranks). Measured (dt 5e-5, seed 12345, mean of 4 rods): 1 rank
// 3.27 mm/s, 2 ranks 3.30, 4 ranks 3.28; single rods within 6% (chaotic bouncing amplifies
// round-off differences).
TEST_F(RodRanksTest, RodsAcrossSubdomainBoundaries)
{
  compare({{"shift", "-10e-3"}, {"dt", "5e-5"}, {"nside", "2"}}, 0.1, 0.05);
}

// The same on rough plates (rms slope 0.01, correlation length 1 mm): the frozen surface is a
// function of position and seed only, so every rank sees the same bumps. Rods wander, their
// speeds scatter (s.d. ~0.8 mm/s) and the chaotic bouncing on the bumps decorrelates the 1-rank
// and the split runs within the 2 s (single rods 3-25% apart), so only the statistics can agree:
// the mean of 16 rods, 4 per sub-domain boundary of 2 and 4 ranks, within three standard errors.
TEST_F(RodRanksTest, RodsOnRoughPlatesAcrossSubdomainBoundaries)
{
  const auto [serial, parallel] = run_both({{"shift", "-10e-3"}, {"dt", "5e-5"}, {"nside", "4"}, {"seed", "1"},
                                            {"rough", "0.01"}, {"rough_length", "1e-3"}}, 16);
  const double tolerance = 3.0 * std::hypot(standard_error(serial), standard_error(parallel));
  if (mpi_rank() == 0)
    std::printf("[ measured ] mean of 16 rods: %.3f mm/s on all ranks, %.3f on 1 (three standard errors: %.3f)\n",
                mean(parallel) * 1e3, mean(serial) * 1e3, tolerance * 1e3);
  EXPECT_GT(mean(serial), 0.0);
  EXPECT_NEAR(mean(parallel), mean(serial), tolerance);
}

std::pair<std::vector<double>, std::vector<double>> RodRanksTest::run_both(std::map<std::string, std::string> vars,
                                                                          int nrods)
{
  vars = flat_plates(vars);
  const int me = mpi_rank();

  // A plugin registers its commands in one instance at a time: the world instance goes first.
  LammpsTest::TearDown();
  std::vector<double> serial(nrods, 0.0);
  if (me == 0) {
    const char *args[] = {"lmp", "-log", "none", "-nocite", "-screen", "none"};
    auto *alone = new LAMMPS_NS::LAMMPS(6, const_cast<char **>(args), MPI_COMM_SELF);
    auto serial_vars = vars;
    serial_vars["tag"] = "test_ranks_serial";
    lammps_commands_string(alone, ("plugin load " ACTIVEGRAIN_PLUGIN_FILE "\n" + deck(serial_vars, nrods)).c_str());
    char message[2048] = "";
    if (lammps_has_error(alone)) lammps_get_last_error_message(alone, message, sizeof(message));
    EXPECT_STREQ(message, "");
    serial = speeds(alone, nrods);
    delete alone;
  }
  broadcast_from_rank0(serial);
  LammpsTest::SetUp();

  vars["tag"] = "test_ranks_parallel";
  command(deck(vars, nrods));
  return {serial, speeds(lmp, nrods)};
}

void RodRanksTest::compare(std::map<std::string, std::string> vars, double rod_tol, double mean_tol)
{
  const int nrods = 4;
  const auto [serial, parallel] = run_both(vars, nrods);
  if (mpi_rank() == 0) {
    int nprocs = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &nprocs);
    std::printf("[ measured ] %d ranks vs 1 rank (mm/s):", nprocs);
    for (int k = 0; k < nrods; ++k) std::printf(" %+.3f/%+.3f", parallel[k] * 1e3, serial[k] * 1e3);
    std::printf("\n");
  }
  for (int k = 0; k < nrods; ++k) {
    EXPECT_GT(serial[k], 0.0);
    EXPECT_NEAR(parallel[k] / serial[k], 1.0, rod_tol) << "rod " << k + 1;
  }
  EXPECT_NEAR(mean(parallel) / mean(serial), 1.0, mean_tol);
}
