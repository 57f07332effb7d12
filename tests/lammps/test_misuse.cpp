// The mistakes a newcomer makes, each a base deck that runs plus the lines that make it wrong,
// checked for its message: forgotten units si (and the reverse), rod atoms integrated as free
// particles, a rod whose atoms carry two molecule IDs, plates counted twice, gravity with no
// plate, a cutoff too small for a rod, a rod longer than its periodic box, flat vibrated plates,
// atoms that no fix integrates, a slop of a sizeable part of a diameter.
#include "lammps_fixture.h"
#include "rod_deck.h"

#include "error.h"

#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

using ::testing::HasSubstr;

namespace {

// One 1 mm bead above a vibrated plate under gravity, SI numbers: `units` first, or none.
std::string bead_deck(const std::string &units)
{
  return units + "\natom_style sphere\natom_modify map array\nboundary p p f\n"
      "region box block 0 0.01 0 0.01 0 0.002\ncreate_box 2 box\ncomm_modify vel yes\n"
      "create_atoms 1 single 0.005 0.005 0.001\nset atom 1 diameter 0.001\nset atom 1 density 2700\n"
      "pair_style gran/impulse\npair_coeff * * 0.3 0.05\nfix nve all nve/sphere\n"
      "timestep 1e-5\n";
}
const char *const GRAVITY = "fix g all gravity 9.81 vector 0 0 -1\n";
const char *const PLATES = "fix plates all wall/impulse zlo 0.0 gap 1.12e-3 vibrate 4e-5 200 0 e 0.3 mu 0.01 "
                           "rough 0.1 2e-3 7\n";

}    // namespace

class Misuse : public LammpsTest {
 protected:
  int warnings() { return lmp->error->get_numwarn(); }
  // A paper rod in a periodic box, with no gravity.
  std::string rod_deck(double half = 6e-3, const std::string &cutoff = "6e-3")
  {
    return rod_deck::box(half) + "comm_modify vel yes cutoff " + cutoff + "\nneighbor 5e-4 bin\n" +
        rod_deck::rod_template(file("rod.mol")) + rod_deck::flat_rod(1e-5) +
        "pair_style gran/impulse\npair_coeff * * 0.3 0.05\n";
  }
  std::string file(const std::string &name)
  {
    return ::testing::UnitTest::GetInstance()->current_test_info()->name() + std::string("-") + name;
  }
  // What the commands print to the log (warnings included), from a log file of their own.
  std::string logged(const std::string &text)
  {
    const std::string log = file("log.txt");
    command("log " + log);
    command(text);
    command("log none");
    std::ifstream in(log);
    std::stringstream read;
    read << in.rdbuf();
    std::remove(log.c_str());
    return read.str();
  }
};

TEST_F(Misuse, ForgottenUnitsSiIsRefused)
{
  command(bead_deck("units si") + GRAVITY + PLATES);
  EXPECT_EQ(error_of("run 10 post no"), "");
  // The same numbers in lj units, each sign alone: gravity 9.81, the plates' 63 (4e-5 (2 pi 200)^2),
  // or lj's default skin 0.3 (300 diameters).
  const std::string small_skin = "neighbor 1e-4 bin\n";
  const std::string extras[] = {GRAVITY + small_skin, PLATES + small_skin, ""};
  for (const std::string &extra : extras) {
    command("clear\nplugin load " ACTIVEGRAIN_PLUGIN_FILE);
    command(bead_deck("") + extra);
    EXPECT_THAT(error_of("run 10 post no"),
                HasSubstr("Pair gran/impulse: particles of diameter 0.001 in units lj (LAMMPS's default units, "
                          "lengths in grain diameters)")) << extra;
    EXPECT_THAT(error_of("run 10 post no"), HasSubstr("these are SI numbers: add units si")) << extra;
  }
  // Small grains in lj units with nothing SI-sized: a warning only.
  command("clear\nplugin load " ACTIVEGRAIN_PLUGIN_FILE);
  command(bead_deck("") + "neighbor 1e-4 bin\n");
  const int before = warnings();
  EXPECT_EQ(error_of("run 10 post no"), "");
  EXPECT_EQ(warnings(), before + 1);
}

TEST_F(Misuse, LjNumbersInUnitsSiWarn)
{
  // d = 1, g = 1 (a granular deck in lj numbers) under units si.
  command("units si\natom_style sphere\nboundary p p f\nregion box block 0 10 0 10 0 4\ncreate_box 1 box\n"
          "comm_modify vel yes\ncreate_atoms 1 single 5 5 1\nset atom 1 diameter 1\nset atom 1 density 1\n"
          "pair_style gran/impulse\npair_coeff * * 0.3 0.05\nfix nve all nve/sphere\n"
          "fix g all gravity 1.0 vector 0 0 -1\nfix plates all wall/impulse zlo 0.0 e 0.3 mu 0.1\n"
          "neighbor 0.2 bin\ntimestep 1e-3");
  const int before = warnings();
  EXPECT_EQ(error_of("run 10 post no"), "");
  EXPECT_EQ(warnings(), before + 1);
}

TEST_F(Misuse, RodAtomsIntegratedAsFreeParticlesAreRefused)
{
  command(rod_deck() + "fix rods all rigid/rod molecule mol rod\n"
          "timestep 1e-5\nthermo_style custom step");
  EXPECT_EQ(error_of("run 5 post no"), "");
  // Instead of fix rigid/rod, and besides it.
  command("unfix rods\nfix nve all nve/sphere");
  EXPECT_THAT(error_of("run 5 post no"),
              HasSubstr("Pair gran/impulse: fix nve (style nve/sphere) integrates rod atoms (atoms with a molecule ID) "
                        "as free particles: rods need fix rigid/rod"));
  command("fix rods all rigid/rod molecule mol rod");
  EXPECT_THAT(error_of("run 5 post no"), HasSubstr("fix nve (style nve/sphere) integrates rod atoms"));
}

TEST_F(Misuse, ARodWithTwoMoleculeIdsIsRefused)
{
  command(rod_deck() + "timestep 1e-5\nthermo_style custom step");
  // Two rods, molecule IDs 1 and 2; an atom of the first given the second's ID (a new ID alone
  // makes a body of one atom, which fix rigid/small refuses itself).
  command("create_atoms 0 single 0 -3e-3 5e-4 mol rod 2 units box\nfix rods all rigid/rod molecule mol rod");
  EXPECT_EQ(error_of("run 5 post no"), "");
  command("unfix rods\nset atom 5 mol 2\nfix rods all rigid/rod molecule mol rod");
  EXPECT_THAT(error_of("run 5 post no"),
              HasSubstr("Fix rigid/rod: molecule ID 1 has 8 atoms, a rod of template rod has 9: a rod's atoms must "
                        "carry one molecule ID of their own"));
}

TEST_F(Misuse, TwoPlateFixesOnTheSameAtomsAreRefused)
{
  command(bead_deck("units si") + GRAVITY + PLATES);
  EXPECT_EQ(error_of("run 5 post no"), "");
  command("fix plates2 all wall/impulse zlo 0.0 gap 1.12e-3 vibrate 4e-5 200 0 e 0.3 mu 0.01 rough 0.1 2e-3 7");
  EXPECT_THAT(error_of("run 5 post no"),
              HasSubstr("Fix wall/impulse: fixes plates and plates2 act on the same atoms: their plates would be "
                        "counted twice"));
  // On other atoms, a second fix is fine.
  command("group none empty\nunfix plates2\nfix plates2 none wall/impulse zlo 0.0 e 0.3 mu 0.01");
  EXPECT_EQ(error_of("run 5 post no"), "");
}

TEST_F(Misuse, GravityWithoutAPlateWarns)
{
  command(bead_deck("units si") + GRAVITY);
  const int before = warnings();
  EXPECT_EQ(error_of("run 1 post no"), "");
  EXPECT_EQ(warnings(), before + 1);
  command("fix plates all wall/impulse zlo 0.0 e 0.3 mu 0.01");
  EXPECT_EQ(error_of("run 1 post no"), "");
  EXPECT_EQ(warnings(), before + 1);
}

TEST_F(Misuse, VibratedFlatPlatesWithBeadsNoteRoughOnce)
{
  command(bead_deck("units si") + GRAVITY + PLATES);
  int before = warnings();
  command("run 1 post no");
  EXPECT_EQ(warnings(), before);
  command("unfix plates\nfix plates all wall/impulse zlo 0.0 gap 1.12e-3 vibrate 4e-5 200 0 e 0.3 mu 0.01");
  before = warnings();
  command("run 1 post no\nrun 1 post no");
  EXPECT_EQ(warnings(), before + 1);
}

TEST_F(Misuse, ARodLongerThanItsPeriodicBoxIsRefused)
{
  // 4.5 mm rods in a 4.4 mm periodic box.
  command(rod_deck::box(2.2e-3) + "comm_modify vel yes cutoff 6e-3\nneighbor 5e-4 bin\n" +
          rod_deck::rod_template(file("rod.mol")) + "pair_style gran/impulse\npair_coeff * * 0.3 0.05\n");
  EXPECT_THAT(error_of("fix rods all rigid/rod molecule mol rod\nrun 0 post no"),
              HasSubstr("Fix rigid/rod: rods of template rod are 0.0045 long, longer than the periodic box (x length "
                        "0.0044): a rod would touch its own image; enlarge the box"));
}

TEST_F(Misuse, TheCutoffQuotedOnOneRankIsTheRule)
{
  command(rod_deck(6e-3, "1e-3") + "fix rods all rigid/rod molecule mol rod\ntimestep 1e-5\nthermo_style custom step");
  const std::string message = error_of("run 1 post no");
  EXPECT_THAT(message, HasSubstr("Fix rigid/rod: rod extent"));
  EXPECT_THAT(message, HasSubstr("(valid on any number of ranks)"));
}

TEST_F(Misuse, AtomsThatNoFixIntegratesWarnOnce)
{
  // Two beads, one integrated by fix nve/sphere, the other too, or frozen (fix freeze): no warning.
  command(bead_deck("units si") + GRAVITY + PLATES +
          "create_atoms 2 single 0.007 0.007 0.001\nset atom 2 diameter 0.001\nset atom 2 density 2700\n"
          "group first id 1\ngroup second id 2");
  const int before = warnings();
  EXPECT_EQ(error_of("run 5 post no"), "");
  command("unfix nve\nfix nve second nve/sphere\nfix frozen first freeze");
  EXPECT_EQ(error_of("run 5 post no"), "");
  EXPECT_EQ(warnings(), before);
  // The first's integrator deleted: it would sit still while contacts push it. One warning, not
  // one a run; run 0 moves nothing and says nothing.
  command("unfix frozen\nrun 0 post no");
  EXPECT_EQ(warnings(), before);
  const std::string log = logged("run 5 post no");
  EXPECT_EQ(warnings(), before + 1);
  EXPECT_THAT(log, HasSubstr("WARNING: Pair gran/impulse: 1 of 2 atoms (types 1) are in the group of no "
                             "time-integrating fix (fix nve/sphere, fix rigid/rod, ...) nor of fix freeze: contacts "
                             "push them but they never move"));
  command("run 5 post no");
  EXPECT_EQ(warnings(), before + 1);
  // Rod atoms in fix rigid/rod's group are integrated (as bodies).
  command("clear\nplugin load " ACTIVEGRAIN_PLUGIN_FILE);
  command(rod_deck() + "fix rods all rigid/rod molecule mol rod\ntimestep 1e-5\nthermo_style custom step");
  const int rods_before = warnings();
  EXPECT_EQ(error_of("run 5 post no"), "");
  EXPECT_EQ(warnings(), rods_before);
  command("unfix rods\ngroup none empty\nfix idle none nve/sphere");
  EXPECT_THAT(logged("run 5 post no"), HasSubstr("Pair gran/impulse: 9 of 9 atoms (types 1 2 3) are in the group of "
                                                 "no time-integrating fix"));
}

TEST_F(Misuse, ASlopAboveATenthOfTheSmallestDiameterWarnsOnce)
{
  // 1 mm beads: slop 0.05 mm is fine, 0.15 mm is more than a tenth of a diameter.
  command(bead_deck("units si") + GRAVITY + PLATES + "pair_style gran/impulse slop 5e-5\npair_coeff * * 0.3 0.05");
  const int before = warnings();
  EXPECT_EQ(error_of("run 5 post no"), "");
  EXPECT_EQ(warnings(), before);
  command("pair_style gran/impulse slop 1.5e-4\npair_coeff * * 0.3 0.05");
  EXPECT_THAT(logged("run 5 post no"),
              HasSubstr("WARNING: Pair gran/impulse: slop 0.00015 is more than a tenth of the smallest particle "
                        "diameter 0.001: overlaps up to slop are never pushed apart"));
  EXPECT_EQ(warnings(), before + 1);
  command("run 5 post no");
  EXPECT_EQ(warnings(), before + 1);
}
