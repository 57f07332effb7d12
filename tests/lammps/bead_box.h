// A LAMMPS instance with a box of 10 x 10 x 2 mm (SI units, z bounded) into which tests place
// a few 1 mm aluminium beads by hand.
#pragma once

#include "lammps_fixture.h"

#include "atom.h"

#include <string>

class BeadBox : public LammpsTest {
 protected:
  static constexpr const char *BOX = R"(
units si
atom_style sphere
atom_modify map array
boundary p p f
region box block 0 0.01 0 0.01 0 0.002
create_box 2 box
comm_modify vel yes
neighbor 0.0002 bin
timestep 1e-5
)";
  static constexpr const char *PAIR = "pair_style gran/impulse\npair_coeff * * 0.3 0.05\n";

  void SetUp() override
  {
    LammpsTest::SetUp();
    command(BOX);
  }
  // A bead of the given type and diameter (density 2700) at x, y, z, moving with vx, vy, vz.
  void bead(double x, double y, double z, double vx, double vy, double vz, int type = 1, double diameter = 0.001)
  {
    command(fmt::format("create_atoms {} single {} {} {}", type, x, y, z));
    const int id = (int) lmp->atom->natoms;
    command(fmt::format("set atom {} diameter {}\nset atom {} density 2700", id, diameter, id));
    command(fmt::format("set atom {} vx {} vy {} vz {}", id, vx, vy, vz));
  }
};
