// The energy ledger of a solve: dissipation, the overlap correction's work, a wall's work.
#include "ag_contact_energy.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

using namespace ActiveGrain;

namespace {

const Vec3 UP(0, 0, 1);

// A bead of mass m (radius r) above a wall moving at wall_velocity, approaching it at speed a.
struct BeadOnWall {
  ContactSolver solver;
  Vec3 before;
  double approach;
  Vec3 wall_velocity;
  double kinetic_before;

  BeadOnWall(double m, double a, const Vec3 &wall_v, ContactModel model, double min_separation = 0.0,
             const Vec3 &spin = Vec3())
  {
    const double r = 1e-3;
    wall_velocity = wall_v;
    const int wall = solver.add_body(RigidBodyState::wall(wall_v));
    const int bead = solver.add_body(RigidBodyState::sphere(m, r, Vec3(0, 0, r), wall_v + Vec3(0.3 * a, 0, -a), spin));
    solver.add_contact(wall, bead, Vec3(), UP, model, min_separation);
    const ContactSolver::Contact &c = solver.contact(0);
    before = solver.body(bead).velocity_at_arm(c.r2) - solver.body(wall).velocity_at_arm(c.r1);
    approach = -dot(before, UP);
    kinetic_before = ActiveGrain::testing::kinetic_energy(solver.body(bead));
    solver.solve();
  }
  double kinetic_after() const { return ActiveGrain::testing::kinetic_energy(solver.body(1)); }
};

}    // namespace

TEST(ContactEnergy, AFrictionlessImpactLosesOneMinusESquaredOfItsApproachEnergy)
{
  const double m = 2e-4, a = 0.3;
  for (double e : {0.0, 0.3, 0.9, 1.0}) {
    BeadOnWall s(m, a, Vec3(), {e, 0.0});
    const ContactEnergy energy = contact_energy(s.solver, 0, s.before, s.approach);
    EXPECT_NEAR(energy.dissipated, (1.0 - e * e) * 0.5 * m * a * a, 1e-12 * m * a * a) << "e " << e;
    EXPECT_EQ(energy.overlap_work, 0.0);
  }
}

TEST(ContactEnergy, TheLedgerBalancesTheKineticEnergyWithFrictionAndAMovingWall)
{
  // Kinetic energy after = before + wall work + overlap work - dissipated, for a sliding,
  // spinning bead hitting a moving plate.
  const double m = 2e-4, a = 0.2;
  for (double mu : {0.0, 0.2, 0.8}) {
    BeadOnWall s(m, a, Vec3(0.01, 0.0, 0.05), {0.6, mu}, 0.0, Vec3(0, 40.0, 0));
    const ContactEnergy energy = contact_energy(s.solver, 0, s.before, s.approach, s.wall_velocity);
    const double change = s.kinetic_after() - s.kinetic_before;
    EXPECT_NEAR(change, energy.wall_work + energy.overlap_work - energy.dissipated, 1e-12 * m * a * a)
        << "mu " << mu;
    EXPECT_GE(energy.dissipated, -1e-15);
  }
}

TEST(ContactEnergy, AnOverlapPushedOutFasterThanRestitutionIsCreditedToTheCorrection)
{
  // A resting overlap (no approach) must leave at s: the push gives it 1/2 m s^2, all of it from
  // the correction, none dissipated.
  const double m = 2e-4, s_min = 0.01;
  BeadOnWall s(m, 0.0, Vec3(), {0.5, 0.0}, s_min);
  const ContactEnergy energy = contact_energy(s.solver, 0, s.before, s.approach);
  EXPECT_NEAR(energy.overlap_work, 0.5 * m * s_min * s_min, 1e-12 * m * s_min * s_min);
  EXPECT_NEAR(energy.dissipated, 0.0, 1e-12 * m * s_min * s_min);
  EXPECT_EQ(energy.wall_work, 0.0);
}
