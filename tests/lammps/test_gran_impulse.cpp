// pair gran/impulse with fix wall/impulse and fix wall/impulse/region in LAMMPS: measured
// restitution of bead-bead, bead-plate and bead-side-wall impacts, energy input by a vibrating
// plate, and the errors for bad input.
#include "bead_box.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "pair.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

class GranImpulse : public BeadBox {
 protected:
  double v(int id, char c) { return value(fmt("v{}[{}]", c, id)); }
  template <class... Args> static std::string fmt(const std::string &f, Args... args)
  {
    return fmt::format(f, args...);
  }
};

TEST_F(GranImpulse, TwoBeadsReboundWithTheCoefficientOfRestitution)
{
  for (double dy : {0.0, 0.0002}) {    // head-on, and off-centre so that friction acts too
    for (double e : {0.0, 0.3, 0.9}) {
      command("delete_atoms group all");
      bead(0.003, 0.005, 0.001, 0.1, 0.0, 0.0);
      bead(0.006, 0.005 + dy, 0.001, -0.05, 0.0, 0.0);
      command(PAIR);
      command(fmt("pair_coeff * * {} 0.05", e));
      command("fix nve all nve/sphere");
      const int n1 = (int) lmp->atom->natoms - 1, n2 = n1 + 1;
      command("run 3000");
      // Normal at impact: the line of centres when they touch.
      const double nx = std::sqrt(0.001 * 0.001 - dy * dy) / 0.001, ny = dy / 0.001;
      const double un_before = (-0.05 - 0.1) * nx;
      const double un_after = (v(n2, 'x') - v(n1, 'x')) * nx + (v(n2, 'y') - v(n1, 'y')) * ny;
      // Off-centre, the predictive contact acts up to one step's approach (1.5 um) before
      // touching, so its normal differs from the touching one by ~1e-4.
      const double tolerance = dy == 0.0 ? 1e-12 : 1e-3 * std::fabs(un_before);
      EXPECT_NEAR(un_after, -e * un_before, tolerance) << "e=" << e << " dy=" << dy;
      EXPECT_NEAR(v(n1, 'x') + v(n2, 'x'), 0.05, 1e-12);    // momentum (equal masses)
      EXPECT_NEAR(v(n1, 'y') + v(n2, 'y'), 0.0, 1e-12);
      command("unfix nve");
    }
  }
}

TEST_F(GranImpulse, BeadDroppedOnAStillPlateBouncesWithE)
{
  bead(0.005, 0.005, 0.0008, 0.0, 0.0, -0.1);
  command(PAIR);
  command("fix nve all nve/sphere\n"
          "fix plates all wall/impulse zlo 0.0 e 0.3 mu 0.01\n"
          "fix impulse all ave/time 1 1000 1000 f_plates[6]");
  command("run 1000");
  EXPECT_NEAR(v(1, 'z'), 0.03, 1e-12);
  // The plate reports the impulse it delivered, m (1 + e) v in all.
  const double m = 2700 * M_PI / 6 * 1e-9;
  EXPECT_NEAR(1000 * value("f_impulse"), m * 1.3 * 0.1, 1e-12 * m);
}

TEST_F(GranImpulse, BeadBetweenStillPlatesUnderGravityKeepsBouncingWithE)
{
  // Under gravity the rebound speed is e times the impact speed within 2 per cent at dt 1e-5 s.
  bead(0.005, 0.005, 0.0015, 0.0, 0.0, 0.0);
  command(PAIR);
  command("fix nve all nve/sphere\n"
          "fix g all gravity 9.81 vector 0 0 -1\n"
          "fix plates all wall/impulse zlo 0.0 e 0.5 mu 0.01 gap 0.002 lid fixed\n"
          );
  // Fall 1 mm: impact speed sqrt(2 g h).
  double vmin = 0, vafter = 0;
  for (int step = 0; step < 2000; ++step) {
    command("run 1 post no");
    const double vz = v(1, 'z');
    if (vz < vmin) vmin = vz;
    if (vz > 0) { vafter = vz; break; }
  }
  ASSERT_LT(vmin, -0.1);
  EXPECT_NEAR(vafter / -vmin, 0.5, 0.01);
}

TEST_F(GranImpulse, BeadOnVibratingPlateGainsEnergy)
{
  // (2 pi f)^2 A = 6.4 g: a bead resting on the plate is thrown up.
  bead(0.005, 0.005, 0.0005, 0.0, 0.0, 0.0);
  command(PAIR);
  command("fix nve all nve/sphere\n"
          "fix g all gravity 9.81 vector 0 0 -1\n"
          "fix plates all wall/impulse zlo 0.0 e 0.3 mu 0.01 vibrate 0.00004 200 0\n"
          "compute ke all ke\n"
          "run 0");
  EXPECT_EQ(value("c_ke"), 0.0);
  double zmax = 0, kemax = 0;
  for (int k = 0; k < 40; ++k) {
    command("run 50 post no");
    zmax = std::max(zmax, value("z[1]"));
    kemax = std::max(kemax, value("c_ke"));
  }
  // Thrown clear above the plate's highest point (z = r + A).
  EXPECT_GT(zmax, 0.0005 + 0.00004 + 0.00001);
  EXPECT_GT(kemax, 0.0);
}

TEST_F(GranImpulse, BeadHitsSideWallRegionsWithE)
{
  struct Case {
    std::string region;    // the side wall
    double x, y, vx, vy;   // bead start and velocity; it hits the wall head-on
    int steps = 6000;      // long enough to hit once, short enough not to hit again
  };
  const Case cases[] = {
      {"region wall block 0.001 0.009 0.001 0.009 INF INF side in", 0.005, 0.005, 0.1, 0.0},
      {"region wall cylinder z 0.005 0.005 0.004 INF INF side in", 0.005, 0.005, 0.0, -0.1},
      {"region wall cylinder z 0.005 0.005 0.0015 INF INF side out", 0.008, 0.005, -0.1, 0.0},
      {"region outer cylinder z 0.005 0.005 0.004 INF INF side in\n"
       "region inner cylinder z 0.005 0.005 0.0015 INF INF side out\n"
       "region wall intersect 2 outer inner", 0.005, 0.0080, 0.0, 0.1, 3000},
      {"region lobe1 cylinder z 0.004 0.005 0.0025 INF INF side in\n"
       "region lobe2 cylinder z 0.006 0.005 0.0025 INF INF side in\n"
       "region wall union 2 lobe1 lobe2", 0.006, 0.005, 0.1, 0.0},
  };
  for (const Case &c : cases) {
    command("clear");
    command("plugin load " ACTIVEGRAIN_PLUGIN_FILE);
    command(BOX);
    command(c.region);
    bead(c.x, c.y, 0.001, c.vx, c.vy, 0.0);
    command(PAIR);
    command("fix nve all nve/sphere\n"
            "fix side all wall/impulse/region wall e 0.4 mu 0.1");
    command(fmt("run {}", c.steps));
    // Head-on: the rebound is e times the incoming speed, reversed.
    EXPECT_NEAR(v(1, 'x'), -0.4 * c.vx, 1e-9) << c.region;
    EXPECT_NEAR(v(1, 'y'), -0.4 * c.vy, 1e-9) << c.region;
  }
}

TEST_F(GranImpulse, PerTypeWallCoefficients)
{
  bead(0.003, 0.005, 0.0008, 0.0, 0.0, -0.1, 1);
  bead(0.007, 0.005, 0.0008, 0.0, 0.0, -0.1, 2);
  command(PAIR);
  command("fix nve all nve/sphere\n"
          "fix plates all wall/impulse zlo 0.0 e 0.3 mu 0.01 type 2 0.6 0.03\n"
          "run 1000");
  EXPECT_NEAR(v(1, 'z'), 0.03, 1e-12);
  EXPECT_NEAR(v(2, 'z'), 0.06, 1e-12);
}

TEST_F(GranImpulse, BadInputGivesClearErrors)
{
  bead(0.005, 0.005, 0.001, 0, 0, 0);
  command("pair_style gran/impulse");
  EXPECT_NE(error_of("pair_coeff * * 1.2 0.1").find("Pair gran/impulse: restitution"), std::string::npos);
  EXPECT_NE(error_of("pair_coeff * * 0.3 -0.1").find("Pair gran/impulse: friction"), std::string::npos);
  EXPECT_NE(error_of("pair_coeff * * 0.3 0.1 tangential compliant 0").find("Pair gran/impulse: tangential compliant "
                                                                           "stiffness ratio = 0 must be > 0"),
            std::string::npos);
  EXPECT_NE(error_of("pair_coeff * * 0.3 0.1 tangential compliant").find("needs its stiffness ratio"), std::string::npos);
  EXPECT_NE(error_of("pair_coeff * * 0.3 0.1 tangential soft 1").find("tangential must be stick or compliant R, not 'soft'"),
            std::string::npos);
  EXPECT_NE(error_of("pair_coeff * * 0.3 0.1 spin 2").find("unknown pair_coeff keyword spin"), std::string::npos);
  EXPECT_NE(error_of("pair_style gran/impulse resolution 5").find("Pair gran/impulse: resolution must be"),
            std::string::npos);
  EXPECT_NE(error_of("pair_style gran/impulse sweeps 8").find("keyword sweeps is gone"), std::string::npos);
  EXPECT_NE(error_of("pair_style gran/impulse order random").find("order must be"), std::string::npos);
  EXPECT_NE(error_of("pair_style gran/impulse tolerance 1e-2").find("keywords tolerance and max_sweeps set"),
            std::string::npos);
  EXPECT_NE(error_of("pair_style gran/impulse resting yes tolerance 0").find("tolerance must be in (0, 1)"),
            std::string::npos);
  EXPECT_NE(error_of("pair_style gran/impulse window -1e-6").find("Pair gran/impulse: window must be"),
            std::string::npos);
  EXPECT_NE(error_of("pair_style gran/impulse slop -1e-6").find("Pair gran/impulse: slop must be >= 0"),
            std::string::npos);
  EXPECT_NE(error_of("pair_style gran/impulse resting yes max_sweeps 0").find("max_sweeps must be >= 1"),
            std::string::npos);
  EXPECT_NE(error_of("pair_style gran/impulse window").find("missing value after keyword window"),
            std::string::npos);
  // A negative speed (which restart files use for resting yes) is no resting speed.
  EXPECT_NE(error_of("pair_style gran/impulse resting -1").find("resting must be yes, newton, no or a speed >= 0"),
            std::string::npos);
  command(PAIR);
  EXPECT_NE(error_of("fix w all wall/impulse zlo 0 e 1.5 mu 0.1").find("Fix wall/impulse: restitution"),
            std::string::npos);
  EXPECT_NE(error_of("fix w all wall/impulse zlo 0 e 0.5 mu -1").find("Fix wall/impulse: friction"),
            std::string::npos);
  EXPECT_NE(error_of("fix w all wall/impulse zlo 0 e 0.5 mu 0.1 tangential compliant -1").find("Fix wall/impulse: tangential compliant stiffness ratio"),
            std::string::npos);
  EXPECT_NE(error_of("fix w all wall/impulse zlo 0 e 0.5").find("Fix wall/impulse: no restitution"),
            std::string::npos);
  EXPECT_NE(error_of("fix w all wall/impulse/region nowhere e 0.5 mu 0.1").find("region nowhere does not exist"),
            std::string::npos);
  // A time step too large for the vibration: 200 Hz needs dt <= 2.5e-4 s.
  command("fix nve all nve/sphere\nfix w all wall/impulse zlo 0 e 0.5 mu 0.1 vibrate 0.00004 200 0\ntimestep 1e-3");
  EXPECT_NE(error_of("run 1").find("Fix wall/impulse: time step"), std::string::npos);
  command("timestep 1e-5\nrun 1");
  // Ghost velocities are required.
  command("comm_modify vel no");
  EXPECT_NE(error_of("run 1").find("comm_modify vel yes"), std::string::npos);
  command("comm_modify vel yes\nunfix w");
  // Wall fixes need the pair style.
  command("pair_style zero 0.001\npair_coeff * *\nfix w all wall/impulse zlo 0 e 0.5 mu 0.1");
  EXPECT_NE(error_of("run 1").find("Fix wall/impulse requires pair_style gran/impulse"), std::string::npos);
}

TEST_F(GranImpulse, WallOnPeriodicDimensionIsAnError)
{
  command("clear\nplugin load " ACTIVEGRAIN_PLUGIN_FILE);
  command("units si\natom_style sphere\nboundary p p p\nregion box block 0 0.01 0 0.01 0 0.002\ncreate_box 1 box");
  EXPECT_NE(error_of("fix w all wall/impulse zlo 0 e 0.5 mu 0.1").find("periodic z"), std::string::npos);
}

TEST_F(GranImpulse, AtomStyleWithoutRadiusIsAnError)
{
  command("clear\nplugin load " ACTIVEGRAIN_PLUGIN_FILE);
  command("units si\natom_style atomic\nregion box block 0 0.01 0 0.01 0 0.002\ncreate_box 1 box\n"
          "create_atoms 1 single 0.005 0.005 0.001\nmass 1 1e-6\ncomm_modify vel yes\n"
          "pair_style gran/impulse\npair_coeff * * 0.3 0.05");
  EXPECT_NE(error_of("run 1").find("Pair gran/impulse requires atom attributes radius"), std::string::npos);
}

TEST_F(GranImpulse, UnsetPairCoefficientsMixGeometrically)
{
  bead(0.003, 0.005, 0.001, 0.1, 0.0, 0.0, 1);
  bead(0.006, 0.005, 0.001, -0.05, 0.0, 0.0, 2);
  command("pair_style gran/impulse\npair_coeff 1 1 0.2 0.05\npair_coeff 2 2 0.8 0.05\n"
          "fix nve all nve/sphere\nrun 3000");
  EXPECT_NEAR(v(2, 'x') - v(1, 'x'), std::sqrt(0.2 * 0.8) * 0.15, 1e-12);
}

TEST_F(GranImpulse, PlatesMovingFarInOneStepGiveAWarning)
{
  // 25 steps per period is allowed, but the plates then move 1.26 % of a 1 mm gap per step.
  bead(0.005, 0.005, 0.0006, 0, 0, 0);
  command(PAIR);
  command("fix nve all nve/sphere\n"
          "fix plates all wall/impulse zlo 0.0 gap 0.001 vibrate 0.00005 200 0 e 0.3 mu 0.01\n"
          "timestep 2e-4");
  const int before = lmp->error->get_numwarn();
  command("run 1");
  EXPECT_GT(lmp->error->get_numwarn(), before);
  command("timestep 1e-5");
  const int after = lmp->error->get_numwarn();
  command("run 1");
  EXPECT_EQ(lmp->error->get_numwarn(), after);
}

TEST_F(GranImpulse, MovingRegionWallContinuesExactlyAcrossARestart)
{
  // Beads pushed by gravity (along -x) against a cylinder wall that moves along +x at 0.02 m/s:
  // they touch it in every step. The wall's velocity is its displacement since the last step, so
  // the restart file must keep the region's last position; without it the first step after
  // read_restart would see the wall move its whole displacement (0.3 mm) in one step.
  const std::string styles = "variable dx equal 0.02*time\n"
                             "region side cylinder z 0.005 0.005 0.004 INF INF side in move v_dx NULL NULL units box\n"
                             "fix nve all nve/sphere\nfix g all gravity 9.81 vector -1 0 0\n"
                             "fix side all wall/impulse/region side e 0.3 mu 0.2\n";
  auto deck = [&]() {
    command("clear\nplugin load " ACTIVEGRAIN_PLUGIN_FILE);
    command(BOX);
    const double y[5] = {0.005, 0.0038, 0.0062, 0.0027, 0.0073};
    for (int k = 0; k < 5; ++k) bead(0.0025 + 0.0002 * k, y[k], 0.001, 0.0, 0.0, 0.0);
    command(PAIR);
    command(styles);
  };
  auto state = [&]() {
    std::vector<double> s;
    for (int id = 1; id <= 5; ++id)
      for (const char *q : {"x", "y", "vx", "vy"}) s.push_back(value(fmt("{}[{}]", q, id)));
    return s;
  };

  // The reference runs the same two halves without the restart: LAMMPS recomputes the
  // simulation time (and so the region's position) at a run's start, which differs in the last
  // bits from one long run, and the beads' resting contacts amplify such differences.
  deck();
  command("run 1500 post no\nrun 1500 post no");
  const auto continuous = state();
  // The beads rest on the wall's inside and are carried along by it.
  EXPECT_NEAR(value("vx[1]"), 0.02, 1e-3);

  deck();
  command("run 1500 post no\nwrite_restart moving-region.restart");
  command("clear\nplugin load " ACTIVEGRAIN_PLUGIN_FILE);
  command("read_restart moving-region.restart\ncomm_modify vel yes\nneighbor 0.0002 bin\n" + styles +
          "run 1500 post no");
  const auto restarted = state();
  for (size_t k = 0; k < continuous.size(); ++k)
    EXPECT_NEAR(restarted[k], continuous[k], 1e-12 * (k % 4 < 2 ? 0.01 : 0.1)) << k;
}

TEST_F(GranImpulse, VibratingPlatesKeepTheirPhaseAcrossARestartWrittenDuringARun)
{
  // A bead between vibrating plates; the restart file is written by the restart command inside
  // one run, at a step (1370) that is no whole number of vibration periods (500 steps). LAMMPS
  // keeps the run's start time in such a file and drops the time since it at the next run's
  // setup (while a read_restart is not followed by a timestep command): the plates, whose drive
  // is a function of the time, would jump by 370 steps of phase (0.74 of a period).
  const std::string styles = "fix nve all nve/sphere\nfix g all gravity 9.81 vector 0 0 -1\n"
                             "fix plates all wall/impulse zlo 0.0 gap 1.12e-3 vibrate 4e-5 200 0.3 e 0.3 mu 0.05\n";
  auto state = [&]() {
    return std::vector<double>{value("f_plates[1]"), value("f_plates[3]"), value("z[1]"), value("vz[1]")};
  };
  command("clear\nplugin load " ACTIVEGRAIN_PLUGIN_FILE);
  command(BOX);
  bead(0.005, 0.005, 0.0005, 0.01, 0.0, 0.0);
  command(PAIR);
  command(styles);
  command("restart 1370 plates-phase.restart\nrun 2000 post no");
  const auto continuous = state();
  command("clear\nplugin load " ACTIVEGRAIN_PLUGIN_FILE);
  command("read_restart plates-phase.restart.1370\ncomm_modify vel yes\nneighbor 0.0002 bin\n" + styles +
          "run 630 post no");
  const auto restarted = state();
  EXPECT_NEAR(restarted[0], continuous[0], 1e-15);    // base plate height
  EXPECT_NEAR(restarted[1], continuous[1], 1e-12);    // plate velocity
  EXPECT_NEAR(restarted[2], continuous[2], 1e-12);    // the bead
  EXPECT_NEAR(restarted[3], continuous[3], 1e-9);
}

TEST_F(GranImpulse, AtomsOfFixFreezeAreBodiesOfInfiniteMass)
{
  // A bead hits a frozen bead head-on: it rebounds with e as from a wall, and the frozen bead
  // (touching another frozen one: a contact skipped) takes nothing. As GRANULAR treats fix freeze.
  bead(0.003, 0.005, 0.001, 0.1, 0.0, 0.0);
  bead(0.006, 0.005, 0.001, 0.0, 0.0, 0.0);
  bead(0.007, 0.005, 0.001, 0.0, 0.0, 0.0);
  command(PAIR);
  command("group frozen id 2 3\ngroup moving id 1\nfix nve moving nve/sphere\nfix hold frozen freeze\nrun 3000");
  EXPECT_NEAR(v(1, 'x'), -0.3 * 0.1, 1e-12);
  EXPECT_EQ(value("x[2]"), 0.006);
  EXPECT_EQ(v(2, 'x'), 0.0);
}

TEST_F(GranImpulse, ABeadCreatedBetweenRunsCarriesNoImpulseOfAnEarlierAtom)
{
  // A bead resting on another on a plate carries half its contact impulse into the next step.
  // Deleted between runs, its place in the per-atom arrays goes to a bead created in free fall
  // elsewhere: that bead must fall freely, not receive the deleted bead's contact force.
  bead(0.005, 0.005, 0.0005, 0.0, 0.0, 0.0);
  bead(0.005, 0.005, 0.0015, 0.0, 0.0, 0.0);
  command(PAIR);
  command("fix nve all nve/sphere\nfix g all gravity 9.81 vector 0 0 -1\n"
          "fix plates all wall/impulse zlo 0.0 e 0.3 mu 0.05\n");
  command("run 200 post no");
  ASSERT_NEAR(value("vz[2]"), 0.0, 1e-6);    // at rest on the lower bead
  command("delete_atoms group all compress no\n");
  bead(0.002, 0.002, 0.0015, 0.0, 0.0, 0.0);
  bead(0.008, 0.008, 0.0015, 0.0, 0.0, 0.0);
  command("run 1 post no");
  for (int id : {1, 2}) EXPECT_NEAR(value(fmt("vz[{}]", id)), -9.81e-5, 1e-15) << id;
}

// The contact models of pair_coeff: types without one of their own mix by geometric means, fix
// adapt reaches each coefficient by name, and a restart file brings them back.
TEST_F(GranImpulse, ContactModelsMixAdaptAndComeBackFromARestart)
{
  bead(0.003, 0.005, 0.001, 0.0, 0.0, 0.0, 1);
  bead(0.006, 0.005, 0.001, 0.0, 0.0, 0.0, 2);
  command("pair_style gran/impulse\npair_coeff 1 1 0.36 0.04\npair_coeff 2 2 0.25 0.09 tangential compliant 0.8\n"
          "fix nve all nve/sphere\nrun 0");
  auto coefficient = [&](const char *name, int i, int j) {
    int dim = 0;
    auto **array = static_cast<double **>(lmp->force->pair->extract(name, dim));
    EXPECT_EQ(dim, 2);
    return array ? array[i][j] : NAN;
  };
  EXPECT_DOUBLE_EQ(coefficient("e", 1, 2), 0.3);
  EXPECT_DOUBLE_EQ(coefficient("mu", 2, 1), 0.06);
  EXPECT_EQ(coefficient("tangential", 1, 1), 0.0);    // sticking
  EXPECT_EQ(coefficient("tangential", 1, 2), 1.0);    // compliant: type 2 is
  EXPECT_DOUBLE_EQ(coefficient("stiffness_ratio", 1, 2), 0.8);
  int dim = 0;
  EXPECT_EQ(lmp->force->pair->extract("nothing", dim), nullptr);
  command("variable e_bb equal 0.5\nfix adapt all adapt 1 pair gran/impulse e 2 2 v_e_bb\nrun 1\nunfix adapt");
  EXPECT_DOUBLE_EQ(coefficient("e", 2, 2), 0.5);
  const std::string file = "contact-models.restart";
  command("write_restart " + file + "\nclear\nplugin load " ACTIVEGRAIN_PLUGIN_FILE "\nread_restart " + file);
  std::remove(file.c_str());
  EXPECT_DOUBLE_EQ(coefficient("e", 1, 1), 0.36);
  EXPECT_DOUBLE_EQ(coefficient("e", 2, 2), 0.5);
  EXPECT_DOUBLE_EQ(coefficient("mu", 2, 2), 0.09);
  EXPECT_EQ(coefficient("tangential", 2, 2), 1.0);
  EXPECT_DOUBLE_EQ(coefficient("stiffness_ratio", 2, 2), 0.8);
}

// Chung and Ooi's test 4 through LAMMPS (an aluminium-oxide sphere, 3.9 m/s at 20 degrees from the
// normal onto a still plate, e 0.98, mu 0.092): with the compliant law on the plate its contact
// point leaves backwards, as Kharaz, Gorham and Salman measured; the sticking law leaves it at rest.
// The same through pair_coeff, a bead onto a bead frozen in place.
TEST_F(GranImpulse, TheCompliantLawReversesTheContactPointOfAnObliqueImpact)
{
  const double R = 0.5e-3, speed = 3.9, a = 20.0 * M_PI / 180.0;
  const double vx = speed * std::sin(a), vz = speed * std::cos(a);
  const std::string ratio = "0.8024";    // Mindlin's 2 (1 - nu) / (2 - nu) at nu 0.33
  auto omega_y = [&](int id) { return lmp->atom->omega[lmp->atom->map(id)][1]; };
  for (const std::string &law : std::vector<std::string>{"", " tangential compliant " + ratio}) {
    command("delete_atoms group all");
    bead(0.005, 0.005, R + 1.5 * vz * 1e-5, vx, 0.0, -vz);
    command("fix nve all nve/sphere\nfix plate all wall/impulse zlo 0.0 e 0.98 mu 0.092" + law + "\n" + PAIR + "run 5");
    const int id = (int) lmp->atom->natoms;
    const double point = value(fmt("vx[{}]", id)) - R * omega_y(id);
    if (law.empty()) EXPECT_NEAR(point, 0.0, 1e-12 * speed);
    else EXPECT_LT(point, -0.3 * vx);
    command("unfix plate\nunfix nve");
  }
  command("delete_atoms group all");
  bead(0.005, 0.005, R, 0.0, 0.0, 0.0, 2);
  bead(0.005 + 2 * R * std::sin(a), 0.005, R + 2 * R * std::cos(a) + 1.5 * speed * 1e-5, 0.0, 0.0, -speed);
  command("group frozen id " + std::to_string((int) lmp->atom->natoms - 1) + "\ngroup moving subtract all frozen\n"
          "fix nve moving nve/sphere\nfix still frozen freeze\npair_style gran/impulse\n"
          "pair_coeff * * 0.98 0.092 tangential compliant " + ratio + "\nrun 5");
  const int id = (int) lmp->atom->natoms;
  // The contact point's velocity along the surface (tangent t in the x-z plane, away from the normal).
  const double nx = std::sin(a), nz = std::cos(a), tx = nz, tz = -nx;
  const double v_in = -speed * tz;    // what the point brings along t (spin 0)
  const double point_t = value(fmt("vx[{}]", id)) * tx + value(fmt("vz[{}]", id)) * tz -
      R * omega_y(id) * (nz * tx - nx * tz);
  EXPECT_LT(point_t, -0.3 * v_in);
}
