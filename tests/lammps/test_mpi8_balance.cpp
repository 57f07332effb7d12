// fix balance with rods (fix rigid/rod bodies), on 1, 2, 4 and 8 ranks (test_mpi8_*): sub-domain
// cuts moved every 50 steps by the shift method (`processors * * 1`) and by recursive coordinate
// bisection (rcb, `comm_style tiled`) carry rods between ranks, and cut through them, at every
// rebalancing. Every rod stays whole (atoms, bodies and each rod's body ID conserved), the rods
// walk as in the serial run, and a run continued from a restart file written after rebalancing
// goes on as the uninterrupted one.
#include "lammps_fixture.h"
#include "rod_walking.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "fix.h"
#include "modify.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

using namespace rod_walking;

namespace {

constexpr int NRODS = 16;
constexpr double START = 0.05, WALK = 0.08;    // s, at the decks' time step 1e-4 s
constexpr int EVERY = 50;                     // steps between rebalancings

// How the sub-domains are cut and rebalanced.
enum class Balance { NONE, SHIFT, RCB };

std::string balance_commands(Balance balance)
{
  switch (balance) {
    case Balance::SHIFT: return "fix balance all balance " + std::to_string(EVERY) + " 1.0 shift xy 10 1.0\n";
    case Balance::RCB: return "fix balance all balance " + std::to_string(EVERY) + " 1.0 rcb\n";
    default: return "";
  }
}

// 16 rods (in.single-rod, nside 4) on plates of rms slope 0.01 (correlation length 1 mm), 20 mm
// apart on the lines x, y = 0, 20, 40, 60 mm of an 80 mm square (rod k is molecule k), set up
// and run START seconds, with the rebalancing asked for from the start.
void rods(LAMMPS_NS::LAMMPS *lmp, Balance balance, const std::string &tag)
{
  std::string cmd = balance == Balance::RCB ? "comm_style tiled\n" : "processors * * 1\n";
  for (const auto &[name, value] : std::map<std::string, std::string>{
           {"shift", "-10e-3"}, {"dt", "1e-4"}, {"nside", "4"}, {"seed", "1"}, {"rough", "0.01"},
           {"rough_length", "1e-3"}, {"tag", tag}, {"time", "0"}})
    cmd += "variable " + name + " index " + value + "\n";
  cmd += "include " ACTIVEGRAIN_SOURCE_DIR "/examples/single-rod/in.single-rod\n"
         "undump bodies\nthermo 0\n" + balance_commands(balance) +
      "run " + std::to_string((int) std::lround(START / 1e-4)) + " post no\n";
  lammps_commands_string(lmp, cmd.c_str());
}

// Per rod (molecule 1..16): the body ID its atoms carry (fix rigid/rod's f_rods[4]), or -1 where
// its atoms disagree or it has not 9 atoms; then the number of atoms and of distinct body IDs.
std::vector<double> bodies(LAMMPS_NS::LAMMPS *lmp)
{
  int dim = 0;
  auto **out = (double **) lmp->modify->get_fix_by_id("rods")->extract("polar", dim);
  std::vector<double> low(NRODS, 1e300), high(NRODS, -1e300), count(NRODS, 0.0);
  for (int i = 0; i < lmp->atom->nlocal; ++i) {
    const int k = (int) lmp->atom->molecule[i] - 1;
    if (k < 0 || k >= NRODS) continue;
    low[k] = std::min(low[k], out[i][3]);
    high[k] = std::max(high[k], out[i][3]);
    count[k] += 1.0;
  }
  MPI_Allreduce(MPI_IN_PLACE, low.data(), NRODS, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, high.data(), NRODS, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, count.data(), NRODS, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  std::vector<double> ids;
  for (int k = 0; k < NRODS; ++k) ids.push_back(low[k] == high[k] && count[k] == 9.0 ? low[k] : -1.0);
  const std::set<double> distinct(ids.begin(), ids.end());
  ids.push_back((double) lmp->atom->natoms);
  ids.push_back((double) distinct.size());
  return ids;
}

// The largest move of any sub-domain boundary since `before` (lo and hi in x and y, over ranks).
double largest_cut_move(LAMMPS_NS::LAMMPS *lmp, const std::vector<double> &before)
{
  double local = 0.0;
  for (int d = 0; d < 2; ++d) {
    local = std::max(local, std::fabs(lmp->domain->sublo[d] - before[2 * d]));
    local = std::max(local, std::fabs(lmp->domain->subhi[d] - before[2 * d + 1]));
  }
  double all = 0.0;
  MPI_Allreduce(&local, &all, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return all;
}

std::vector<double> cuts(LAMMPS_NS::LAMMPS *lmp)
{
  return {lmp->domain->sublo[0], lmp->domain->subhi[0], lmp->domain->sublo[1], lmp->domain->subhi[1]};
}

// The serial reference: rank 0 alone, no rebalancing; per rod its speed along its axis over WALK.
std::vector<double> serial_speeds(LAMMPS_NS::LAMMPS *alone)
{
  rods(alone, Balance::NONE, "balance_serial");
  lammps_commands_string(alone, measure(NRODS, WALK).c_str());
  EXPECT_FALSE(lammps_has_error(alone));
  return speeds(alone, NRODS);
}

}    // namespace

class BalanceTest : public LammpsTest {
 protected:
  void check(Balance balance, const char *name);

  // Atoms and rods conserved, each rod one body of 9 atoms with the body ID it had.
  static void expect_whole(const std::vector<double> &before, const std::vector<double> &after,
                           const std::string &name)
  {
    if (mpi_rank() == 0)
      std::printf("[ measured ] %s on %d ranks: %g atoms, %g distinct body IDs (before: %g, %g)\n", name.c_str(),
                  mpi_ranks(), after[NRODS], after[NRODS + 1], before[NRODS], before[NRODS + 1]);
    EXPECT_EQ(after[NRODS], 9.0 * NRODS) << name;
    EXPECT_EQ(after[NRODS + 1], NRODS) << name;
    for (int k = 0; k < NRODS; ++k) {
      EXPECT_GT(before[k], 0.0) << name << ": rod " << k + 1 << " is not one body of 9 atoms";
      EXPECT_EQ(after[k], before[k]) << name << ": rod " << k + 1 << " changed its body";
    }
  }

  // Each rod's centre of mass, x and y (groups rod1 .. rod16).
  std::vector<double> positions()
  {
    std::vector<double> x;
    for (int k = 1; k <= NRODS; ++k)
      for (const char *c : {"x", "y"}) x.push_back(value("xcm(rod" + std::to_string(k) + "," + c + ")"));
    return x;
  }
};

// Rods rebalanced by `balance` every 50 steps, from the start:
// - every rod whole after START and after WALK more (atoms, rods, each rod's body ID), the cuts
//   moved meanwhile;
// - over WALK, the mean speed of the 16 rods within three standard errors of the rod-by-rod
//   differences plus 2 per cent of the serial run's without rebalancing (as
//   test_mpi8_corners.cpp; measured: equal to 4 digits on 2, 4 and 8 ranks);
// - a restart file written after START (after 10 rebalancings), read back and continued over
//   WALK with the same rebalancing (the cuts are not in the file: the continuation asks for the
//   same processors or comm_style and fix balance, which cut anew from the positions read):
//   every rod at the uninterrupted run's position within 1e-12 m, with its body ID (the rods
//   move about 0.4 mm; measured: at most 4e-15 m on 1, 2, 4 and 8 ranks, where another order of
//   summing a body's forces changes the last bits).
void BalanceTest::check(Balance balance, const char *name)
{
  const auto serial = serial_reference(NRODS, serial_speeds);
  const std::string restart = std::string("test_balance_") + name + ".restart";
  const std::string walk_steps = std::to_string((int) std::lround(WALK / 1e-4));
  rods(lmp, balance, std::string("balance_") + name);
  ASSERT_FALSE(lammps_has_error(lmp));
  const auto start = cuts(lmp);
  const auto before = bodies(lmp);
  command("write_restart " + restart);
  command(measure(NRODS, WALK));
  const auto parallel = speeds(lmp, NRODS);
  const double moved = largest_cut_move(lmp, start);
  const auto uninterrupted = positions();
  expect_whole(before, bodies(lmp), name);

  const double tolerance = speed_tolerance(serial, parallel);
  if (mpi_rank() == 0)
    std::printf("[ measured ] %s on %d ranks: cuts moved up to %.3f mm while measuring; mean speed of 16 rods "
                "%.4f mm/s, on 1 rank without rebalancing %.4f (allowed difference %.3f)\n",
                name, mpi_ranks(), moved * 1e3, mean(parallel) * 1e3, mean(serial) * 1e3, tolerance * 1e3);
  if (mpi_ranks() > 1) EXPECT_GT(moved, 0.0) << name << ": the rebalancing moved no cut";
  EXPECT_GT(mean(serial), 1e-3);
  EXPECT_NEAR(mean(parallel), mean(serial), tolerance) << name;

  TearDown();
  SetUp();
  std::string groups;
  for (int k = 1; k <= NRODS; ++k) groups += "group rod" + std::to_string(k) + " molecule " + std::to_string(k) + "\n";
  command(std::string("atom_modify map array\n") + (balance == Balance::RCB ? "comm_style tiled\n" : "processors * * 1\n") +
          "read_restart " + restart + "\n"
          "fix molecule_ids all property/atom mol ghost yes\n" +
          single_rod_styles(std::string("out/rod_balance_restart_") + name + ".mol", "0.01 1e-3 1", false) +
          "timestep 1e-4\nthermo 0\n" + balance_commands(balance) + groups + "run " + walk_steps + " post no");
  const auto continued = positions();
  expect_whole(before, bodies(lmp), std::string(name) + ", continued from the restart file");
  double largest = 0.0;
  for (size_t k = 0; k < continued.size(); ++k) largest = std::max(largest, std::fabs(continued[k] - uninterrupted[k]));
  if (mpi_rank() == 0)
    std::printf("[ measured ] restart after %s rebalancing on %d ranks: largest difference of a rod's centre from "
                "the uninterrupted run %.3g m after %s steps\n", name, mpi_ranks(), largest, walk_steps.c_str());
  EXPECT_LT(largest, 1e-12) << name;
}

TEST_F(BalanceTest, ShiftRebalancedRodsStayWholeWalkAsOnOneRankAndRestartExactly)
{
  check(Balance::SHIFT, "shift");
}

TEST_F(BalanceTest, RcbRebalancedRodsStayWholeWalkAsOnOneRankAndRestartExactly)
{
  check(Balance::RCB, "rcb");
}
