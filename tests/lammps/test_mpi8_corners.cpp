// Rank invariance where sub-domains meet at corners: this file also runs under mpirun -np 2, 4
// and 8 (test_mpi8_*), with `processors * * 1`, which splits the monolayer's plane only (2 x 1,
// 2 x 2 and 4 x 2 sub-domains). Rank 0 runs each system alone (MPI_COMM_SELF) as the reference,
// then all ranks run it. Short systems: on 8 ranks sharing two cores a step costs milliseconds.
#include "beads_deck.h"
#include "rod_walking.h"

#include "comm.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

using namespace rod_walking;

namespace {

// 16 rods on plates of rms slope 0.01 (correlation length 1 mm) in an 80 mm square, 20 mm apart,
// centred on the lines x, y = 0, 20, 40, 60 mm: with 4 x 2 sub-domains (8 ranks) the cuts are at
// x = 0, 20, 40, 60 and y = 0, 40 mm (or x and y swapped), so 8 rods start on a corner of four
// sub-domains and the other 8 on an edge of two. The decks' time step, 0.05 s to settle, 0.15 s measured.
constexpr int NRODS = 16;
constexpr double START = 0.05, WALK = 0.15;    // s

// Per rod (1..16) its mean speed along its own axis over WALK, then compute polar/rod's polar
// order |<p>| and rod count at the end.
std::vector<double> walk_and_order(LAMMPS_NS::LAMMPS *lmp, const std::string &tag)
{
  std::string vars = "processors * * 1\n";
  for (const auto &[name, value] : std::map<std::string, std::string>{
           {"shift", "-10e-3"}, {"dt", "1e-4"}, {"nside", "4"}, {"seed", "1"}, {"rough", "0.01"},
           {"rough_length", "1e-3"}, {"tag", tag}})
    vars += "variable " + name + " index " + value + "\n";
  lammps_commands_string(lmp, (vars + "variable time index " + std::to_string(START) + "\n"
                               "include " ACTIVEGRAIN_SOURCE_DIR "/examples/single-rod/in.single-rod\n"
                               "undump bodies\nthermo 0\ncompute order all polar/rod\n" +
                               measure(NRODS, WALK)).c_str());
  std::vector<double> result = speeds(lmp, NRODS);
  result.push_back(extracted(lmp, "c_order[1]"));
  result.push_back(extracted(lmp, "c_order[6]"));
  return result;
}

}    // namespace

class CornersTest : public BeadMonolayer {};

// Walking speed and polar order of rods that start on sub-domain corners. The rods bounce
// chaotically on the bumps, so single rods may decorrelate between the serial and the parallel
// run: their mean speeds must agree within three standard errors of the rod-by-rod differences
// plus 2 per cent (measured: equal to 4 digits after 0.15 s on 2, 4 and 8 ranks; a rod solved
// twice, or missing its contacts across a cut, walked 15 per cent slower). Their headings turn by
// a few degrees in 0.15 s: the polar order of the 16 rods agrees within 0.02 (it is 1 for aligned
// rods, about 0.2 for these random headings), and compute polar/rod counts each rod once.
TEST_F(CornersTest, RodsWalkAndOrderAsOnOneRankAcrossSubdomainCorners)
{
  const auto serial = serial_reference(NRODS + 2, [](LAMMPS_NS::LAMMPS *alone) {
    auto r = walk_and_order(alone, "corners_serial");
    EXPECT_FALSE(lammps_has_error(alone));
    return r;
  });
  const auto parallel = walk_and_order(lmp, "corners_parallel");
  ASSERT_FALSE(lammps_has_error(lmp));
  const std::vector<double> vs(serial.begin(), serial.begin() + NRODS), vp(parallel.begin(), parallel.begin() + NRODS);
  const double tolerance = speed_tolerance(vs, vp);
  if (mpi_rank() == 0)
    std::printf("[ measured ] %d ranks (%d x %d x %d): mean speed of 16 rods %.4f mm/s, on 1 rank %.4f (allowed "
                "difference %.3f); polar order %.5f, on 1 rank %.5f; rods counted %g\n",
                mpi_ranks(), lmp->comm->procgrid[0], lmp->comm->procgrid[1], lmp->comm->procgrid[2], mean(vp) * 1e3,
                mean(vs) * 1e3, tolerance * 1e3, parallel[NRODS], serial[NRODS], parallel[NRODS + 1]);
  EXPECT_EQ(lmp->comm->procgrid[2], 1);
  EXPECT_GT(mean(vs), 1e-3);    // they walk (about 4.5 mm/s)
  EXPECT_NEAR(mean(vp), mean(vs), tolerance);
  EXPECT_NEAR(parallel[NRODS], serial[NRODS], 0.02);
  EXPECT_EQ(parallel[NRODS + 1], 16.0);
  EXPECT_EQ(serial[NRODS + 1], 16.0);
}

namespace {

// At twice the deck's time step: 250 steps per vibration period.
constexpr int WARMUP = 500;    // steps (2 periods)
constexpr int BLOCKS = 6;
constexpr int BLOCK = 250;     // steps per block average (1 period)

// The bead monolayer (360 beads, area fraction 0.75, calibrated rough plates), split in the
// plane only: its mean kinetic energy over BLOCKS periods and the standard error of the blocks.
std::vector<double> agitation(LAMMPS_NS::LAMMPS *lmp)
{
  lammps_commands_string(lmp, "processors * * 1\nvariable steps index 0\nvariable dt index 2e-5\n"
                              "include " ACTIVEGRAIN_SOURCE_DIR "/examples/beads-vibrated/in.beads-vibrated\n"
                              "thermo 0\n");
  lammps_command(lmp, fmt::format("run {} post no", WARMUP).c_str());
  lammps_command(lmp, fmt::format("fix keavg all ave/time 10 {} {} c_ke", BLOCK / 10, BLOCK).c_str());
  std::vector<double> blocks;
  for (int k = 0; k < BLOCKS; ++k) {
    lammps_command(lmp, fmt::format("run {} post no", BLOCK).c_str());
    blocks.push_back(extracted(lmp, "f_keavg"));
  }
  const double m = mean(blocks);
  return {m, standard_error(blocks), extracted(lmp, "count(all)")};
}

}    // namespace

// The agitated bead bed (at twice the deck's time step): the mean kinetic energy over 6 periods
// within four combined standard errors of the blocks plus 1 per cent (the bed's collisions
// decorrelate the runs within a period), no bead lost.
TEST_F(CornersTest, BedIsAgitatedAsOnOneRankAcrossSubdomainCorners)
{
  const auto serial = serial_reference(3, [](LAMMPS_NS::LAMMPS *alone) {
    auto r = agitation(alone);
    EXPECT_FALSE(lammps_has_error(alone));
    return r;
  });
  const auto parallel = agitation(lmp);
  ASSERT_FALSE(lammps_has_error(lmp));
  const double allowed = 4.0 * std::hypot(serial[1], parallel[1]) + 0.01 * serial[0];
  if (mpi_rank() == 0)
    std::printf("[ measured ] %d ranks (%d x %d x %d): mean kinetic energy %.4g +- %.2g J, on 1 rank %.4g +- %.2g "
                "(allowed difference %.2g); %g beads\n",
                mpi_ranks(), lmp->comm->procgrid[0], lmp->comm->procgrid[1], lmp->comm->procgrid[2], parallel[0],
                parallel[1], serial[0], serial[1], allowed, parallel[2]);
  ASSERT_GT(serial[0], 0.0);
  EXPECT_NEAR(parallel[0], serial[0], allowed);
  EXPECT_EQ(parallel[2], 360.0);
}
