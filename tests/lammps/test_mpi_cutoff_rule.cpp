// One ghost cutoff rule for rigid bodies (ghost_cutoff.h): the value fix rigid/rod quotes on one
// rank, for a cutoff too small for a rod, runs unchanged on any number of ranks (this file runs
// on 1, 2 and 4 ranks; tests/integration/test_cutoff_rule.py on 8).
#include "lammps_fixture.h"
#include "rod_deck.h"

#include <regex>
#include <string>

using ::testing::HasSubstr;

namespace {

// Four paper rods in a periodic box, no gravity, moving: they cross the ranks' boundaries.
std::string deck(const std::string &cutoff)
{
  return rod_deck::box(6e-3) + "comm_modify vel yes cutoff " + cutoff + "\nneighbor 5e-4 bin\n" +
      rod_deck::rod_template("cutoff_rule-rod.mol") +
      "create_atoms 0 single -3e-3 -3e-3 0 mol rod 1 units box rotate 0 0 0 1\n"
      "create_atoms 0 single 3e-3 -3e-3 0 mol rod 2 units box rotate 90 0 0 1\n"
      "create_atoms 0 single -3e-3 3e-3 0 mol rod 3 units box rotate 45 0 0 1\n"
      "create_atoms 0 single 3e-3 3e-3 0 mol rod 4 units box rotate 135 0 1 0\n"
      "velocity all create 1e-6 4928 mom yes rot yes dist gaussian\n"
      "pair_style gran/impulse\npair_coeff * * 0.3 0.05\n"
      "fix rods all rigid/rod molecule mol rod\ntimestep 1e-5\nthermo_style custom step\n";
}

const std::regex QUOTED("use comm_modify cutoff ([0-9.e+-]+)");

}    // namespace

class CutoffRule : public LammpsTest {};

TEST_F(CutoffRule, TheValueQuotedOnOneRankRunsOnAnyNumberOfRanks)
{
  const std::vector<double> quoted = serial_reference(1, [](LAMMPS_NS::LAMMPS *alone) {
    lammps_commands_string(alone, (deck("1e-3") + "run 1 post no").c_str());
    char buf[2048] = "";
    if (lammps_has_error(alone)) lammps_get_last_error_message(alone, buf, sizeof(buf));
    std::cmatch m;
    return std::vector<double>{std::regex_search(buf, m, QUOTED) ? std::stod(m[1]) : 0.0};
  });
  ASSERT_GT(quoted[0], 0.0) << "no cutoff quoted on one rank";
  // The rod extent (2.25 mm) would do on one rank; the rule asks for the span plus the neighbor cutoff.
  EXPECT_GT(quoted[0], rod_deck::LENGTH);
  command(deck(fmt::format("{}", quoted[0])));
  EXPECT_EQ(error_of("run 200 post no"), "");
  // Just below the rule: refused on more than one rank, by pair gran/impulse, quoting the same value.
  int nprocs = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &nprocs);
  if (nprocs > 1) {
    command("comm_modify cutoff " + fmt::format("{}", 0.98 * quoted[0]));
    const std::string message = error_of("run 1 post no");
    EXPECT_THAT(message, HasSubstr("Pair gran/impulse: rigid body span"));
    EXPECT_THAT(message, HasSubstr(fmt::format("use comm_modify cutoff {}", quoted[0])));
  }
}
