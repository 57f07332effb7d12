// A rod split between ranks bounces as on one rank: its wall contacts are solved together on
// one rank (pair gran/impulse), not once per rank that owns some of its atoms. Rank 0 runs the
// bounce alone (MPI_COMM_SELF) as the reference, then all ranks run it (this file also runs
// under mpirun -np 2 and -np 4).
#include "lammps_fixture.h"
#include "rod_deck.h"

#include "atom.h"

#include <array>
#include <cmath>
#include <cstdio>

using namespace rod_deck;

namespace {

const int BOUNCE_STEPS = 150;    // 0.05 mm at 0.1 m/s: the rod hits after ~50 steps

struct Bounce {
  std::string newton = "on";
  // A 1 mm bead falls with the rod 0.1 mm above its nose, to be hit by the rebounding rod: its
  // atom and the nose atom are both ghosts on the rod's solver rank (which owns the tail).
  bool bead = false;
  // The plate is the bottom face of a block region (fix wall/impulse/region) that ends at the
  // periodic box, and the rod lies across the periodic corner: its solver rank sees part of it
  // as ghost images outside the box.
  bool region_wall = false;
};

// One rod centred on the sub-domain corner (0, 0) of 2 and 4 ranks (or on the periodic corner),
// along 30 degrees in the plane, its lowest points 0.05 mm above a still plate, dropped flat
// onto it.
std::string bounce_deck(const std::string &file, const Bounce &setup)
{
  const std::string plate = setup.region_wall
      ? "region floor block -6e-3 6e-3 -6e-3 6e-3 0 INF open 1 open 2 open 3 open 4 open 6 units box\n"
        "fix plates all wall/impulse/region floor e 0.5 mu 0.2\nvariable jz equal f_plates[3]\n"
      : "fix plates all wall/impulse zlo 0.0 e 0.5 mu 0.2\nvariable jz equal f_plates[6]\n";
  return "newton " + setup.newton + "\nunits si\natom_style sphere\natom_modify map array\nboundary p p f\n"
         "fix molecule_ids all property/atom mol ghost yes\n"
         "region box block -6e-3 6e-3 -6e-3 6e-3 -1e-3 3e-3\ncreate_box 4 box\n"
         "comm_modify vel yes cutoff 6e-3\nneighbor 5e-4 bin\n" + rod_template(file) +
      flat_rod(5e-5) +
      (setup.region_wall ? "displace_atoms all move 6e-3 6e-3 0 units box\n" : "") +
      "group rod type 1 2 3\n" +
      (setup.bead ? "create_atoms 4 single $(x[9]) $(y[9]) $(z[9]+radius[9]+6e-4) units box\n"
              "set type 4 diameter 1e-3\nset type 4 density 2700\ngroup bead type 4\n"
              "fix beads bead nve/sphere\nvariable bead_vz equal vcm(bead,z)\n"
            : "") +
      "velocity all set 0.05 0.02 -0.1 units box\n"
      "pair_style gran/impulse\npair_coeff * * 0.3 0.05\n"
      "fix rods rod rigid/rod molecule mol rod\n" +
      plate + "timestep 1e-5\n"
      "variable vx equal vcm(all,x)\nvariable vy equal vcm(all,y)\nvariable vz equal vcm(all,z)\n"
      "variable wx equal omega(all,x)\nvariable wy equal omega(all,y)\nvariable wz equal omega(all,z)\n"
      // The impulse the plate reports delivering, summed over the steps, and the rod's mass and
      // initial vertical velocity, for momentum balance (no gravity).
      "fix delivered all ave/time 1 1 1 v_jz ave running\n"
      "variable mass equal mass(all)\nvariable vz0 equal $(vcm(all,z):%.17g)\n"
      "run " + std::to_string(BOUNCE_STEPS) + " post no\n"
      // Mean of the samples at steps 0 (setup: nothing delivered) to BOUNCE_STEPS.
      "variable delivered equal f_delivered*" + std::to_string(BOUNCE_STEPS + 1) + "\n"
      "variable momentum equal v_mass*(v_vz-v_vz0)\n";
}

// v (3), omega (3) of all atoms, impulse delivered by the plate (z), momentum change of all
// atoms (z), the bead's velocity (z; 0 without a bead)
std::array<double, 9> motion(void *lmp)
{
  std::array<double, 9> m{};
  const char *names[9] = {"vx", "vy", "vz", "wx", "wy", "wz", "delivered", "momentum", "bead_vz"};
  for (int k = 0; k < 9; ++k) {
    auto *value = (double *) lammps_extract_variable(lmp, names[k], nullptr);
    m[k] = value ? *value : 0.0;
    lammps_free(value);
  }
  return m;
}

}    // namespace

class RodBounceTest : public LammpsTest {
 protected:
  const std::string file = "test_mpi_rod_bounce.mol";
  void compare_with_one_rank(const Bounce &setup);
};

TEST_F(RodBounceTest, FlatRodAcrossSubdomainsBouncesAsOnOneRank)
{
  compare_with_one_rank(Bounce());
}

// With newton off no force reaches an owner from a ghost but through this style's own reverse
// communication: the same bounce.
TEST_F(RodBounceTest, FlatRodAcrossSubdomainsBouncesAsOnOneRankNewtonOff)
{
  Bounce setup;
  setup.newton = "off";
  compare_with_one_rank(setup);
}

// A rod whose contacts include a bead hit by its nose: the rod-bead contact is solved on the
// rod's solver rank from two ghost atoms, with the rod's plate contacts.
TEST_F(RodBounceTest, SplitRodHitsBeadAsOnOneRank)
{
  Bounce setup;
  setup.bead = true;
  compare_with_one_rank(setup);
}

// A region wall meets the ghost images of a rod's atoms outside the box where their owners are.
TEST_F(RodBounceTest, RodAcrossPeriodicCornerBouncesOnRegionWallAsOnOneRank)
{
  Bounce setup;
  setup.region_wall = true;
  compare_with_one_rank(setup);
}

void RodBounceTest::compare_with_one_rank(const Bounce &setup)
{
  int me = 0, nprocs = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  MPI_Comm_size(MPI_COMM_WORLD, &nprocs);

  // A plugin registers its commands in one instance at a time: the world instance goes first.
  LammpsTest::TearDown();
  std::array<double, 9> serial{};
  if (me == 0) {
    const char *args[] = {"lmp", "-log", "none", "-nocite", "-screen", "none"};
    auto *alone = new LAMMPS_NS::LAMMPS(6, const_cast<char **>(args), MPI_COMM_SELF);
    lammps_commands_string(alone, ("plugin load " ACTIVEGRAIN_PLUGIN_FILE "\n" + bounce_deck(file, setup)).c_str());
    char message[2048] = "";
    if (lammps_has_error(alone)) lammps_get_last_error_message(alone, message, sizeof(message));
    EXPECT_STREQ(message, "");
    serial = motion(alone);
    delete alone;
  }
  MPI_Bcast(serial.data(), 9, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  LammpsTest::SetUp();
  command(bounce_deck(file, setup));
  const auto parallel = motion(lmp);

  // Bounced: moving up, slower than it came (e = 0.5 at the contacts).
  EXPECT_GT(serial[2], 0.0);
  EXPECT_LT(serial[2], 0.1);
  if (nprocs > 1) {
    // Split between ranks indeed: no rank owns all 9 atoms of the rod (types 1 to 3).
    int most = 0, mine = 0;
    for (int i = 0; i < lmp->atom->nlocal; ++i) mine += lmp->atom->type[i] <= 3;
    MPI_Allreduce(&mine, &most, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    EXPECT_LT(most, SPHERES);
  }
  const double speed = std::sqrt(serial[0] * serial[0] + serial[1] * serial[1] + serial[2] * serial[2]);
  const double half_length = 0.5 * LENGTH;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(parallel[k], serial[k], 1e-12 * speed) << "v " << k;
    EXPECT_NEAR(parallel[3 + k] * half_length, serial[3 + k] * half_length, 1e-12 * speed) << "omega " << k;
  }
  if (setup.bead) {
    // Hit by the rod: thrown up.
    EXPECT_GT(serial[8], 0.0);
    EXPECT_NEAR(parallel[8], serial[8], 1e-12 * speed);
  }
  // The plate reports each contact's impulse once: it is the change of momentum.
  EXPECT_GT(parallel[7], 0.0);
  EXPECT_NEAR(parallel[6], parallel[7], 1e-12 * parallel[7]);
  EXPECT_NEAR(parallel[6], serial[6], 1e-12 * serial[6]);
  if (me == 0)
    std::printf("[ measured ] newton %s, %d ranks: v = %.15g %.15g %.15g, 1 rank: %.15g %.15g %.15g\n",
                setup.newton.c_str(), nprocs, parallel[0], parallel[1], parallel[2], serial[0], serial[1], serial[2]);
}

// On several ranks the solver rank of a rod must see a neighbor cutoff beyond the rod's far end.
TEST_F(RodBounceTest, ShortGhostCutoffIsAnErrorOnSeveralRanks)
{
  int nprocs = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &nprocs);
  const std::string deck = bounce_deck(file, Bounce());
  // Ghost cutoff 4 mm: enough for fix rigid/rod (half the rod), not for the rod's contacts.
  std::string shorter = deck;
  shorter.replace(shorter.find("cutoff 6e-3"), 11, "cutoff 4e-3");
  const std::string message = error_of(shorter);
  if (nprocs == 1) {
    EXPECT_EQ(message, "");
  } else {
    EXPECT_NE(message.find("Pair gran/impulse: rigid body span"), std::string::npos) << message;
    EXPECT_NE(message.find("use comm_modify cutoff"), std::string::npos) << message;
  }
}
