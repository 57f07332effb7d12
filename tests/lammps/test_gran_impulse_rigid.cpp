// Rigid bodies in pair gran/impulse: the atoms a RigidBodyProvider claims for one body form ONE
// body of the contact solve, with the body's mass, centre of mass and inertia. Tested with a
// test-only provider (fix test/rigid: the fix group is one body of given mass, inertia and
// motion) and no integrator: one step's contact forces are checked against the core's law.
#include "lammps_fixture.h"

#include "ag_impulse.h"
#include "atom.h"
#include "fix.h"
#include "modify.h"
#include "rigid_body_provider.h"
#include "update.h"

#include <cmath>

using ActiveGrain::Mat3;
using ActiveGrain::RigidBodyState;
using ActiveGrain::Vec3;

namespace {

// fix ID group test/rigid M Ixx Iyy Izz vx vy vz wx wy wz
class FixTestRigid : public LAMMPS_NS::Fix, public LAMMPS_NS::RigidBodyProvider {
 public:
  FixTestRigid(LAMMPS_NS::LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
  {
    double a[10];
    for (int k = 0; k < 10; ++k) a[k] = std::stod(arg[3 + k]);
    body.inv_mass = 1.0 / a[0];
    body.inv_inertia = Mat3::diagonal(Vec3(1 / a[1], 1 / a[2], 1 / a[3]));
    body.v = Vec3(a[4], a[5], a[6]);
    body.omega = Vec3(a[7], a[8], a[9]);
  }
  int setmask() override { return 0; }
  void init() override
  {
    // Centre of mass: the mean of the (equal-mass) constituents.
    Vec3 sum;
    int n = 0;
    for (int i = 0; i < atom->nlocal; ++i)
      if (atom->mask[i] & groupbit) { sum += Vec3(atom->x[i]); ++n; }
    body.com = sum / n;
  }
  bool body_of_atom(int i, RigidBodyState &state, LAMMPS_NS::tagint &id) const override
  {
    if (!(atom->mask[i] & groupbit)) return false;
    state = body;
    id = 1;
    return true;
  }
  // No integrator moves this body: late impulses are claimed and not applied.
  bool add_late_impulse(int i, const Vec3 &, const Vec3 &) override { return atom->mask[i] & groupbit; }
  RigidBodyState body;
};

}    // namespace

class GranImpulseRigid : public LammpsTest {
 protected:
  void SetUp() override
  {
    LammpsTest::SetUp();
    (*lmp->modify->fix_map)["test/rigid"] = [](LAMMPS_NS::LAMMPS *l, int n, char **a) -> LAMMPS_NS::Fix * {
      return new FixTestRigid(l, n, a);
    };
    command("units si\natom_style sphere\natom_modify map array\nboundary p p f\n"
            "region box block 0 0.01 0 0.01 0 0.004\ncreate_box 1 box\ncomm_modify vel yes\n"
            "neighbor 0.0002 bin\ntimestep 1e-5\n"
            "pair_style gran/impulse\npair_coeff * * 0.3 0.05");
  }
  // A rod of 5 overlapping spheres (d = 1 mm, 0.9 mm apart) along x centred at (x, 5 mm, z),
  // tilted by angle about y.
  void rod(double x, double z, double tilt)
  {
    for (int k = -2; k <= 2; ++k)
      command(fmt::format("create_atoms 1 single {} 0.005 {} units box", x + 0.0009 * k * std::cos(tilt),
                          z - 0.0009 * k * std::sin(tilt)));
    command("set atom * diameter 0.001\nset atom * density 2700\ngroup rod type 1");
  }
  Vec3 total(double **a)
  {
    Vec3 s;
    for (int i = 0; i < lmp->atom->nlocal; ++i) s += Vec3(a[i]);
    return s;
  }
  // Total torque about c of forces and per-atom torques.
  Vec3 total_torque(const Vec3 &c)
  {
    Vec3 s;
    for (int i = 0; i < lmp->atom->nlocal; ++i)
      s += cross(Vec3(lmp->atom->x[i]) - c, Vec3(lmp->atom->f[i])) + Vec3(lmp->atom->torque[i]);
    return s;
  }
};

TEST_F(GranImpulseRigid, RodFallingFlatGetsTheImpulseOfOneBodyNotFive)
{
  const double M = 2.5e-5, I = 4e-11;    // rod-like mass and transverse inertia
  rod(0.005, 0.0005, 0.0);
  // The five contacts are one compliant impact: symmetric, and as one contact under the centre
  // (within the impact's resolution, about 3/150 on the impulse at worst).
  command(fmt::format("fix body rod test/rigid {} 1e-12 {} {} 0 0 -0.1 0 0 0", M, I, I));
  command("fix plates all wall/impulse zlo 0.0 e 0.3 mu 0.03\nrun 1");
  const double dt = 1e-5;
  const Vec3 F = total(lmp->atom->f);
  EXPECT_NEAR(F.z * dt, 1.3 * M * 0.1, 1e-3 * 1.3 * M * 0.1) << "one body of mass M, five contacts";
  EXPECT_NEAR(F.x, 0.0, 1e-9 * std::fabs(F.z));
  const Vec3 com(0.005, 0.005, 0.0005);
  EXPECT_NEAR(norm(total_torque(com)) * dt, 0.0, 1e-3 * 1.3 * M * 0.1 * 0.0018);
}

TEST_F(GranImpulseRigid, TiltedRodHittingWithOneEndGetsTheLawWithItsInertia)
{
  const double M = 2.5e-5, I = 4e-11, tilt = 0.08;
  rod(0.005, 0.0005 + 0.0018 * std::sin(tilt), tilt);    // the k = 2 sphere just touches
  command(fmt::format("fix body rod test/rigid {} 1e-12 {} {} 0.02 0 -0.1 0 3 0", M, I, I));
  command("fix plates all wall/impulse zlo 0.0 e 0.3 mu 0.03\nrun 1");
  auto *fix = dynamic_cast<FixTestRigid *>(lmp->modify->get_fix_by_id("body"));
  ASSERT_TRUE(fix);
  // The lowest sphere touches the plate at the point below its centre.
  const Vec3 lowest(0.005 + 0.0018 * std::cos(tilt), 0.005, 0.0005);
  const Vec3 c = lowest - Vec3(0, 0, 0.0005);
  const Vec3 J = ActiveGrain::collision_impulse(RigidBodyState::wall(Vec3()), fix->body, c, Vec3(0, 0, 1),
                                                {0.3, 0.03});
  const double dt = 1e-5;
  const Vec3 F = total(lmp->atom->f);
  ASSERT_GT(J.z, 0.0);
  EXPECT_NEAR(norm(F * dt - J), 0.0, 1e-9 * norm(J));
  EXPECT_NEAR(norm(total_torque(fix->body.com) * dt - cross(c - fix->body.com, J)), 0.0,
              1e-9 * norm(J) * 0.002);
}

TEST_F(GranImpulseRigid, OverlappingConstituentsOfOneBodyDoNotCollide)
{
  rod(0.005, 0.002, 0.0);
  command("fix body rod test/rigid 2.5e-5 1e-12 4e-11 4e-11 0.1 0 0 0 0 5\nrun 1");
  for (int i = 0; i < lmp->atom->nlocal; ++i) EXPECT_EQ(norm(Vec3(lmp->atom->f[i])), 0.0);
}
