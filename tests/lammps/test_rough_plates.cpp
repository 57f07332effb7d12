// fix wall/impulse rough: a frozen random plate surface. Roughness 0 is the flat plate bit for
// bit; a vertical drop is deflected sideways as the asked rms slope predicts, never gaining
// energy; bad values are refused with the keyword named.
#include "beads_deck.h"

#include "atom.h"

#include <cmath>
#include <string>

namespace {

// Positions and velocities of every atom, gathered by ID, for bit-for-bit comparisons.
std::vector<double> state_of(LAMMPS_NS::LAMMPS *lmp)
{
  const auto natoms = (int) lmp->atom->natoms;
  std::vector<double> x(3 * natoms), v(3 * natoms);
  lammps_gather_atoms(lmp, (char *) "x", 1, 3, x.data());
  lammps_gather_atoms(lmp, (char *) "v", 1, 3, v.data());
  x.insert(x.end(), v.begin(), v.end());
  return x;
}

}    // namespace

TEST_F(BeadMonolayer, RoughnessZeroIsTheFlatPlateBitForBit)
{
  load_deck("variable nx index 6\nvariable ny index 4\nvariable rough index 0");
  command("run 1500 post no");
  const std::vector<double> with_keyword = state_of(lmp);

  TearDown();
  SetUp();
  load_deck("variable nx index 6\nvariable ny index 4\nvariable rough index 0");
  command("unfix plates\n"
          "fix plates all wall/impulse zlo 0.0 gap ${gap} vibrate ${A} ${f} 0.0 e 0.3 mu 0.01\n"
          "run 1500 post no");
  const std::vector<double> without = state_of(lmp);
  ASSERT_EQ(with_keyword.size(), without.size());
  for (std::size_t k = 0; k < without.size(); ++k) ASSERT_EQ(with_keyword[k], without[k]) << k;
}

TEST_F(BeadMonolayer, RoughPlateDeflectsADropByTheRmsSlope)
{
  // 400 beads far apart (a 2 mm lattice, jittered so that they sample every part of the 1 mm
  // cells of the surface) fall at 0.1 m/s on a still frictionless plate with rms slope 0.02. Each
  // leaves along its local normal: horizontal speed (1 + e) v n_z |n_h|, so the rms horizontal
  // speed over the beads is (1 + e) v times the rms slope, within the sampling error of 400
  // points (~5 %; 0.7 % off with this seed).
  const double slope = 0.02, e = 0.3, v0 = 0.1;
  command("units si\natom_style sphere\natom_modify map array\nboundary p p f\ncomm_modify vel yes\n"
          "region box block 0 0.04 0 0.04 -1e-4 2e-3 units box\ncreate_box 1 box\n"
          "lattice sc 0.002 origin 0.25 0.25 0\nregion layer block INF INF INF INF -0.1 0.1 units lattice\n"
          "create_atoms 1 region layer\ndisplace_atoms all random 5e-4 5e-4 0 4821 units box\nset type 1 z 0.0008\nset type 1 diameter 0.001\nset type 1 density 2700\n"
          "velocity all set 0 0 -0.1 units box\nneighbor 1e-4 bin\n"
          "pair_style gran/impulse\npair_coeff * * 0.3 0.0\nfix nve all nve/sphere\ntimestep 1e-5\n"
          "variable vh2 atom vx*vx+vy*vy\nvariable ke atom 0.5*mass*(vx*vx+vy*vy+vz*vz)\n"
          "compute vh2 all reduce sum v_vh2\ncompute ke all reduce sum v_ke\nthermo_style custom step c_ke c_vh2\n");
  command(fmt::format("fix plate all wall/impulse zlo 0.0 e {} mu 0.0 rough {} 1e-3 7", e, slope));
  ASSERT_EQ(lmp->atom->natoms, 400);
  command("run 0 post no");
  const double ke_before = value("c_ke");
  command("run 600 post no");    // every bead has bounced once (0.3 mm at 0.1 m/s)
  const double rms_horizontal = std::sqrt(value("c_vh2") / 400.0);
  EXPECT_NEAR(rms_horizontal / ((1 + e) * v0), slope, 0.1 * slope);
  EXPECT_GT(value("vz[1]"), 0.0);
  EXPECT_LE(value("c_ke"), ke_before * (e * e + 1e-3));    // what is left after the impact
}

TEST_F(BeadMonolayer, BadRoughnessGivesClearErrors)
{
  load_deck("variable nx index 2\nvariable ny index 2");
  const std::string fix = "fix bad all wall/impulse zlo 0.0 e 0.3 mu 0.01 rough ";
  EXPECT_THAT(error_of(fix + "-0.01 1e-3 5"), ::testing::HasSubstr("Fix wall/impulse: rough rms slope"));
  EXPECT_THAT(error_of(fix + "0.5 1e-3 5"), ::testing::HasSubstr("Fix wall/impulse: rough rms slope"));
  EXPECT_THAT(error_of(fix + "0.02 0 5"), ::testing::HasSubstr("Fix wall/impulse: rough correlation length"));
  EXPECT_THAT(error_of(fix + "0.02 1e-3 0"), ::testing::HasSubstr("Fix wall/impulse: rough seed"));
  EXPECT_THAT(error_of(fix + "0.02 1e-3"), ::testing::HasSubstr("Fix wall/impulse: rough needs"));
}
