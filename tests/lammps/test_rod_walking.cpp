// Vibrated tapered rods walk nose-first: emergent from vibration, plate friction and taper
// (no propulsion force anywhere). Paper parameters: plates 1.12 mm apart, 200 Hz, A = 0.04 mm,
// rod-plate e 0.1, mu 0.03, gravity. Each case: 4 rods far apart, 0.1 s settling + 2 s measured.
#include "lammps_fixture.h"
#include "rod_walking.h"

#include <cmath>
#include <cstdio>

using namespace rod_walking;

namespace {
// The largest time step at which the speed stays within 10% of the small-dt value
// (examples/single-rod/measure.py dt; see the time-step table in the docs).
constexpr const char *LARGEST_CONVERGED_DT = "1e-4";
constexpr const char *REFERENCE_DT = "2.5e-6";
}    // namespace

class RodWalkingTest : public LammpsTest {
 protected:
  // Flat plates (the deterministic model) unless rough_plates: then the deck's calibrated roughness.
  std::vector<double> walk(std::map<std::string, std::string> vars, int nside = 2, bool rough_plates = false)
  {
    vars.emplace("tag", "test_walking");
    vars.emplace("nside", std::to_string(nside));
    vars.emplace("dt", LARGEST_CONVERGED_DT);
    command(deck(rough_plates ? vars : flat_plates(vars), nside * nside));
    return speeds(lmp, nside * nside);
  }
  // Index variables survive "clear": start a new instance for a second system.
  void fresh_lammps()
  {
    LammpsTest::TearDown();
    LammpsTest::SetUp();
  }
  static void report(const char *what, const std::vector<double> &v)
  {
    std::printf("[ measured ] %s: speed along own axis", what);
    for (double x : v) std::printf(" %+.3f", x * 1e3);
    std::printf(" mm/s (mean %+.3f)\n", mean(v) * 1e3);
  }
};

TEST_F(RodWalkingTest, PaperRodWalksNoseFirst)
{
  const auto v = walk({});
  report("paper rods", v);
  for (double x : v) EXPECT_GT(x, 0.0);
  // A walk, not a drift: at least 1 mm/s (experiment: 3.6 +- 2.5 mm/s).
  EXPECT_GT(mean(v), 1e-3);
}

TEST_F(RodWalkingTest, ReversedTaperWalksTheOtherWay)
{
  // Tail atom narrow, nose atom wide: the rod still leads with its narrow end, i.e. tail-first.
  const auto v = walk({{"tail", "0.7e-3"}, {"nose", "1.1e-3"}});
  report("reversed taper", v);
  for (double x : v) EXPECT_LT(x, 0.0);
}

TEST_F(RodWalkingTest, NoPlateFrictionNoTranslation)
{
  const auto frictional = walk({});
  fresh_lammps();
  const auto frictionless = walk({{"mu_wall", "0"}});
  report("mu_wall 0", frictionless);
  for (double x : frictionless) EXPECT_LT(std::fabs(x), 0.1 * mean(frictional));
}

// The deck's calibrated plate roughness (docs/calibration.rst) scatters the walk but keeps what
// the flat plates show: nose first, the other way with the taper reversed, no walk without plate
// friction. Frictionless rods are not still on rough plates, though: tilted normals kick them
// sideways and only restitution along the tilt damps that, so they wander at a few mm/s, along
// their axes as often backwards as forwards (measured over 9 rods: mean within its standard error
// of zero).
TEST_F(RodWalkingTest, OnCalibratedRoughPlatesTheWalkKeepsItsDirection)
{
  const auto paper = walk({}, 2, true);
  report("rough plates", paper);
  EXPECT_GT(mean(paper), 1e-3);
  fresh_lammps();
  const auto reversed = walk({{"tail", "0.7e-3"}, {"nose", "1.1e-3"}}, 2, true);
  report("rough plates, reversed taper", reversed);
  EXPECT_LT(mean(reversed), -1e-3);
  fresh_lammps();
  const auto frictionless = walk({{"mu_wall", "0"}}, 3, true);
  report("rough plates, mu_wall 0", frictionless);
  EXPECT_LT(std::fabs(mean(frictionless)), 3.0 * standard_error(frictionless));
}

TEST_F(RodWalkingTest, LargestConvergedTimeStep)
{
  const auto large = walk({}, 1);
  fresh_lammps();
  const auto small = walk({{"dt", REFERENCE_DT}}, 1);
  std::printf("[ measured ] dt %s: %+.3f mm/s, dt %s: %+.3f mm/s\n", LARGEST_CONVERGED_DT, large[0] * 1e3,
              REFERENCE_DT, small[0] * 1e3);
  EXPECT_NEAR(large[0] / small[0], 1.0, 0.1);
}

TEST_F(RodWalkingTest, RodDroppedFlatOnStillPlateComesToRest)
{
  // No vibration: a rod released flat at mid-gap falls onto the base plate and stops there.
  command("variable tag index test_rest\nvariable nside index 1\nvariable amplitude index 0\n"
          "variable dt index 1e-5\nvariable time index 0.2\n"
          "include " ACTIVEGRAIN_SOURCE_DIR "/examples/single-rod/in.single-rod\n"
          "undump bodies\n"
          "compute xcm all com\nvariable x equal c_xcm[1]\nvariable y equal c_xcm[2]\n"
          "variable speed equal sqrt(vcm(all,x)^2+vcm(all,y)^2+vcm(all,z)^2)\n"
          "run 0 post no");
  const double x0 = value("v_x"), y0 = value("v_y");
  command("run 20000 post no");    // 0.2 s more
  // At rest, against 4 mm/s and 0.8 mm in 0.2 s for walking: below 1% of that speed and 0.25%
  // of that distance. (Without rolling resistance a rigid rod may keep rocking about its axis on
  // the slopes of the rough plates under its spheres: up to 2e-5 m/s here, 2e-7 to 2e-4 m/s
  // for other seeds, the same with and without the pair style's window; on flat plates it rolls
  // steadily at 2e-6 m/s.)
  EXPECT_LT(value("v_speed"), 4e-5);
  EXPECT_LT(std::hypot(value("v_x") - x0, value("v_y") - y0), 2e-6);
}

TEST_F(RodWalkingTest, RestartContinuesTheWalkExactly)
{
  const std::string restart = "test_walking_restart.restart";
  command("variable tag index test_restart\nvariable nside index 1\nvariable dt index 5e-5\n"
          "variable time index 0.05\n"
          "include " ACTIVEGRAIN_SOURCE_DIR "/examples/single-rod/in.single-rod\n"
          "undump bodies\n"
          "write_restart " + restart + "\nrun 1000 post no");
  const double x = value("xcm(all,x)"), y = value("xcm(all,y)"), vx = value("vcm(all,x)");

  // The styles again after read_restart (templates and rigid fixes are not in restart files; the
  // pair style and its settings, the window of impacts in order among them, are).
  fresh_lammps();
  command("atom_modify map array\nread_restart " + restart + "\n"
          "fix molecule_ids all property/atom mol ghost yes\n" +
          single_rod_styles("out/rod_test_restart2.mol", DECK_ROUGHNESS, false) + "timestep 5e-5\nrun 1000 post no");
  EXPECT_NEAR(value("xcm(all,x)"), x, 1e-12);
  EXPECT_NEAR(value("xcm(all,y)"), y, 1e-12);
  EXPECT_NEAR(value("vcm(all,x)"), vx, 1e-12);
}

TEST_F(RodWalkingTest, OnRoughPlatesRodsSpinAsAtSmallStepsWithImpactsInOrder)
{
  // The rods' spin about the vertical on the calibrated rough plates sets how often they turn.
  // Its mean square (4 rods, 4 s after settling) at the decks' step against 1e-5 s: with the
  // impacts of a step in their order (the deck's window) within 25 %; lumped into one impact per
  // step (window step) at 1e-4 s it was half (measured 0.89-0.90 against 0.48,
  // docs/time_step.rst).
  auto mean_square_spin = [&](const std::string &dt, const std::string &window) {
    command("variable tag index test_spin\nvariable nside index 2\nvariable dt index " + dt +
            "\nvariable window index " + window + "\nvariable time index " + std::to_string(SETTLE) +
            "\ninclude " ACTIVEGRAIN_SOURCE_DIR "/examples/single-rod/in.single-rod\n"
            "undump bodies\nthermo 0\n"
            "compute spin all property/atom omegaz\nvariable spin2 atom c_spin*c_spin\n"
            "compute mean_spin2 all reduce ave v_spin2\n"
            "fix spin all ave/time 10 1 10 c_mean_spin2 ave running\n"
            "run $(round(4.0/dt))");
    return value("f_spin");
  };
  const double large = mean_square_spin(LARGEST_CONVERGED_DT, "5e-6");
  fresh_lammps();
  const double lumped = mean_square_spin(LARGEST_CONVERGED_DT, "step");
  fresh_lammps();
  const double small = mean_square_spin("1e-5", "5e-6");
  std::printf("[ measured ] <omega_z^2>: dt %s %.3f, lumped %.3f, dt 1e-5 %.3f (rad/s)^2\n",
              LARGEST_CONVERGED_DT, large, lumped, small);
  EXPECT_NEAR(large / small, 1.0, 0.25);
  EXPECT_LT(lumped / small, 0.75);
}
