// Resting contacts solved together (pair_style gran/impulse resting yes) in dense packings of
// rods and beads between the vibrating rough plates of the paper's decks: a packing at bead
// fraction 0.78, rods 0.04, and the jammed corner of the phase diagram (the committed state
// examples/channel/states/channel-small-jammed-corner-0s.data.gz: 30 x 15 d, total 0.862). The
// bodies' velocities do not depend on the order in which contacts are handed to the solver (tag,
// reverse, shuffle) beyond the solve's tolerance, and every resting solve converges within its
// sweep cap (tests/core/test_resting_solve.cpp checks single solves); the solve's tolerance is
// kept in restart files.
#include "bead_box.h"

#include "atom.h"
#include "pair_gran_impulse.h"

#include <array>
#include <cmath>
#include <map>

namespace {
constexpr int STEPS = 200;
}    // namespace

class RestingContacts : public LammpsTest {
 protected:
  using Velocities = std::map<LAMMPS_NS::tagint, std::array<double, 3>>;

  // The packings: variables for examples/rods-and-beads/in.create (the jammed corner's cell and its
  // state apart: a continuation from a restart file takes the cell alone).
  static constexpr const char *DENSE = "variable geometry index box\nvariable Lx index 16e-3\nvariable Ly index 16e-3\n"
                                       "variable phi_b index 0.78\nvariable phi_r index 0.04\nvariable seed index 5\n";
  static constexpr const char *JAMMED_CELL =
      "variable geometry index channel\nvariable Lx index 30e-3\nvariable Ly index 15e-3\n"
      "variable phi_b index 0.8203\nvariable phi_r index 0.0414\n";
  static constexpr const char *JAMMED_STATE =
      "variable from index " ACTIVEGRAIN_SOURCE_DIR "/examples/channel/states/channel-small-jammed-corner-0s.data.gz\n";
  // in.create with resting contacts solved together, at dt 1e-4; its output (the rod template)
  // in a folder of the test's own, so that tests may run at once.
  static std::string out_folder()
  {
    return std::string("test_resting_contacts_") + ::testing::UnitTest::GetInstance()->current_test_info()->name();
  }
  std::string law = "yes";    // pair gran/impulse's resting
  std::string resting() const
  {
    return "variable resting index " + law + "\nvariable out index " + out_folder() +
        "\nvariable create_dir index " ACTIVEGRAIN_SOURCE_DIR "/examples/rods-and-beads\n"
        "include ${create_dir}/in.create\ntimestep 1e-4\n";
  }

  Velocities velocities()
  {
    Velocities v;
    for (int i = 0; i < lmp->atom->nlocal; ++i)
      v[lmp->atom->tag[i]] = {lmp->atom->v[i][0], lmp->atom->v[i][1], lmp->atom->v[i][2]};
    return v;
  }
  static double largest_difference(const Velocities &a, const Velocities &b)
  {
    double largest = 0.0;
    for (const auto &[id, v] : a)
      for (int k = 0; k < 3; ++k) largest = std::max(largest, std::fabs(v[k] - b.at(id)[k]));
    return largest;
  }

  // Every atom's velocity by tag after steps steps; the most sweeps a step's resting solve took.
  Velocities run(const std::string &packing, const std::string &order, int steps, double &most_sweeps)
  {
    command(packing + resting() +
            // the same style again: new settings, the same coefficients
            "pair_style gran/impulse resolution ${resolution} window ${window} resting " + law + " order " + order +
            "\ncompute solver all pair gran/impulse\n"
            "variable sweeps equal c_solver[" + std::to_string(LAMMPS_NS::PairGranImpulse::RESTING_SWEEPS + 1) +
            "]\nthermo_style custom step v_sweeps\nthermo 1\nrun 0 post no");
    most_sweeps = 0.0;
    for (int step = 0; step < steps; ++step) {
      command("run 1 pre no post no");
      most_sweeps = std::max(most_sweeps, value("v_sweeps"));
    }
    return velocities();
  }
  void fresh_lammps()
  {
    LammpsTest::TearDown();
    LammpsTest::SetUp();
  }

  // The jammed corner 20 steps on, then one step straight on and one from a restart file written
  // there: the largest velocity difference.
  double jammed_corner_a_step_after_a_restart_file()
  {
    const std::string file = out_folder() + ".restart";
    command(std::string(JAMMED_CELL) + JAMMED_STATE + resting() + "run 20 post no\nwrite_restart " + file +
            "\nrun 1 post no");
    const Velocities straight = velocities();
    fresh_lammps();
    command(std::string(JAMMED_CELL) + "variable continue index " + file + "\n" + resting() + "run 1 post no");
    const double largest = largest_difference(straight, velocities());
    std::printf("[ measured ] the jammed corner (resting %s), a step after a restart file: largest velocity "
                "difference %.3g m/s\n", law.c_str(), largest);
    return largest;
  }

  // Runs the packing in the three orders and compares the velocities with the solve's tolerance:
  // its resting speed (twice the plates' peak acceleration times dt) times resting_tolerance.
  void expect_the_same_velocities_in_every_order(const std::string &packing, const char *name, int steps)
  {
    double sweeps_tag = 0, sweeps_reverse = 0, sweeps_shuffle = 0;
    const Velocities tag = run(packing, "tag", steps, sweeps_tag);
    fresh_lammps();
    const Velocities reverse = run(packing, "reverse", steps, sweeps_reverse);
    fresh_lammps();
    const Velocities shuffle = run(packing, "shuffle", steps, sweeps_shuffle);
    const double largest = std::max(largest_difference(tag, reverse), largest_difference(tag, shuffle));
    double fastest = 0.0;
    for (const auto &[id, v] : tag)
      for (int k = 0; k < 3; ++k) fastest = std::max(fastest, std::fabs(v[k]));
    const ActiveGrain::SolverSettings settings;
    const double omega = 2.0 * M_PI * value("v_freq");
    const double tolerance =
        settings.resting_tolerance * settings.resting_gain * 1e-4 * omega * omega * value("v_amplitude");
    std::printf("[ measured ] %s, %zu atoms after %d steps: largest velocity difference between orders %.3g m/s "
                "(tolerance %.3g m/s, fastest component %.3g m/s); most sweeps of a step %g, %g, %g\n",
                name, tag.size(), steps, largest, tolerance, fastest, sweeps_tag, sweeps_reverse, sweeps_shuffle);
    EXPECT_LT(largest, tolerance);
    EXPECT_LT(std::max({sweeps_tag, sweeps_reverse, sweeps_shuffle}), settings.max_resting_sweeps);
  }
};

TEST_F(RestingContacts, BodyVelocitiesDoNotDependOnContactOrder)
{
  // The packing is created once and written as a state, from which each order starts: creating
  // it anew in each LAMMPS instance of this process does not always give the same atoms.
  command(std::string(DENSE) + resting() + "variable state index ${out}/dense\ninclude ${create_dir}/in.write-state");
  fresh_lammps();
  expect_the_same_velocities_in_every_order(DENSE + ("variable from index " + out_folder() + "/dense-0s.data.gz\n"),
                                            "bead fraction 0.78", STEPS);
}

TEST_F(RestingContacts, TheJammedCornersVelocitiesDoNotDependOnContactOrder)
{
  // The packing, kicked by the rough plates everywhere at once, is chaotic: the orders' round-off
  // in the compliant impacts (1e-15 m/s) grows about e-fold every 4 steps and reaches the
  // velocities themselves within 200 steps. Compared after 50.
  expect_the_same_velocities_in_every_order(std::string(JAMMED_CELL) + JAMMED_STATE, "the jammed corner", 50);
}

TEST_F(RestingContacts, TheJammedCornerContinuesFromARestartFileToRoundOff)
{
  // Every resting solve starts from the state alone: the restart file holds all it needs. What
  // differs is the rods' round-off on reading a restart file (without resting too: 1.6e-14 m/s
  // after 20 steps), which this chaotic packing grows about e-fold every 4 steps: compared after
  // the first step.
  EXPECT_LT(jammed_corner_a_step_after_a_restart_file(), 1e-15);
}

TEST_F(RestingContacts, WithRestingNewtonTheJammedCornersVelocitiesDoNotDependOnContactOrder)
{
  // The same with the restitution of collisions kept (Poisson's expansion and its energy bound).
  law = "newton";
  expect_the_same_velocities_in_every_order(std::string(JAMMED_CELL) + JAMMED_STATE, "the jammed corner, newton", 50);
}

TEST_F(RestingContacts, WithRestingNewtonTheJammedCornerContinuesFromARestartFileToRoundOff)
{
  // As above, with the restitution of collisions kept.
  law = "newton";
  EXPECT_LT(jammed_corner_a_step_after_a_restart_file(), 1e-15);
}

class RestingRing : public BeadBox {
 protected:
  static constexpr const char *STYLES = "fix nve all nve/sphere\ncompute solver all pair gran/impulse\n";
  // The sweeps of the next step's resting solve.
  double sweeps_of_next_step()
  {
    command("variable sweeps equal c_solver[" + std::to_string(LAMMPS_NS::PairGranImpulse::RESTING_SWEEPS + 1) +
            "]\nrun 1 post no");
    return value("v_sweeps");
  }
  void read_ring(const std::string &pair_style = "")
  {
    LammpsTest::TearDown();
    LammpsTest::SetUp();
    command("read_restart test_resting_ring.restart\ncomm_modify vel yes\nneighbor 0.0002 bin\n" + pair_style +
            STYLES);
  }
};

TEST_F(RestingRing, TheToleranceAndTheSweepCapTravelInRestartFiles)
{
  // A ring of 10 touching beads around the periodic box, jostled along it slower than the resting
  // speed: one resting solve from zero, whose sweeps depend on the tolerance and the cap. Read back
  // from a restart file, the style solves with the settings it was given, not the defaults.
  for (int i = 0; i < 10; ++i) bead(0.0005 + 0.001 * i, 0.005, 0.001, 0.01 * std::sin(2.3 * i + 0.5), 0, 0);
  command(std::string(PAIR) + "pair_style gran/impulse resting 0.05 tolerance 0.1\n" + STYLES +
          "run 0 post no\nwrite_restart test_resting_ring.restart");
  const double given = sweeps_of_next_step();
  read_ring();
  const double restarted = sweeps_of_next_step();
  read_ring("pair_style gran/impulse resting 0.05\n");
  const double by_default = sweeps_of_next_step();
  read_ring("pair_style gran/impulse resting 0.05 max_sweeps 3\n");
  command("write_restart test_resting_ring_capped.restart");
  const double capped = sweeps_of_next_step();
  LammpsTest::TearDown();
  LammpsTest::SetUp();
  command(std::string("read_restart test_resting_ring_capped.restart\ncomm_modify vel yes\nneighbor 0.0002 bin\n") +
          STYLES);
  const double capped_restarted = sweeps_of_next_step();
  std::printf("[ measured ] sweeps at tolerance 0.1: %g, after a restart %g; at the default tolerance %g; capped at "
              "3: %g, after a restart %g\n", given, restarted, by_default, capped, capped_restarted);
  EXPECT_GT(given, 1.0);
  EXPECT_EQ(restarted, given);
  EXPECT_GT(by_default, given);
  EXPECT_EQ(capped, 3.0);
  EXPECT_EQ(capped_restarted, 3.0);
}

class RestingPile : public BeadBox {
 protected:
  static constexpr double DT = 1e-4;
  void pile(const std::string &pair_style, int steps)
  {
    bead(0.0045, 0.005, 0.0005, 0, 0, 0);
    bead(0.0055, 0.005, 0.0005, 0, 0, 0);
    bead(0.005, 0.005, 0.0005 + 0.001 * std::sqrt(0.75), 0, 0, 0);
    command("pair_style gran/impulse resting yes " + pair_style + "\npair_coeff * * 0.3 0.5\n"
            "timestep 1e-4\nfix nve all nve/sphere\nfix g all gravity 9.81 vector 0 0 -1\n"
            "fix plate all wall/impulse zlo 0.0 e 0.3 mu 0.5\ncompute solver all pair gran/impulse\n"
            "variable overlap equal c_solver[" + std::to_string(LAMMPS_NS::PairGranImpulse::LARGEST_OVERLAP + 1) + "]\n"
            "thermo_style custom step ke v_overlap\nrun " + std::to_string(steps) + " post no");
  }
  double fastest()
  {
    double largest = 0.0;
    for (int i = 0; i < lmp->atom->nlocal; ++i)
      for (int k = 0; k < 3; ++k) largest = std::max(largest, std::fabs(lmp->atom->v[i][k]));
    return largest;
  }
};

TEST_F(RestingPile, WithinItsSlopAPileRestsWithoutPushes)
{
  // Without slop, the resting solve's tolerance lets gravity press each contact a little deeper in
  // a step and the overlap push opens it again: the beads keep a floor of velocity. Overlaps within
  // the slop touch and are not pushed: the pile settles into them, and only their excess is pushed.
  pile("", 1000);
  const double pushed = fastest(), pushed_overlap = value("v_overlap");
  LammpsTest::TearDown();
  LammpsTest::SetUp();
  command(BOX);
  const double slop = 1e-6;
  pile(fmt::format("slop {}", slop), 1000);
  const double still = fastest(), still_overlap = value("v_overlap");
  std::printf("[ measured ] a pile after 0.1 s: fastest velocity component %.3g m/s without slop, %.3g m/s with "
              "slop 1 um (g dt = %.3g m/s); largest overlap %.3g and %.3g m\n",
              pushed, still, 9.81 * DT, pushed_overlap, still_overlap);
  EXPECT_GT(pushed, 0.01 * 9.81 * DT);
  EXPECT_LT(still, 0.2 * pushed);
  EXPECT_LT(still_overlap, 1.5 * slop);
}

TEST_F(RestingPile, TheSlopTravelsInRestartFiles)
{
  // The pile with its contacts at the slop: read back without a pair_style command, the style
  // keeps its slop (without it, the next step would push the overlaps open).
  pile("slop 1e-6", 1000);
  command("write_restart test_resting_pile.restart\nrun 20 post no");
  const double straight = lmp->atom->v[lmp->atom->map(1)][2];
  LammpsTest::TearDown();
  LammpsTest::SetUp();
  command("read_restart test_resting_pile.restart\ncomm_modify vel yes\nneighbor 0.0002 bin\ntimestep 1e-4\n"
          "fix nve all nve/sphere\nfix g all gravity 9.81 vector 0 0 -1\n"
          "fix plate all wall/impulse zlo 0.0 e 0.3 mu 0.5\nrun 20 post no");
  const double restarted = lmp->atom->v[lmp->atom->map(1)][2];
  LammpsTest::TearDown();
  LammpsTest::SetUp();
  command("read_restart test_resting_pile.restart\ncomm_modify vel yes\nneighbor 0.0002 bin\ntimestep 1e-4\n"
          "pair_style gran/impulse resting yes\npair_coeff * * 0.3 0.5\n"
          "fix nve all nve/sphere\nfix g all gravity 9.81 vector 0 0 -1\n"
          "fix plate all wall/impulse zlo 0.0 e 0.3 mu 0.5\nrun 20 post no");
  const double without_slop = lmp->atom->v[lmp->atom->map(1)][2];
  std::printf("[ measured ] bead 1's vz 20 steps after the restart file: %.6g m/s straight on, %.6g restarted, "
              "%.6g restarted without slop\n", straight, restarted, without_slop);
  EXPECT_NEAR(restarted, straight, 1e-12);
  EXPECT_GT(std::fabs(without_slop - straight), 1e-9);
}

class RestingCollision : public BeadBox {
 protected:
  // Two beads resting on a still frictionless plate under gravity (each touching it: one island)
  // meet head-on at 1.5 mm/s, slower than resting yes's speed (2 dt g = 2 mm/s at dt 1e-4); the
  // separation velocity along x once they have met.
  double separation_after_meeting(const std::string &resting, bool through_a_restart = false)
  {
    bead(0.003, 0.005, 0.0005, 0.00075, 0, 0);
    bead(0.0040001, 0.005, 0.0005, -0.00075, 0, 0);
    const std::string styles = "timestep 1e-4\nfix nve all nve/sphere\nfix g all gravity 9.81 vector 0 0 -1\n"
                               "fix plate all wall/impulse zlo 0.0 e 0.3 mu 0.0\n";
    command("pair_style gran/impulse resting " + resting + "\npair_coeff * * 0.3 0.0\n" + styles);
    if (through_a_restart) {
      command("run 0 post no\nwrite_restart test_resting_collision.restart");
      LammpsTest::TearDown();
      LammpsTest::SetUp();
      command("read_restart test_resting_collision.restart\ncomm_modify vel yes\nneighbor 0.0002 bin\n" + styles);
    }
    command("run 3 post no");    // half of a step's impulse acts in the next step
    return value("vx[2]") - value("vx[1]");
  }
};

TEST_F(RestingCollision, RestingNewtonKeepsTheRestitutionOfASlowCollisionAlsoAfterARestart)
{
  // Resting yes ends the collision without rebound (the beads leave at what the overlap
  // correction gives their first step's overlap of 0.05 um); resting newton leaves at e = 0.3
  // times the approach, as resting no's impact does, also when read back from a restart file
  // (where the setting travels: the plastic default would stop it).
  const double approach = 0.0015, tolerance = 1.3 * 0.01 * 2 * 9.81 * 1e-4;
  const double plastic = separation_after_meeting("yes");
  LammpsTest::TearDown();
  LammpsTest::SetUp();
  command(BOX);
  const double newton = separation_after_meeting("newton");
  LammpsTest::TearDown();
  LammpsTest::SetUp();
  command(BOX);
  const double restarted = separation_after_meeting("newton", true);
  LammpsTest::TearDown();
  LammpsTest::SetUp();
  command(BOX);
  const double impact = separation_after_meeting("no");
  std::printf("[ measured ] separation over approach: resting yes %.4f, newton %.4f, newton restarted %.4f, no %.4f\n",
              plastic / approach, newton / approach, restarted / approach, impact / approach);
  EXPECT_LT(plastic, 0.1 * approach);    // the overlap correction's push of the first step's overlap
  EXPECT_NEAR(newton, 0.3 * approach, tolerance);
  EXPECT_NEAR(restarted, newton, 1e-15);
  EXPECT_NEAR(impact, 0.3 * approach, 1e-3 * approach);
}
