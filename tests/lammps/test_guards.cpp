// What pair gran/impulse and the wall fixes refuse or warn about (rigid bodies they do not know,
// integrators other than velocity Verlet, particles that do not fit, a coarse time step or skin),
// and how a time step change keeps the half of an impulse still due.
#include "bead_box.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "neighbor.h"
#include "pair.h"

#include <cmath>
#include <string>

class Guards : public BeadBox {
 protected:
  void SetUp() override
  {
    BeadBox::SetUp();
    command(PAIR);
  }
  int warnings() { return lmp->error->get_numwarn(); }
  // Step until the plate has delivered an impulse: the step of the impact (half of it still due).
  void run_until_impact(const std::string &impulse = "f_plates[6]")
  {
    command("run 0 post no");
    for (int step = 0; value(impulse) == 0.0; ++step) {
      ASSERT_LT(step, 200) << "no impact";
      command("run 1 post no");
    }
  }
};

TEST_F(Guards, AtomsOfPlainRigidBodiesAreRefused)
{
  bead(0.003, 0.005, 0.001, 0, 0, 0);
  bead(0.004, 0.005, 0.001, 0, 0, 0);
  command("fix body all rigid single");
  EXPECT_THAT(error_of("run 1"), ::testing::HasSubstr("Pair gran/impulse: fix body (style rigid) makes rigid bodies"));
  command("unfix body\nfix ids all property/atom i_body\nset atom * i_body 1\n"
          "fix body all rigid/small custom i_body");
  EXPECT_THAT(error_of("run 1"), ::testing::HasSubstr("fix body (style rigid/small) makes rigid bodies"));
  command("unfix body\nfix nve all nve/sphere");
  EXPECT_EQ(error_of("run 1"), "");
}

TEST_F(Guards, RespaAndMinimizeAreRefused)
{
  bead(0.005, 0.005, 0.001, 0, 0, 0);
  command("fix nve all nve/sphere\nrun_style respa 2 2");
  EXPECT_THAT(error_of("run 1"), ::testing::HasSubstr("Pair gran/impulse: run_style respa is not supported"));
  command("run_style verlet");
  EXPECT_THAT(error_of("minimize 0 0 10 10"), ::testing::HasSubstr("Pair gran/impulse: minimize is not supported"));
  EXPECT_EQ(error_of("run 1"), "");
}

TEST_F(Guards, TimestepChangeKeepsTheHalfImpulseStillDue)
{
  // A bead dropped at 0.1 m/s on a still plate (e = 0.3, no gravity) leaves at exactly 0.03 m/s,
  // also when the time step changes right after the impact step: between runs (timestep), with
  // the next run's setup skipped (run pre no), after a restart, and within a run (fix dt/reset).
  // Applying the stored half with the wrong dt would leave at -0.1 + 0.065 (1 + dt_new/dt_old).
  const std::string deck = "fix nve all nve/sphere\nfix plates all wall/impulse zlo 0.0 e 0.3 mu 0.01\n";
  struct Case {
    std::string name, change, next_run;
  };
  const Case cases[] = {
      {"unchanged", "", "run 50 post no"},
      {"timestep", "timestep 2.5e-6", "run 50 post no"},
      {"timestep, run pre no", "timestep 4e-5", "run 50 pre no post no"},
      {"restart", "write_restart guards.restart\nclear\nplugin load " ACTIVEGRAIN_PLUGIN_FILE
                  "\nread_restart guards.restart\ncomm_modify vel yes\nneighbor 0.0002 bin\n" + deck +
                  "timestep 2.5e-6", "run 50 post no"},
  };
  for (const Case &c : cases) {
    command("delete_atoms group all");
    bead(0.005, 0.005, 0.00052, 0, 0, -0.1);
    command(deck + "timestep 1e-5");
    run_until_impact();
    EXPECT_NEAR(value("vz[1]"), -0.1 + 0.065, 1e-12) << c.name;    // half of m (1 + e) 0.1
    command(c.change);
    command(c.next_run);
    EXPECT_NEAR(value("vz[1]"), 0.03, 1e-12) << c.name;
    command("unfix nve\nunfix plates\ntimestep 1e-5");
  }

  // fix dt/reset: dt = 2e-6 m / |v|, or less while the contact force acts, changes at the end of
  // the impact step (2e-5 s before, 6.7e-5 s once the bead leaves at 0.03 m/s).
  command("delete_atoms group all");
  bead(0.005, 0.005, 0.000502, 0, 0, -0.1);
  command(deck + "fix dt all dt/reset 1 NULL NULL 2e-6 units box\ntimestep 2e-5");
  run_until_impact();
  const double dt_impact = value("dt");
  command("run 20 post no");
  EXPECT_GT(value("dt"), 2.0 * dt_impact);
  EXPECT_NEAR(value("vz[1]"), 0.03, 1e-12) << "fix dt/reset";
}

TEST_F(Guards, TimestepChangeKeepsTheHalfImpulseOnARod)
{
  // A rod dropped on a plate: fix rigid/rod sums the rescaled contact forces into its body, so
  // the rod leaves the impact as with an unchanged time step (no gravity: free flight after it).
  auto rod_after_impact = [&](const std::string &change, int steps) {
    command("clear\nplugin load " ACTIVEGRAIN_PLUGIN_FILE);
    command("units si\natom_style sphere\natom_modify map array\nboundary p p f\n"
            "fix molecule_ids all property/atom mol ghost yes\n"
            "region box block -6e-3 6e-3 -6e-3 6e-3 -1e-3 3e-3\ncreate_box 3 box\n"
            "comm_modify vel yes cutoff 6e-3\nneighbor 5e-4 bin\n"
            "rod_template rod length 4.5e-3 tail 1.1e-3 nose 0.7e-3 spheres 9 density 8500\n"
            "create_atoms 0 single 0 0 6e-4 mol rod 1 units box rotate 0 0 0 1\n"
            "velocity all set 0.02 0 -0.1 units box\n"
            "pair_style gran/impulse\npair_coeff * * 0.3 0.05\n"
            "fix rods all rigid/rod molecule mol rod\n"
            "fix plates all wall/impulse zlo 0.0 e 0.5 mu 0.2\ntimestep 1e-5\n"
            "thermo_style custom step");    // (a rigid rod alone: too few degrees of freedom for a temperature)
    run_until_impact();
    command(change);
    command(fmt::format("run {} post no", steps));
    return std::vector<double>{value("vcm(all,x)"), value("vcm(all,z)"), value("omega(all,y)")};
  };
  const auto unchanged = rod_after_impact("", 20);
  ASSERT_GT(unchanged[1], -0.09);    // the impact slowed the fall
  ASSERT_GT(std::fabs(unchanged[2]), 1.0);    // the tail hit first: the rod turns
  // Between runs, and within the run's setup by fix dt/reset (after fix rigid/rod has summed the
  // forces of the step into its body).
  for (const char *change : {"timestep 2.5e-6", "fix dt all dt/reset 1 NULL 2.5e-6 1 units box"}) {
    const auto changed = rod_after_impact(change, 80);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(changed[k], unchanged[k], 1e-9 * std::fabs(unchanged[k])) << change << ", " << k;
  }
}

TEST_F(Guards, SkinSmallerThanAStepsClosingDistanceWarnsOncePerRun)
{
  // Skin 0.2 mm: beads at 4 m/s close 0.08 mm per step (no warning), at 6 m/s 0.12 mm (more than
  // half the skin: one warning per run, not one per step).
  bead(0.003, 0.005, 0.001, 4.0, 0, 0);
  command("fix nve all nve/sphere");
  int before = warnings();
  command("run 20 post no");
  EXPECT_EQ(warnings(), before);
  command("set atom 1 vx 6.0");
  before = warnings();
  command("run 20 post no");
  EXPECT_EQ(warnings(), before + 1);
  command("run 20 post no");
  EXPECT_EQ(warnings(), before + 2);
  // The spin's surface speed counts too: 4 m/s plus 2 m/s of spin.
  command("set atom 1 vx 4.0\nset atom 1 omega 0 4000 0");
  before = warnings();
  command("run 5 post no");
  EXPECT_EQ(warnings(), before + 1);
}

TEST_F(Guards, PlateSpeedCountsInTheSkinWarning)
{
  // A bead at rest 1 mm above a base plate vibrating at 2000 Hz, from phase 0 (its top speed
  // A 2 pi f). Skin 0.2 mm: amplitude 1 mm gives 12.6 m/s, 0.126 mm per step, more than half
  // the skin: a warning although no particle moves; 0.5 mm gives at most 6.3 m/s, 0.063 mm per
  // step (no warning). 5 steps each: the plate does not reach the bead.
  bead(0.005, 0.005, 0.0015, 0, 0, 0);
  command("fix nve all nve/sphere\nfix plates all wall/impulse zlo 0.0 e 0.3 mu 0.01 vibrate 1e-3 2000 0 "
          "rough 0.1 2e-3 7");    // (rough: no note on flat plates)
  int before = warnings();
  command("run 5 post no");
  EXPECT_EQ(warnings(), before + 1);
  EXPECT_EQ(value("vz[1]"), 0.0);    // only the plate moved
  command("unfix plates\nfix plates all wall/impulse zlo 0.0 e 0.3 mu 0.01 vibrate 5e-4 2000 0 "
          "rough 0.1 2e-3 7");
  before = warnings();
  command("run 5 post no");
  EXPECT_EQ(warnings(), before);
}

TEST_F(Guards, ParticlesThatDoNotFitAreRefused)
{
  // Plates 0.1 mm apart for 1 mm beads.
  bead(0.005, 0.005, 0.001, 0, 0, 0);
  command("fix nve all nve/sphere\nfix plates all wall/impulse zlo 0.0005 gap 1e-4 e 0.3 mu 0.01");
  EXPECT_THAT(error_of("run 1"),
              ::testing::HasSubstr("Fix wall/impulse: gap 0.0001 is narrower than the largest particle of group all (diameter 0.001)"));
  command("unfix plates\nfix plates all wall/impulse zlo 0.0 gap 1.12e-3 e 0.3 mu 0.01");
  EXPECT_EQ(error_of("run 1"), "");
  // Only the fix's group counts.
  bead(0.002, 0.002, 0.001, 0, 0, 0, 1, 0.0015);
  command("group small id 1\nunfix plates\nfix plates small wall/impulse zlo 0.0 gap 1.12e-3 e 0.3 mu 0.01");
  EXPECT_EQ(error_of("run 1"), "");
  command("unfix plates\nfix plates all wall/impulse zlo 0.0 gap 1.12e-3 e 0.3 mu 0.01");
  EXPECT_THAT(error_of("run 1"), ::testing::HasSubstr("group all (diameter 0.0015)"));
  command("unfix plates");

  // A side wall region narrower than a bead: a 0.8 mm wide channel.
  command("region narrow block INF INF 0.0046 0.0054 INF INF\nfix side small wall/impulse/region narrow e 0.3 mu 0.01");
  EXPECT_THAT(error_of("run 1"),
              ::testing::HasSubstr("Fix wall/impulse/region: region narrow is narrower (y extent"));
  command("unfix side");

  // A bead wider than the box (2 mm high).
  command("set atom 2 diameter 0.0025");
  EXPECT_THAT(error_of("run 1"),
              ::testing::HasSubstr("Pair gran/impulse: particles of diameter 0.0025 are wider than the box (z length 0.002)"));
}

TEST_F(Guards, TimeStepMustResolveTheVibration)
{
  bead(0.005, 0.005, 0.0006, 0, 0, 0);
  command("fix nve all nve/sphere\nfix plates all wall/impulse zlo 0.0 gap 1.12e-3 vibrate 4e-5 200 0 e 0.3 mu 0.01");
  // dt 1e-2 s against the 5 ms period; 2.5e-4 s (20 steps per period) is the largest allowed.
  command("timestep 1e-2");
  EXPECT_THAT(error_of("run 1"), ::testing::HasSubstr("Fix wall/impulse: time step 0.01 too large for the vibration"));
  // (after a run, the timestep command itself checks)
  EXPECT_THAT(error_of("timestep 2.6e-4\nrun 1"), ::testing::HasSubstr("Fix wall/impulse: time step"));
  command("timestep 2.4e-4");
  EXPECT_EQ(error_of("run 1"), "");
  // Within a run, fix dt/reset may not go past it either (dt = 1 mm / |v| = 1e-2 s at 0.1 m/s).
  command("timestep 1e-5\nset atom 1 vx 0.1\nfix dt all dt/reset 1 NULL NULL 1e-3 units box");
  EXPECT_THAT(error_of("run 5"), ::testing::HasSubstr("Fix wall/impulse: time step"));
}

TEST_F(Guards, InsertedParticlesSetTheNeighborCutoff)
{
  // No atoms at the start: the cutoff comes from the beads fix pour will insert (radius 0.5 mm),
  // and they land on the plate and on each other instead of falling through.
  command("fix g all gravity 9.81 vector 0 0 -1\nfix nve all nve/sphere\n"
          "fix plates all wall/impulse zlo 0.0 e 0.3 mu 0.3\n"
          "region slab block 0.001 0.009 0.001 0.009 0.0011 0.0019\n"
          "fix ins all pour 6 1 4767 region slab diam one 0.001 dens 2700 2700 vel 0 0 0 0 -0.1\n"
          "run 0 post no");
  EXPECT_NEAR(lmp->force->pair->cutforce, 0.001, 1e-12);
  command("run 3000 post no");
  EXPECT_EQ(lmp->atom->natoms, 6);
  EXPECT_GT(value("bound(all,zmin)"), 0.0005 - 1e-5);    // none below the plate

  // An atom grown during a run (no setup in between) beyond the cutoff is refused.
  EXPECT_THAT(error_of("run 20 pre no post no every 10 \"set atom 1 diameter 0.0012\""),
              ::testing::HasSubstr("Pair gran/impulse: an atom is larger by"));
}
