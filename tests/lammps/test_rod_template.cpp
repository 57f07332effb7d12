// rod_template: the molecule it defines carries the solid rod's mass, COM and inertia, tail
// first and nose last; bad input gives a clear ERROR. Also fix rigid/rod's input checks.
#include "lammps_fixture.h"
#include "rod_deck.h"

#include "ag_projected_area.h"
#include "ag_rod_geometry.h"
#include "atom.h"
#include "molecule.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <set>

using namespace rod_deck;

namespace {
ActiveGrain::RodGeometry analytic(double tail = TAIL, double nose = NOSE)
{
  return ActiveGrain::rod_solid({LENGTH, tail, nose, SPHERES, DENSITY});
}
}    // namespace

class RodTemplateTest : public LammpsTest {
 protected:
  const std::string file = "test_rod_template.mol";
  LAMMPS_NS::Molecule *molecule()
  {
    int imol = lmp->atom->find_molecule("rod");
    return imol < 0 ? nullptr : lmp->atom->molecules[imol];
  }
};

TEST_F(RodTemplateTest, MoleculeCarriesSolidMassComInertia)
{
  command(box() + rod_template(file));
  auto *mol = molecule();
  ASSERT_NE(mol, nullptr);
  const auto g = analytic();
  ASSERT_EQ(mol->natoms, SPHERES);
  mol->compute_mass();
  mol->compute_com();
  mol->compute_inertia();
  EXPECT_NEAR(mol->masstotal / g.mass, 1.0, 1e-3);
  // Rod along +x with its COM at the origin: the tail face sits at -com.
  EXPECT_NEAR(mol->com[0], 0.0, 1e-3 * LENGTH);
  const double tail_face = mol->x[0][0] - mol->radius[0];
  EXPECT_NEAR(-tail_face / g.com, 1.0, 1e-3);
  EXPECT_NEAR(mol->itensor[0] / g.inertia_axial, 1.0, 1e-3);
  EXPECT_NEAR(mol->itensor[1] / g.inertia_transverse, 1.0, 1e-3);
  EXPECT_NEAR(mol->itensor[2] / g.inertia_transverse, 1.0, 1e-3);
  // The per-sphere masses alone reproduce the solid's mass and COM.
  double m = 0, m1 = 0;
  for (int i = 0; i < mol->natoms; ++i) {
    m += mol->rmass[i];
    m1 += mol->rmass[i] * mol->x[i][0];
  }
  EXPECT_NEAR(m / g.mass, 1.0, 1e-12);
  EXPECT_NEAR(m1 / m, 0.0, 1e-12 * LENGTH);
  // Tail first (widest, type 1), nose last (narrowest, type 3).
  EXPECT_EQ(mol->type[0], 1);
  EXPECT_EQ(mol->type[SPHERES - 1], 3);
  for (int i = 1; i < SPHERES; ++i) EXPECT_LT(mol->radius[i], mol->radius[i - 1]);
  for (int i = 1; i < SPHERES - 1; ++i) EXPECT_EQ(mol->type[i], 2);
}

TEST_F(RodTemplateTest, ProjectedAreaVariableIsTheUnionOfTheDiscs)
{
  command(box() + rod_template(file));
  auto *mol = molecule();
  ASSERT_NE(mol, nullptr);
  std::vector<double> centres, radii;
  for (int i = 0; i < mol->natoms; ++i) {
    centres.push_back(mol->x[i][0]);
    radii.push_back(mol->radius[i]);
  }
  const auto shares = ActiveGrain::disc_chain_area_shares(centres, radii);
  const double area = std::accumulate(shares.begin(), shares.end(), 0.0);
  EXPECT_NEAR(value("v_rod_area") / area, 1.0, 1e-12);
  // Rounded ends and scallops: a little less than the frustum's trapezoid.
  EXPECT_LT(area, LENGTH * (TAIL + NOSE) / 2);
  EXPECT_GT(area, 0.85 * LENGTH * (TAIL + NOSE) / 2);
}

TEST_F(RodTemplateTest, BadDimensionsAreErrors)
{
  command(box());
  const std::string rest = " spheres 9 density 8500 file " + file;
  EXPECT_NE(error_of("rod_template rod length 0 tail 1.1e-3 nose 0.7e-3" + rest).find("Rod_template: length must be > 0"),
            std::string::npos);
  EXPECT_NE(error_of("rod_template rod length 4.5e-3 tail -1.1e-3 nose 0.7e-3" + rest).find("Rod_template: tail diameter"),
            std::string::npos);
  EXPECT_NE(error_of("rod_template rod length 4.5e-3 tail 1.1e-3 nose 0 " + rest).find("Rod_template: nose diameter"),
            std::string::npos);
  EXPECT_NE(error_of("rod_template rod length 4.5e-3 tail 1.1e-3 nose 0.7e-3 spheres 9 density -1 file " + file)
                .find("Rod_template: density"),
            std::string::npos);
  EXPECT_NE(error_of("rod_template rod length 4.5e-3 tail 1.1e-3 nose 0.7e-3 spheres 3 density 8500 file " + file)
                .find("Rod_template: neighbouring spheres do not intersect"),
            std::string::npos);
  EXPECT_NE(error_of("rod_template rod length 4.5e-3 tail 1.1e-3 spheres 9 density 8500").find("keyword nose is required"),
            std::string::npos);
  EXPECT_NE(error_of("rod_template rod length 4.5e-3 tail 1.1e-3 nose 0.7e-3" + rest + " colour red").find("unknown keyword colour"),
            std::string::npos);
  EXPECT_NE(error_of("rod_template rod length 4.5e-3 tail 1.1e-3 nose 0.7e-3" + rest + " types 1 2 1").find("types"),
            std::string::npos);
  EXPECT_NE(error_of("rod_template rod length 4.5e-3 tail 1.1e-3 nose 0.7e-3" + rest + " types 1 2 4").find("atom type 4"),
            std::string::npos);
}

TEST_F(RodTemplateTest, TaperCheckRejectsWideNose)
{
  command(box());
  const std::string reversed = "rod_template rod length 4.5e-3 tail 0.7e-3 nose 1.1e-3 spheres 9 density 8500 file " + file;
  EXPECT_NE(error_of(reversed + " taper_check yes").find("Rod_template: taper_check: nose diameter"), std::string::npos);
  // Without the check a reversed rod is legal (used to test that motion follows the geometry).
  EXPECT_EQ(error_of(reversed), "");
}

TEST_F(RodTemplateTest, FixNeedsRodTemplate)
{
  command(box() + rod_template(file) + "create_atoms 0 single 0 0 0 mol rod 1 units box");
  EXPECT_NE(error_of("fix r all rigid/rod molecule").find("Fix rigid/rod: requires the mol keyword"), std::string::npos);
}

TEST_F(RodTemplateTest, FixRejectsShortGhostCutoff)
{
  command(box() + rod_template(file) +
          "create_atoms 0 single 0 0 0 mol rod 1 units box\n"
          "fix r all rigid/rod molecule mol rod\n"
          "pair_style gran/impulse\npair_coeff * * 0.3 0.05\n"
          "comm_modify vel yes cutoff 1e-3\n"
          "compute t all temp/sphere\nthermo_modify temp t");
  EXPECT_NE(error_of("run 0").find("Fix rigid/rod: rod extent"), std::string::npos);
}

TEST_F(RodTemplateTest, FixRejectsOtherPairStyles)
{
  command(box() + rod_template(file) +
          "create_atoms 0 single 0 0 0 mol rod 1 units box\n"
          "fix r all rigid/rod molecule mol rod\n"
          "comm_modify cutoff 6e-3\n"
          "pair_style zero 1e-3\npair_coeff * *\n"
          "compute t all temp/sphere\nthermo_modify temp t");
  EXPECT_NE(error_of("run 0").find("Fix rigid/rod: rods need pair_style gran/impulse (found pair_style zero)"),
            std::string::npos);
}

TEST_F(RodTemplateTest, FixRejectsMissingPairStyle)
{
  command(box() + rod_template(file) +
          "create_atoms 0 single 0 0 0 mol rod 1 units box\n"
          "fix r all rigid/rod molecule mol rod\n"
          "comm_modify cutoff 6e-3\n"
          "compute t all temp/sphere\nthermo_modify temp t");
  EXPECT_NE(error_of("run 0").find("Fix rigid/rod: rods need pair_style gran/impulse (found pair_style none)"),
            std::string::npos);
}

TEST_F(RodTemplateTest, WithoutFileKeywordNoFileIsLeftAnywhere)
{
  // Two jobs in one directory must not share a template file: without keyword file the template
  // goes through a private temporary file, removed once read; nothing appears in the working
  // directory or stays in the temporary directory.
  namespace fs = std::filesystem;
  auto listing = [](const fs::path &dir, const std::string &prefix) {
    std::set<std::string> names;
    for (const auto &entry : fs::directory_iterator(dir)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind(prefix, 0) == 0) names.insert(name);
    }
    return names;
  };
  const auto here = listing(fs::current_path(), "");
  command(box() + "rod_template agtmpcheck length 4.5e-3 tail 1.1e-3 nose 0.7e-3 spheres 9 density 8500");
  EXPECT_EQ(listing(fs::current_path(), ""), here);
  EXPECT_TRUE(listing(fs::temp_directory_path(), "rod_template-agtmpcheck-").empty());
  const int imol = lmp->atom->find_molecule("agtmpcheck");
  ASSERT_GE(imol, 0);
  auto *mol = lmp->atom->molecules[imol];
  EXPECT_EQ(mol->natoms, SPHERES);
  mol->compute_mass();
  EXPECT_NEAR(mol->masstotal / analytic().mass, 1.0, 1e-3);

  // With keyword file, the file is written there and kept.
  command("rod_template shown length 4.5e-3 tail 1.1e-3 nose 0.7e-3 spheres 9 density 8500 file shown.mol");
  std::ifstream shown("shown.mol");
  ASSERT_TRUE(shown.good());
  std::string first;
  std::getline(shown, first);
  EXPECT_NE(first.find("rod_template shown"), std::string::npos);
}
