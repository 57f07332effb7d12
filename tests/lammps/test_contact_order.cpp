// A rod's walking speed is a property of the model, not of the contact solver: the order in
// which contacts are visited (pair_style gran/impulse order tag|reverse|shuffle), the impact
// resolution once converged, and the numbering of a rod's atoms do not change it. Four paper
// rods on flat plates, 0.1 s settling + 2 s measured at dt 1e-5 s per case, within 2%
// (examples/single-rod/measure.py order repeats it with more rods; tests/core/test_contact_solver.cpp
// checks the order independence of a single solve).
#include "lammps_fixture.h"
#include "rod_walking.h"

#include <fstream>
#include <sstream>

using namespace rod_walking;

namespace {
constexpr const char *DT = "1e-5";
constexpr double AGREEMENT = 0.02;
constexpr int NRODS = 4;
}    // namespace

class ContactOrderTest : public LammpsTest {
 protected:
  double walk(std::map<std::string, std::string> vars)
  {
    vars.emplace("tag", "test_contact_order");
    vars.emplace("dt", DT);
    command(deck(flat_plates(vars), NRODS));
    return mean(speeds(lmp, NRODS));
  }
  void fresh_lammps()
  {
    LammpsTest::TearDown();
    LammpsTest::SetUp();
  }
  static void report(const char *what, double v) { std::printf("[ measured ] %s: %+.3f mm/s\n", what, v * 1e3); }
};

TEST_F(ContactOrderTest, SpeedDoesNotDependOnOrderOrResolution)
{
  const double shuffled = walk({});
  report("order shuffle (default)", shuffled);
  EXPECT_GT(shuffled, 1e-3);    // a walk, not a drift
  const std::vector<std::pair<const char *, std::map<std::string, std::string>>> cases = {
      {"order tag", {{"order", "tag"}}},
      {"order reverse", {{"order", "reverse"}}},
      {"resolution 1000", {{"resolution", "1000"}}}};
  for (const auto &[what, vars] : cases) {
    fresh_lammps();
    const double v = walk(vars);
    report(what, v);
    EXPECT_NEAR(v / shuffled, 1.0, AGREEMENT) << what;
  }
}

namespace {

// Reverse the atom IDs within each rod of a data file (9 atoms per molecule, IDs 9(m-1)+1 ..
// 9m): the nose atom gets the lowest ID. Atoms, Velocities and Molecules sections.
void renumber_nose_first(const std::string &in_file, const std::string &out_file, int spheres)
{
  std::ifstream in(in_file);
  std::ofstream out(out_file);
  std::string line;
  bool in_atom_section = false;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string first;
    fields >> first;
    if (first == "Atoms" || first == "Velocities" || first == "Molecules") in_atom_section = true;
    else if (!first.empty() && !std::isdigit(static_cast<unsigned char>(first[0]))) in_atom_section = false;
    if (in_atom_section && !first.empty() && std::isdigit(static_cast<unsigned char>(first[0]))) {
      const long id = std::stol(first);
      const long rod = (id - 1) / spheres, k = (id - 1) % spheres;
      std::string rest;
      std::getline(fields, rest);
      out << rod * spheres + (spheres - k) << rest << "\n";
    } else {
      out << line << "\n";
    }
  }
}

}    // namespace

TEST_F(ContactOrderTest, RenumberingARodNoseFirstDoesNotChangeItsSpeed)
{
  // The same four rods, written to a data file just after creation and read back with their
  // atom IDs as built (tail first) or reversed (nose first).
  int me = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  const std::string built = "test_contact_order_built.data", reversed = "test_contact_order_reversed.data";
  command("variable tag index test_contact_order\nvariable rough index 0\nvariable dt index " + std::string(DT) +
          "\nvariable time index 0\n"
          "include " ACTIVEGRAIN_SOURCE_DIR "/examples/single-rod/in.single-rod\n"
          "undump bodies\nwrite_data " + built + " nocoeff");
  if (me == 0) renumber_nose_first(built, reversed, 9);
  MPI_Barrier(MPI_COMM_WORLD);

  auto walk_from = [&](const std::string &file) {
    fresh_lammps();
    command("units si\natom_style sphere\natom_modify map array\ndimension 3\nboundary p p f\n"
            "fix molecule_ids all property/atom mol ghost yes\n"
            "read_data " + file + " fix molecule_ids NULL Molecules\n" +
            single_rod_styles("out/rod_test_contact_order_read.mol", "0 1e-3 1") +
            "thermo 0\ntimestep " + std::string(DT) + "\n"
            "run " + std::to_string(static_cast<int>(SETTLE / std::stod(DT))) + "\n" + measure(NRODS));
    return mean(speeds(lmp, NRODS));
  };
  const double tail_first = walk_from(built), nose_first = walk_from(reversed);
  report("rods numbered tail first", tail_first);
  report("rods numbered nose first", nose_first);
  EXPECT_GT(tail_first, 1e-3);
  EXPECT_NEAR(nose_first / tail_first, 1.0, AGREEMENT);
}
