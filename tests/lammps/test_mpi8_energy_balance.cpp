// Energy input and dissipation (compute pair gran/impulse, the wall fixes' ENERGY block) on 1, 2,
// 4 and 8 ranks (test_mpi8_*): a bead dropped on a still plate loses (1 - e^2) of its impact energy,
// and in a vibrated bead bed the plates' work plus the overlap correction's equals the energy
// dissipated plus the change of kinetic and potential energy over a window.
#include "beads_deck.h"
#include "bead_box.h"

#include "pair_gran_impulse.h"

#include <cmath>
#include <string>

using LAMMPS_NS::PairGranImpulse;

namespace {
constexpr double G = 9.81;

// compute pair gran/impulse's value (1-based) of an Output.
std::string pair_output(int index) { return "c_solver[" + std::to_string(index + 1) + "]"; }

// The four energies of the solve, each summed over a window of steps (fix ave/time "sums", whose
// averages are scaled back by the window length).
const std::string ENERGIES = pair_output(PairGranImpulse::DISSIPATED_PAIR) + " " +
    pair_output(PairGranImpulse::DISSIPATED_WALL) + " " + pair_output(PairGranImpulse::OVERLAP_WORK) + " " +
    pair_output(PairGranImpulse::WALL_WORK);
enum Summed { PAIR_LOST = 1, WALL_LOST, OVERLAP, WALL_WORK };

void report(const char *format, double a, double b)
{
  int me = 0, nprocs = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  MPI_Comm_size(MPI_COMM_WORLD, &nprocs);
  if (me == 0) {
    std::printf("[ measured ] %d ranks: ", nprocs);
    std::printf(format, a, b);
    std::printf("\n");
  }
}
}    // namespace

class DroppedBead : public BeadBox {};

// A 1 mm bead dropped from 1 mm above a still plate (e 0.5): the impact at v = sqrt(2 g h) loses
// (1 - e^2) (1/2) m v^2, all at the wall; the still plate does no work and nothing overlaps.
TEST_F(DroppedBead, LosesOneMinusESquaredOfItsImpactEnergy)
{
  constexpr double RADIUS = 0.5e-3, HEIGHT = 1e-3, E = 0.5;
  constexpr int STEPS = 1600;    // the impact comes at step 1428, the next one after step 2800
  command(PAIR);
  bead(0.005, 0.005, RADIUS + HEIGHT, 0, 0, 0);
  command("fix plates all wall/impulse zlo 0.0 e 0.5 mu 0.01\nfix gravity all gravity 9.81 vector 0 0 -1\n"
          "fix integrate all nve/sphere\ncompute solver all pair gran/impulse\n"
          "fix sums all ave/time 1 " + std::to_string(STEPS) + " " + std::to_string(STEPS) + " " + ENERGIES +
          " f_plates[16] f_plates[17] f_plates[18]\nthermo 0\nrun " + std::to_string(STEPS) + " post no");
  const double sum = STEPS;    // ave/time's averages times the window
  const double mass = 2700.0 * 4.0 / 3.0 * M_PI * RADIUS * RADIUS * RADIUS;
  const double impact = 0.5 * mass * 2.0 * G * HEIGHT, expected = (1.0 - E * E) * impact;
  const double lost = sum * value("f_sums[" + std::to_string(WALL_LOST) + "]");
  report("dropped bead: dissipated %.6g J, (1 - e^2) x impact energy %.6g J", lost, expected);
  EXPECT_NEAR(lost, expected, 1e-3 * expected);
  EXPECT_EQ(value("f_sums[" + std::to_string(PAIR_LOST) + "]"), 0.0);
  EXPECT_EQ(value("f_sums[" + std::to_string(OVERLAP) + "]"), 0.0);
  EXPECT_EQ(value("f_sums[" + std::to_string(WALL_WORK) + "]"), 0.0);
  // The plate's own block: work, dissipated, overlap correction at the base.
  EXPECT_EQ(value("f_sums[5]"), 0.0);
  EXPECT_DOUBLE_EQ(sum * value("f_sums[6]"), lost);
  EXPECT_EQ(value("f_sums[7]"), 0.0);
}

class VibratedBedEnergy : public BeadMonolayer {};

// The example deck (360 beads between vibrating plates, calibrated rough plates), after a start
// of 10 periods, over a window of 10 periods: the plates' work W and the overlap correction's E
// equal what the contacts dissipate (D, pairs and plates) plus what the bed's kinetic (translation
// and spin) and potential energy K + U gained: W + E - D = delta(K + U). Left out of the balance:
// gravity's work within the contacts' gain, J . g (dt/2 + t_c), velocity Verlet's gravity step
// and K read mid-impulse at the window's ends; measured together 2e-8 of W on 1 rank. Dropping
// the overlap term (0.6 % of W) or the pair dissipation, or counting the plates' work at their
// velocity at the step's start instead of when a contact closes (0.5 % of W), fails.
TEST_F(VibratedBedEnergy, PlatesWorkBalancesDissipation)
{
  constexpr int START = 5000, WINDOW = 5000;    // a multiple of WINDOW: whole windows
  load_deck("variable rough index 0.06");    // the calibrated rough plates: beads collide sideways too
  command("compute solver all pair gran/impulse\n"
          "variable energy equal c_ke+c_rke+9.81*mass(all)*xcm(all,z)\n"
          "thermo_style custom step v_energy\nthermo " + std::to_string(START) +
          "\nrun " + std::to_string(START) + " post no");
  const double before = value("v_energy");
  command("fix sums all ave/time 1 " + std::to_string(WINDOW) + " " + std::to_string(WINDOW) + " " + ENERGIES +
          "\nrun " + std::to_string(WINDOW) + " post no");
  const double gained = value("v_energy") - before;
  auto summed = [&](int k) { return WINDOW * value("f_sums[" + std::to_string(k) + "]"); };
  const double work = summed(WALL_WORK), overlap = summed(OVERLAP);
  const double lost = summed(PAIR_LOST) + summed(WALL_LOST);
  report("vibrated bed: plates' work %.6g J, dissipated %.6g J", work, lost);
  report("vibrated bed: dissipated at pairs %.6g J, at the plates %.6g J", summed(PAIR_LOST), summed(WALL_LOST));
  report("vibrated bed: overlap correction %.6g J, kinetic + potential energy gained %.6g J", overlap, gained);
  report("vibrated bed: balance W + E - D - gained %.3g J (%.3g of W)", work + overlap - lost - gained,
         (work + overlap - lost - gained) / work);
  ASSERT_GT(work, 0.0);
  EXPECT_GT(summed(PAIR_LOST), 0.0);
  EXPECT_GT(summed(WALL_LOST), 0.0);
  EXPECT_NEAR(work + overlap - lost, gained, 1e-4 * work);
}
