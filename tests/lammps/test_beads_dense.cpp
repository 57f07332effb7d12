// A dense bead monolayer (area fraction 0.75) between plates vibrating at the paper's drive:
// 1e5 steps with bounded overlaps and no bead leaving the cell.
#include "beads_deck.h"

#include <iostream>

TEST_F(BeadMonolayer, DenseRunKeepsOverlapsBoundedAndBeadsInTheCell)
{
  load_deck();
  const double d = 1.0e-3;
  const double natoms = value("count(all)");
  command("variable base equal f_plates[1]\n"
          "variable lid equal f_plates[2]\n"
          "variable below atom v_base-(z-radius)\n"     // overlap with the base
          "variable above atom z+radius-v_lid\n"        // overlap with the lid
          "compute below all reduce max v_below\n"
          "compute above all reduce max v_above\n"
          "thermo_style custom step c_below c_above\n"
          "thermo 1000");
  double worst_contact = 0, worst_below = -1, worst_above = -1;
  // Chunks of 2.5 vibration periods, so that the checks see the plates at different phases.
  for (int chunk = 0; chunk < 80; ++chunk) {
    command("run 1250 post no");
    worst_contact = std::max(worst_contact, largest_overlap());
    worst_below = std::max(worst_below, value("c_below"));
    worst_above = std::max(worst_above, value("c_above"));
    ASSERT_EQ(value("count(all)"), natoms) << "beads lost";
  }
  // The stated bound: overlaps stay below 1e-4 d (0.1 um for 1 mm beads) at dt = 1e-5 s, where
  // contacts are found (after the atoms moved). At a step's end, a bead whose contact closed
  // within the step has moved back by its late impulse (up to (1 + e) u dt, about 0.3 um here)
  // and may overlap a plate by up to e u dt until the next step's flight.
  EXPECT_LT(worst_contact, 1e-4 * d);
  EXPECT_LT(worst_below, 2e-4 * d);
  EXPECT_LT(worst_above, 2e-4 * d);
  std::cout << "largest overlap / d: contacts " << worst_contact / d << ", base " << worst_below / d
            << ", lid " << worst_above / d << "\n";
}

TEST_F(BeadMonolayer, SolverHealthIsReportedThroughComputePair)
{
  // compute pair gran/impulse reads the solver's global outputs (docs: the layout): every
  // compliant impact of the dense bed ends and every overlap opens.
  load_deck();
  command("pair_style gran/impulse\npair_coeff * * 0.3 0.05\n"
          "compute health all pair gran/impulse\n"
          "thermo_style custom step c_health[*]\nthermo 100\nrun 1000 post no");
  using LAMMPS_NS::PairGranImpulse;
  EXPECT_GT(value("c_health[1]"), 0.0);     // contacts in the last step
  EXPECT_GE(value("c_health[2]"), 0.0);     // sub-steps of the largest impact of the last step
  EXPECT_LE(value("c_health[3]"), 1e-2);    // overlap shortfall: within the pushes' tolerance
  EXPECT_GT(value("c_health[4]"), 0.0);     // largest overlap
  EXPECT_EQ(value("c_health[5]"), 0.0);     // no step hit the cap
  EXPECT_EQ(value("c_health[2]"), solver_output(PairGranImpulse::SUBSTEPS));
  EXPECT_EQ(value("c_health[4]"), solver_output(PairGranImpulse::LARGEST_OVERLAP));
}

TEST_F(BeadMonolayer, ImpactPhaseTallyShowsLockIn)
{
  // Identical beads on flat plates fall into step with the drive (issue: the absorbing state):
  // after 0.1 s every bead hits the base once per period, always at the same drive phase, so
  // R = |<exp(i phase)>| over the impacts is 1 to 1e-4. The tally is the wall fix's IMPACTS
  // block (base: count, sum cos, sum sin), summed here over 0.05 s with fix ave/time.
  load_deck();
  const int base = 3 + 3 * 2 + 1;    // state (3), impulse of base and lid (3 each); from 1
  command("run 10000 post no\n"
          "fix lockin all ave/time 1 5000 5000 f_plates[" + std::to_string(base) + "] f_plates[" +
          std::to_string(base + 1) + "] f_plates[" + std::to_string(base + 2) + "]\n"
          "variable impacts equal f_lockin[1]*5000\n"
          "variable R equal sqrt(f_lockin[2]^2+f_lockin[3]^2)/f_lockin[1]\n"
          "run 5000 post no");
  EXPECT_EQ(value("v_impacts"), 360.0 * 10);    // 360 beads, 10 periods
  EXPECT_GT(value("v_R"), 1.0 - 1e-4);
  // Without a drive there is no phase: nothing is tallied.
  command("unfix plates\nfix plates all wall/impulse zlo 0.0 gap 1.12e-3 e 0.3 mu 0.01\nrun 5000 post no");
  EXPECT_EQ(value("f_lockin[1]"), 0.0);
}
