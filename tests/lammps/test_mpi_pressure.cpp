// Pressure and stress of pair gran/impulse and its wall fixes against statics, on 1, 2 and 4
// ranks (test_mpi_*). A contact force is its impulse over the time step, J / dt; averaged over
// many steps it is the static force. The virial W = sum over contacts of r (x) F (a pair: the
// centre-to-centre vector; a wall: from the contact point to the atom's centre) then follows from
// the loads alone.
#include "bead_box.h"
#include "rod_deck.h"

#include "domain.h"
#include "force.h"

#include <cmath>
#include <string>

namespace {
constexpr double G = 9.81;
constexpr double RADIUS = 0.5e-3;
constexpr double DT = 1e-5;
constexpr int SETTLE = 2000;    // a multiple of WINDOW: fix ave/time averages whole windows
constexpr int WINDOW = 2000;
void report(const std::string &what, double measured, double expected)
{
  int me = 0, nprocs = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  MPI_Comm_size(MPI_COMM_WORLD, &nprocs);
  if (me == 0)
    std::printf("[ measured ] %s, %d ranks: %.6g (statics %.6g, relative error %.2g)\n", what.c_str(), nprocs,
                measured, expected, measured / expected - 1.0);
}
}    // namespace

class StaticPressure : public BeadBox {
 protected:
  // The bead box cut into slabs along x: rows along x cross sub-domain boundaries.
  void SetUp() override
  {
    LammpsTest::SetUp();
    command(std::string("processors * 1 1\n") + BOX);
  }
  double bead_mass() { return 2700.0 * 4.0 / 3.0 * M_PI * RADIUS * RADIUS * RADIUS; }
  double volume() { return lmp->domain->xprd * lmp->domain->yprd * lmp->domain->zprd; }
  // Virial (energy units) from a pressure component of compute pressure (pressure units).
  double virial_of(const std::string &pressure) { return value(pressure) * volume() / lmp->force->nktv2p; }
  // Settle, then average over WINDOW steps the given quantities (fix ave/time "av").
  void settle_and_average(const std::string &quantities)
  {
    command("fix integrate all nve/sphere\nthermo 0\nrun " + std::to_string(SETTLE) + " post no\n"
            "fix av all ave/time 1 " + std::to_string(WINDOW) + " " + std::to_string(WINDOW) + " " +
            quantities + "\nrun " + std::to_string(WINDOW) + " post no");
  }
};

// A monolayer of 25 beads resting on a still base plate at z = 0 under gravity, no lid, no
// bead touching another. Statics: the plate pushes each bead up with its weight m g, at the
// contact point a radius R below its centre, so the plate's force per area is the weight per
// area and the plate's virial is W_zz = N m g R; the pair virial vanishes. (The same from the
// whole system: -sum_i r_i . F_i over gravity at the centres and the plate at z_plate gives
// N m g (z_centre - z_plate) = N m g R, independent of the origin.) A virial from the atoms'
// absolute heights, or none at all, fails.
TEST_F(StaticPressure, MonolayerRestingOnAPlate)
{
  command(PAIR);
  for (int ix = 0; ix < 5; ++ix)
    for (int iy = 0; iy < 5; ++iy) bead(0.001 + 0.002 * ix, 0.001 + 0.002 * iy, RADIUS, 0, 0, 0);
  const double n = 25.0, weight = n * bead_mass() * G;
  command("fix plates all wall/impulse zlo 0.0 e 0.3 mu 0.01\nfix_modify plates virial yes\n"
          "fix gravity all gravity 9.81 vector 0 0 -1\n"
          "compute all_virial all pressure NULL virial\ncompute pair_virial all pressure NULL pair\n"
          "compute wall_virial all pressure NULL fix");
  settle_and_average("f_plates[6] c_all_virial[3] c_pair_virial[3] c_wall_virial[3] c_all_virial[1]");
  const double area = lmp->domain->xprd * lmp->domain->yprd;
  EXPECT_NEAR(value("f_av[1]") / DT / area, weight / area, 1e-3 * weight / area);
  const double expected = weight * RADIUS;
  report("plate force", value("f_av[1]") / DT, weight);
  report("virial zz, pair + plate", virial_of("f_av[2]"), expected);
  EXPECT_NEAR(virial_of("f_av[2]"), expected, 1e-2 * expected);
  EXPECT_NEAR(virial_of("f_av[4]"), expected, 1e-2 * expected);
  EXPECT_NEAR(virial_of("f_av[3]"), 0.0, 1e-6 * expected);
  EXPECT_NEAR(virial_of("f_av[5]"), 0.0, 1e-6 * expected);    // nothing pushes sideways
}

// A row of N = 6 touching beads along x, pressed by a sideways gravity g (-x) against the plane
// x = 1 mm of fix wall/impulse/region; no plates (the beads float at mid-height). Statics: the
// contact between beads k and k+1 (counted from the wall) carries the weight of the N - k - 1
// beads beyond it, over a centre distance 2R; the wall carries all N, a radius from the first
// centre. So W_xx(pair) = sum_k 2R (N - k - 1) m g = R m g N (N - 1) and W_xx(wall) = R m g N.
// The row crosses sub-domain boundaries on 2 and 4 ranks (processors * 1 1). The per-atom
// virial of compute stress/atom (its negative) sums to the pair's global one in a step.
TEST_F(StaticPressure, RowPressedAgainstASideWall)
{
  command(PAIR);
  const int n = 6;
  for (int k = 0; k < n; ++k) bead(0.001 + RADIUS + 2 * RADIUS * k, 0.005, 0.001, 0, 0, 0);
  const double mg = bead_mass() * G;
  command("region side plane 0.001 0 0 1 0 0\nfix side all wall/impulse/region side e 0.3 mu 0.05\n"
          "fix_modify side virial yes\nfix gravity all gravity 9.81 vector -1 0 0\n"
          "compute pair_virial all pressure NULL pair\ncompute wall_virial all pressure NULL fix\n"
          "compute stress all stress/atom NULL pair\ncompute stress_sum all reduce sum c_stress[1] c_stress[4]");
  settle_and_average("c_pair_virial[1] c_wall_virial[1] c_pair_virial[2] c_pair_virial[4]");
  const double pair_expected = RADIUS * mg * n * (n - 1), wall_expected = RADIUS * mg * n;
  report("virial xx, pair", virial_of("f_av[1]"), pair_expected);
  report("virial xx, side wall", virial_of("f_av[2]"), wall_expected);
  EXPECT_NEAR(virial_of("f_av[1]"), pair_expected, 1e-2 * pair_expected);
  EXPECT_NEAR(virial_of("f_av[2]"), wall_expected, 1e-2 * wall_expected);
  EXPECT_NEAR(virial_of("f_av[3]"), 0.0, 1e-6 * pair_expected);
  EXPECT_NEAR(virial_of("f_av[4]"), 0.0, 1e-6 * pair_expected);

  // One step's per-atom virials against the global one of the same step.
  command("thermo_style custom step c_pair_virial[1] c_pair_virial[4] c_stress_sum[1] c_stress_sum[2]\n"
          "thermo 1\nrun 1 post no");
  const double pair_xx = virial_of("c_pair_virial[1]");
  ASSERT_GT(pair_xx, 0.1 * pair_expected);    // the row is loaded in this step
  EXPECT_NEAR(-value("c_stress_sum[1]"), pair_xx, 1e-9 * pair_xx);
  EXPECT_NEAR(-value("c_stress_sum[2]"), virial_of("c_pair_virial[4]"), 1e-9 * pair_xx);
}

class RodPackingStress : public LammpsTest {};

// A dense packing of rods (fix rigid/rod) and beads between still plates, without gravity,
// started with random velocities (as test_mpi8_energy.cpp): in a step with contacts after 100
// steps, the negative sum of compute stress/atom (pair) equals the pair style's global virial in
// all six components. On several ranks a rod's contacts are solved on its solver rank, from ghost
// atoms too: each contact's virial must be tallied once and reach the atoms that own it.
TEST_F(RodPackingStress, PerAtomVirialSumsToTheGlobalOne)
{
  command("atom_modify map array\n"
          "variable geometry index box\nvariable Lx index 24e-3\nvariable Ly index 24e-3\n"
          "variable phi_b index 0.55\nvariable phi_r index 0.10\nvariable amplitude index 0\n"
          "variable seed index 11\nvariable out index test_mpi_pressure_out\n"
          "variable create_dir index " ACTIVEGRAIN_SOURCE_DIR "/examples/rods-and-beads\n"
          "include ${create_dir}/in.create\n"
          "unfix gravity\nvelocity all create 3e14 4928 dist gaussian\ntimestep 1e-5\nthermo 0\nrun 100 post no\n"
          "compute solver all pair gran/impulse\ncompute pair_virial all pressure NULL pair\n"
          "compute stress all stress/atom NULL pair\ncompute stress_sum all reduce sum c_stress[*]\n"
          "thermo_style custom step c_solver[1] c_pair_virial[*] c_stress_sum[*]\nthermo 1");
  // Contacts are few per step (a contact is solved in the step it closes): the first step with some.
  for (int step = 0; step == 0 || value("c_solver[1]") == 0.0; ++step) {
    ASSERT_LT(step, 50) << "no contacts";
    command("run 1 post no");
  }
  const double volume = lmp->domain->xprd * lmp->domain->yprd * lmp->domain->zprd / lmp->force->nktv2p;
  double scale = 0.0;
  for (int k = 1; k <= 6; ++k) scale = std::max(scale, std::fabs(value("c_pair_virial[" + std::to_string(k) + "]")));
  ASSERT_GT(scale, 0.0);
  for (int k = 1; k <= 6; ++k) {
    const std::string component = std::to_string(k);
    EXPECT_NEAR(-value("c_stress_sum[" + component + "]"), value("c_pair_virial[" + component + "]") * volume,
                1e-9 * scale * volume)
        << "component " << k;
  }
}

class RodPressure : public LammpsTest {};

// One paper rod (fix rigid/rod) lying flat on a still plate at z = 0 under gravity, across the
// sub-domain corner of 2 and 4 ranks (its plate contacts are solved on one rank, from ghost
// atoms of the others). The virial that compute pressure sums is the plate's (fix_modify virial
// yes: each contact's force times the arm from the contact point to its sphere's centre) and fix
// rigid/rod's, whose constraint forces hold the spheres in the body (as fix rigid/small tallies
// them, f_c = m a - f on each sphere). At rest f_c = -(plate + gravity) on each sphere, so the
// sum is W_zz = g sum_i m_i z_i, the spheres' weights at their heights above the plate. (For
// this rod the plate's part alone already gives it: the spheres' heights are linear along the
// rod, as the plate's load is, and the rigid part averages to zero by the torque balance.) A
// contact tallied on two ranks, or a rigid part that does not vanish at rest, fails.
TEST_F(RodPressure, RodRestingOnAPlate)
{
  using namespace rod_deck;
  command("units si\natom_style sphere\natom_modify map array\nboundary p p f\n"
          "fix molecule_ids all property/atom mol ghost yes\n"
          "region box block -6e-3 6e-3 -6e-3 6e-3 -1e-3 3e-3\ncreate_box 4 box\n"
          "comm_modify vel yes cutoff 6e-3\nneighbor 5e-4 bin\n" +
          rod_template("test_mpi_pressure_rod.mol") + flat_rod(0.0) +
          "pair_style gran/impulse\npair_coeff * * 0.3 0.05\nfix rods all rigid/rod molecule mol rod\n"
          "fix plates all wall/impulse zlo 0.0 e 0.3 mu 0.2\nfix_modify plates virial yes\n"
          "fix gravity all gravity 9.81 vector 0 0 -1\ntimestep 1e-5\n"
          "compute all_virial all pressure NULL virial\n"
          "thermo 0\nrun 2000 post no\n"
          "fix av all ave/time 1 2000 2000 c_all_virial[3] f_plates[6]\n"
          "run 2000 post no");
  const double volume = lmp->domain->xprd * lmp->domain->yprd * lmp->domain->zprd / lmp->force->nktv2p;
  const double weight = G * value("mass(all)");
  const double expected = weight * value("xcm(all,z)");
  const double total = value("f_av[1]") * volume, force = value("f_av[2]") / DT;
  // The plate's part alone: the same window again without fix rigid/rod's virial.
  command("fix_modify rods virial no\nrun 2000 post no");
  const double plate = value("f_av[1]") * volume;
  report("rod on a plate: plate force", force, weight);
  report("rod on a plate: virial zz, plate + rigid/rod", total, expected);
  report("rod on a plate: virial zz, plate alone", plate, expected);
  EXPECT_NEAR(force, weight, 1e-3 * weight);
  EXPECT_NEAR(total, expected, 1e-2 * expected);
  EXPECT_NEAR(plate, expected, 1e-2 * expected);
}
