// Rough plates are the same surface on 1, 2 and 4 ranks (this file also runs under mpirun -np 2
// and -np 4): the height field is a function of position and seed only, so a bead monolayer on
// rough plates moves as in the serial run, to round-off, until chaos amplifies it.
#include "beads_deck.h"

#include <cmath>
#include <string>
#include <vector>

namespace {

// Identical to round-off on 2 ranks up to ~400 steps here (1e-6 relative by 600: chaos).
constexpr int kSteps = 300;

// Total and horizontal kinetic energy of the beads after kSteps on plates with rms slope 0.05.
// The deck's random start heights (and so the velocities seeded from positions) depend on the
// number of ranks: heights and velocities are set again from positions alone.
std::vector<double> energies(LAMMPS_NS::LAMMPS *lmp)
{
  lammps_commands_string(lmp, "variable steps index 0\nvariable rough index 0.05\n"
                              "include " ACTIVEGRAIN_SOURCE_DIR "/examples/beads-vibrated/in.beads-vibrated\n"
                              "variable zstart atom ${gap}/2+0.05e-3*sin(7e3*x+1.3e4*y)\n"
                              "set type 1 z v_zstart\nvelocity all create 1.0e13 ${seed} loop geom\n"
                              "variable kh atom 0.5*mass*(vx*vx+vy*vy)\ncompute kh all reduce sum v_kh\n"
                              "thermo_style custom step c_ke c_kh\nthermo 0\n");
  lammps_command(lmp, fmt::format("run {} post no", kSteps).c_str());
  std::vector<double> result;
  for (const char *name : {"c_ke", "c_kh"}) {
    lammps_command(lmp, fmt::format("variable agtest_e equal {}", name).c_str());
    auto *p = (double *) lammps_extract_variable(lmp, "agtest_e", nullptr);
    result.push_back(p ? *p : -1.0);
    lammps_free(p);
  }
  return result;
}

}    // namespace

TEST_F(BeadMonolayer, RoughPlatesMoveBeadsAsOnOneRank)
{
  const std::vector<double> serial = serial_reference(2, energies);
  const std::vector<double> parallel = energies(lmp);
  ASSERT_FALSE(lammps_has_error(lmp));
  ASSERT_GT(serial[1], 0.0);
  EXPECT_NEAR(parallel[0], serial[0], 1e-9 * serial[0]);
  EXPECT_NEAR(parallel[1], serial[1], 1e-9 * serial[1]);
}
