// compute areafrac/chunk and compute polar/rod: exact area fractions of known packings, on any
// number of ranks (this file also runs under mpirun -np 2 and -np 4), and clear errors.
#include "lammps_fixture.h"

#include "compute.h"
#include "modify.h"

#include <cmath>

namespace {

class ComputesTest : public LammpsTest {
 protected:
  // 100 unit beads on a square lattice of spacing 1 in a 10 x 10 monolayer cell.
  void bead_lattice()
  {
    command(R"(units lj
atom_style sphere
dimension 3
boundary p p f
comm_modify vel yes
lattice sc 1.0 origin 0.5 0.5 0.5
region box block 0 10 0 10 0 1.12 units box
create_box 1 box
create_atoms 1 region box
set type 1 diameter 1.0
set type 1 density 1.0)");
  }
  double array(const char *id, int row, int col)
  {
    auto *c = lmp->modify->get_compute_by_id(id);
    c->compute_array();
    return c->array[row][col];
  }
};

TEST_F(ComputesTest, SquareLatticeInSlabsIsPiOverFour)
{
  bead_lattice();
  command(R"(compute slabs all chunk/atom bin/1d x lower 2.0 units box
compute phi all areafrac/chunk slabs
run 0 post no)");
  auto *c = lmp->modify->get_compute_by_id("phi");
  c->compute_array();
  ASSERT_EQ(c->size_array_rows, 5);
  for (int bin = 0; bin < 5; ++bin) {
    EXPECT_NEAR(c->array[bin][0], M_PI / 4, 1e-12) << "bin " << bin;
    EXPECT_EQ(c->array[bin][1], 0.0);    // no rods
    EXPECT_EQ(c->array[bin][2], 0.0);
  }
}

TEST_F(ComputesTest, TwoDimensionalBinsCountEachBeadOnce)
{
  bead_lattice();
  command(R"(compute cells all chunk/atom bin/2d x lower 5.0 y lower 2.0 units box
compute phi all areafrac/chunk cells
run 0 post no)");
  auto *c = lmp->modify->get_compute_by_id("phi");
  c->compute_array();
  ASSERT_EQ(c->size_array_rows, 10);
  for (int bin = 0; bin < 10; ++bin) EXPECT_NEAR(c->array[bin][0], M_PI / 4, 1e-12);
}

TEST_F(ComputesTest, RingBinsUseTheRingArea)
{
  // Beads on two circles, r = 2 and r = 4 (n = 8 and 16), in rings 1-3 and 3-5.
  command(R"(units lj
atom_style sphere
boundary f f f
region box block -6 6 -6 6 0 1.12 units box
create_box 1 box)");
  for (auto [radius, n] : {std::pair{2.0, 8}, std::pair{4.0, 16}})
    for (int k = 0; k < n; ++k)
      command(fmt::format("create_atoms 1 single {} {} 0.5 units box", radius * cos(2 * M_PI * k / n),
                          radius * sin(2 * M_PI * k / n)));
  command(R"(set type 1 diameter 0.8
set type 1 density 1.0
compute rings all chunk/atom bin/cylinder z lower 1.12 0 0 1 5 2 units box
compute phi all areafrac/chunk rings
run 0 post no)");
  auto *c = lmp->modify->get_compute_by_id("phi");
  c->compute_array();
  ASSERT_EQ(c->size_array_rows, 2);
  const double bead = M_PI * 0.4 * 0.4;
  EXPECT_NEAR(c->array[0][0], 8 * bead / (M_PI * (9 - 1)), 1e-12);
  EXPECT_NEAR(c->array[1][0], 16 * bead / (M_PI * (25 - 9)), 1e-12);
}

TEST_F(ComputesTest, BadInputNamesTheStyle)
{
  bead_lattice();
  EXPECT_THAT(error_of("compute phi all areafrac/chunk nosuchchunk"),
              ::testing::HasSubstr("areafrac/chunk"));
  EXPECT_THAT(error_of("compute phi all areafrac/chunk"), ::testing::HasSubstr("areafrac/chunk"));
  EXPECT_THAT(error_of("compute p all polar/rod extra"), ::testing::HasSubstr("Compute polar/rod"));
  EXPECT_THAT(error_of("compute p all polar/rod\nthermo_style custom step c_p\nrun 0 post no"),
              ::testing::HasSubstr("Compute polar/rod: no rod fix"));
}

TEST_F(ComputesTest, AtomStyleWithoutRadiusIsRefused)
{
  command(R"(units lj
atom_style atomic
region box block 0 4 0 4 0 1 units box
create_box 1 box
compute slabs all chunk/atom bin/1d x lower 2.0 units box)");
  EXPECT_THAT(error_of("compute phi all areafrac/chunk slabs"),
              ::testing::HasSubstr("Compute areafrac/chunk: atom style must define radius"));
}

}    // namespace
