// compute areafrac/chunk and compute polar/rod: exact area fractions of known packings, on any
// number of ranks (this file also runs under mpirun -np 2 and -np 4), and clear errors.
#include "lammps_fixture.h"

#include "ag_projected_area.h"
#include "ag_rod_geometry.h"
#include "compute.h"
#include "modify.h"

#include <cmath>
#include <numeric>

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

// The paper's rods (SI units) in a 20 mm x 10 mm periodic cell between plates.
class RodComputesTest : public ComputesTest {
 protected:
  static constexpr double LENGTH = 4.5e-3, TAIL = 1.1e-3, NOSE = 0.7e-3;
  static constexpr int SPHERES = 9;

  void rod_cell()
  {
    command(fmt::format(R"(units si
atom_style sphere
atom_modify map array
boundary p p f
comm_modify vel yes cutoff 6e-3
fix molecule_ids all property/atom mol ghost yes
region box block 0 0.02 0 0.01 -1e-4 1.22e-3 units box
create_box 3 box
rod_template rod length {} tail {} nose {} spheres {} density 8500 types 1 2 3
pair_style gran/impulse
pair_coeff * * 0.3 0.05
neigh_modify exclude molecule/intra all
thermo_style custom step)", LENGTH, TAIL, NOSE, SPHERES));
  }
  // A rod with its centre of mass near (x, y), axis at angle theta (degrees) in the plane.
  void rod_at(double x, double y, double theta, int seed)
  {
    command(fmt::format("create_atoms 0 single {} {} 5.6e-4 mol rod {} units box rotate {} 0 0 1", x, y,
                        seed, theta));
  }
  void integrate_rods() { command("fix rods all rigid/rod molecule mol rod\nrun 0 post no"); }

  // Projected area of one flat rod: the union of its spheres' discs.
  static double rod_area()
  {
    ActiveGrain::RodParameters p;
    p.length = LENGTH; p.tail_diameter = TAIL; p.nose_diameter = NOSE; p.nspheres = SPHERES;
    p.density = 8500;
    std::vector<double> x, r;
    for (const auto &s : ActiveGrain::make_rod_geometry(p).spheres) {
      x.push_back(s.x);
      r.push_back(s.radius);
    }
    auto shares = ActiveGrain::disc_chain_area_shares(x, r);
    return std::accumulate(shares.begin(), shares.end(), 0.0);
  }
  const double *vector_of(const char *id)
  {
    auto *c = lmp->modify->get_compute_by_id(id);
    c->compute_vector();
    return c->vector;
  }
};

TEST_F(RodComputesTest, AlignedRodsArePolar)
{
  rod_cell();
  const double theta = 30.0;
  // Three rods, one across the periodic boundary in x.
  rod_at(0.005, 0.003, theta, 11);
  rod_at(0.012, 0.007, theta, 12);
  rod_at(0.0195, 0.0045, theta, 13);
  integrate_rods();
  command("compute order all polar/rod");
  const double *v = vector_of("order");
  EXPECT_NEAR(v[0], 1.0, 1e-9);
  EXPECT_NEAR(v[1], cos(theta * M_PI / 180), 1e-9);
  EXPECT_NEAR(v[2], sin(theta * M_PI / 180), 1e-9);
  EXPECT_NEAR(v[3], 0.0, 1e-9);
  EXPECT_NEAR(v[4], 1.0, 1e-9);
  EXPECT_EQ(v[5], 3.0);
}

TEST_F(RodComputesTest, OpposedRodsAreNematicNotPolar)
{
  rod_cell();
  rod_at(0.005, 0.003, 10.0, 21);
  rod_at(0.012, 0.007, 190.0, 22);
  rod_at(0.005, 0.007, 100.0, 23);
  rod_at(0.015, 0.003, 280.0, 24);
  integrate_rods();
  command("compute order all polar/rod");
  const double *v = vector_of("order");
  EXPECT_NEAR(v[0], 0.0, 1e-9);
  EXPECT_NEAR(v[4], 0.0, 1e-9);    // two perpendicular nematic axes cancel as well
  EXPECT_EQ(v[5], 4.0);
}

TEST_F(RodComputesTest, LocalTableHasEveryRodOnce)
{
  rod_cell();
  for (int k = 0; k < 4; ++k) rod_at(0.0025 + 0.005 * k, 0.005, 45.0 * k, 31 + k);
  integrate_rods();
  command("compute order all polar/rod");
  auto *c = lmp->modify->get_compute_by_id("order");
  c->compute_local();
  double sum_px = 0, count = c->size_local_rows;
  for (int row = 0; row < c->size_local_rows; ++row) sum_px += c->array_local[row][4];
  double all_px = 0, all_count = 0;
  MPI_Allreduce(&sum_px, &all_px, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(&count, &all_count, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  EXPECT_EQ(all_count, 4.0);
  EXPECT_NEAR(all_px, 1 + cos(M_PI / 4) + 0 + cos(3 * M_PI / 4), 1e-9);
}

TEST_F(RodComputesTest, EachRodCountsItsTrueShapeOnceAcrossBins)
{
  rod_cell();
  rod_at(0.0049, 0.003, 0.0, 41);     // straddles the bin edge at x = 5 mm
  rod_at(0.0199, 0.007, 15.0, 42);    // straddles the periodic boundary
  integrate_rods();
  command(R"(compute slabs all chunk/atom bin/1d x lower 0.005 units box
compute phi all areafrac/chunk slabs)");
  auto *c = lmp->modify->get_compute_by_id("phi");
  c->compute_array();
  ASSERT_EQ(c->size_array_rows, 4);
  const double bin_area = 0.005 * 0.01;
  double area = 0, rods = 0, beads = 0;
  int bins_with_rods = 0;
  for (int bin = 0; bin < 4; ++bin) {
    area += c->array[bin][1] * bin_area;
    rods += c->array[bin][2];
    beads += c->array[bin][0];
    bins_with_rods += c->array[bin][1] > 0;
  }
  EXPECT_NEAR(area, 2 * rod_area(), 1e-12 * bin_area);
  EXPECT_NEAR(rods, 2.0, 1e-12);
  EXPECT_EQ(beads, 0.0);
  EXPECT_GE(bins_with_rods, 3);    // each straddling rod is shared between two bins
  EXPECT_LT(rod_area(), LENGTH * (TAIL + NOSE) / 2);    // rounded ends: less than the trapezoid
}

}    // namespace
