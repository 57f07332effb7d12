// Impacts act when their contact closes, not at the start of the step that finds it: a bead or a
// rod dropped on a still plate under gravity rebounds to the same height at large time steps as
// at small ones. (Applied at the step's start, the impulse reversed a grain up to one step's
// flight short of the plate, and gravity acted on the approach for half a step too little: the
// apex came out up to 7% off at dt = 5e-5 s.) This file also runs under mpirun -np 2 and -np 4,
// with the rod on the corner of the sub-domains.
#include "lammps_fixture.h"
#include "rod_deck.h"

#include <cmath>
#include <string>

using namespace rod_deck;

class ImpactTiming : public LammpsTest {
 protected:
  // Highest centre-of-mass height of `group` after its first rebound, sampled every `every` steps
  // (at the apex the speed is zero: the sampling error is second order).
  double rebound_apex(double dt, double duration, int every = 1, const std::string &group = "all")
  {
    command(fmt::format("timestep {}\nvariable zcm equal xcm({},z)\nvariable vz equal vcm({},z)", dt,
                        group, group));
    bool rising = false;
    double apex = -1.0;
    const int chunks = static_cast<int>(duration / (dt * every));
    for (int k = 0; k < chunks; ++k) {
      command(fmt::format("run {} post no", every));
      const double vz = value("v_vz");
      if (vz > 0.0) rising = true;
      if (rising) apex = std::max(apex, value("v_zcm"));
      if (rising && vz < 0.0) break;
    }
    return apex;
  }
};

// A 1 mm bead dropped from h (bottom above the plate): its first apex is e^2 h, for drop heights
// that put the impact at different points within a step.
TEST_F(ImpactTiming, BeadReboundsToRestitutionSquaredAtLargeTimeSteps)
{
  const double e = 0.3;
  for (double dt : {5e-5, 1e-4})
    for (double h : {1.00e-4, 1.07e-4, 1.13e-4}) {
      LammpsTest::TearDown();
      LammpsTest::SetUp();
      command(fmt::format(
          "units si\natom_style sphere\nboundary p p f\ncomm_modify vel yes\n"
          "region box block 0 0.004 0 0.004 -1e-4 3e-3 units box\ncreate_box 1 box\n"
          "create_atoms 1 single 0.002 0.002 {} units box\n"
          "set type 1 diameter 1e-3\nset type 1 density 2700\n"
          "pair_style gran/impulse\npair_coeff * * {} 0.05\n"
          "fix plate all wall/impulse zlo 0.0 e {} mu 0.01\n"
          "fix gravity all gravity 9.81 vector 0 0 -1\nfix integrate all nve/sphere",
          5e-4 + h, e, e));
      const double apex = rebound_apex(dt, 0.02) - 5e-4;
      EXPECT_NEAR(std::sqrt(apex / h), e, 2e-3 * e) << "dt " << dt << ", h " << h;
    }
}

// The same on a bead held by fix freeze (a body of infinite mass that gravity does not move):
// only the falling bead gains velocity before the contact closes.
TEST_F(ImpactTiming, BeadReboundsFromAFrozenBeadToRestitutionSquared)
{
  const double e = 0.3, h = 1.07e-4;
  command(fmt::format(
      "units si\natom_style sphere\nboundary p p f\ncomm_modify vel yes\n"
      "region box block 0 0.004 0 0.004 -1e-4 4e-3 units box\ncreate_box 1 box\n"
      "create_atoms 1 single 0.002 0.002 5e-4 units box\n"
      "create_atoms 1 single 0.002 0.002 {} units box\n"
      "set type 1 diameter 1e-3\nset type 1 density 2700\n"
      "group base id 1\ngroup falling id 2\n"
      "pair_style gran/impulse\npair_coeff * * {} 0.05\n"
      "fix gravity all gravity 9.81 vector 0 0 -1\nfix hold base freeze\nfix integrate all nve/sphere",
      1.5e-3 + h, e));
  const double apex = rebound_apex(5e-5, 0.02, 1, "falling") - 1.5e-3;
  EXPECT_NEAR(std::sqrt(apex / h), e, 2e-3 * e);
}

// A rod of equal end diameters dropped flat: all its spheres meet the plate at once (one compliant
// impact through fix rigid/rod's body), and it rebounds without turning, to e^2 h.
TEST_F(ImpactTiming, FlatRodReboundsToRestitutionSquaredAtLargeTimeSteps)
{
  const double e = 0.5, d = 0.9e-3;
  for (double h : {1.00e-4, 1.07e-4, 1.13e-4}) {
    LammpsTest::TearDown();
    LammpsTest::SetUp();
    command("units si\natom_style sphere\natom_modify map array\nboundary p p f\n"
            "fix molecule_ids all property/atom mol ghost yes\n"
            "region box block -6e-3 6e-3 -6e-3 6e-3 -1e-3 3e-3\ncreate_box 3 box\n"
            "comm_modify vel yes cutoff 6e-3\nneighbor 5e-4 bin\n" +
            rod_template("test_impact_timing.mol", d, d) + flat_rod(h, 30.0, d, d) +
            fmt::format("pair_style gran/impulse\npair_coeff * * 0.3 0.05\n"
                        "fix rods all rigid/rod molecule mol rod\n"
                        "fix plate all wall/impulse zlo 0.0 e {} mu 0.2\n"
                        "fix gravity all gravity 9.81 vector 0 0 -1", e));
    const double lying = value("xcm(all,z)") - h;
    const double apex = rebound_apex(5e-5, 0.02) - lying;
    EXPECT_NEAR(std::sqrt(apex / h), e, 2e-3 * e) << "h " << h;
    EXPECT_LT(std::fabs(value("omega(all,y)")) + std::fabs(value("omega(all,x)")), 1e-9);
  }
}
