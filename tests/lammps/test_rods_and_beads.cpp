// examples/rods-and-beads: the requested area fractions are reached within 0.005 (box, channel,
// annulus), and the rods lie flat in the plate plane.
#include "lammps_fixture.h"

#include "atom.h"

#include <cmath>

class RodsAndBeadsTest : public LammpsTest {
 protected:
  void create(const std::string &vars, double phi_b, double phi_r)
  {
    command(vars + "\nvariable out index test_rods_and_beads_out\n"
                   "variable create_dir index " ACTIVEGRAIN_SOURCE_DIR "/examples/rods-and-beads\n"
                   "include ${create_dir}/in.create\n"
                   "run 0 post no");
    EXPECT_NEAR(value("v_phi_b_reached"), phi_b, 0.005);
    EXPECT_NEAR(value("v_phi_r_reached"), phi_r, 0.005);
    // Rods lie flat: every rod atom at the same height.
    const int n = lmp->atom->nlocal;
    for (int i = 0; i < n; ++i)
      if (lmp->atom->type[i] <= 3) EXPECT_NEAR(lmp->atom->x[i][2], value("v_zrod"), 1e-9);
  }
};

TEST_F(RodsAndBeadsTest, PeriodicBoxAtPaperFractions)
{
  create("variable phi_b index 0.80\nvariable phi_r index 0.03", 0.80, 0.03);
}

TEST_F(RodsAndBeadsTest, Channel)
{
  create("variable geometry index channel\nvariable Lx index 100e-3\nvariable Ly index 31e-3\n"
         "variable phi_b index 0.75\nvariable phi_r index 0.015",
         0.75, 0.015);
}

TEST_F(RodsAndBeadsTest, Annulus)
{
  create("variable geometry index annulus\nvariable R_out index 40e-3\nvariable R_in index 20e-3\n"
         "variable phi_b index 0.71\nvariable phi_r index 0.02",
         0.71, 0.02);
}
