// Many contacts at once: the block Gauss-Seidel solver.
#include "ag_contact_solver.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

using namespace ActiveGrain;
using namespace ActiveGrain::testing;

TEST(ContactSolver, SingleContactGivesExactlyTheLaw)
{
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const RigidBodyState a = random_body(rng), b = random_body(rng);
    const Vec3 c = b.com + random_unit(rng) * 0.5;
    Vec3 n = random_unit(rng);
    if (dot(b.velocity_at(c) - a.velocity_at(c), n) > 0) n = -n;
    const ContactMaterial mat{0.6, 0.7};
    ContactSolver solver;
    const int ia = solver.add_body(a);
    const int ib = solver.add_body(b);
    solver.add_contact(ia, ib, c, n, mat);
    solver.solve(8, 1e-12);
    const Vec3 expected = collision_impulse(a, b, c, n, mat);
    EXPECT_NEAR(norm(solver.impulse(0) - expected), 0.0, 1e-12 * (1 + norm(expected)));
    RigidBodyState b_after = b;
    b_after.apply_impulse(expected, c);
    EXPECT_NEAR(norm(solver.body(1).v - b_after.v), 0.0, 1e-12 * (1 + norm(b_after.v)));
  }
}

namespace {

// A rod (mass m, length L, axis x) falling flat with speed v onto a still plate. The contacts
// sit symmetrically at x = -a ... a. Returns the total impulse and the rod's final state.
Vec3 flat_rod_impact(int ncontacts, double e, double mu, RigidBodyState &rod_after, int sweeps = 200)
{
  const double m = 2.0, L = 4.5;
  RigidBodyState rod;
  rod.inv_mass = 1.0 / m;
  const double I_axis = 0.02, I_trans = m * L * L / 12.0;
  rod.inv_inertia = Mat3::diagonal(Vec3(1 / I_axis, 1 / I_trans, 1 / I_trans));
  rod.com = Vec3(0, 0, 0.5);
  rod.v = Vec3(0, 0, -1.0);    // no slip: friction must not break the symmetry
  ContactSolver solver;
  const int plate = solver.add_body(RigidBodyState::wall(Vec3()));
  const int body = solver.add_body(rod);
  for (int k = 0; k < ncontacts; ++k) {
    const double x = ncontacts == 1 ? 0.0 : -1.8 + 3.6 * k / (ncontacts - 1);
    solver.add_contact(plate, body, Vec3(x, 0, 0), Vec3(0, 0, 1), {e, mu});
  }
  solver.solve(sweeps, 1e-13);
  Vec3 total;
  for (int k = 0; k < ncontacts; ++k) total += solver.impulse(k);
  rod_after = solver.body(body);
  return total;
}

}    // namespace

TEST(ContactSolver, SymmetricContactsGiveTheSameTotalImpulseAsOneCentralContact)
{
  for (double e : {0.1, 0.3, 1.0}) {
    RigidBodyState one, two, five;
    const Vec3 J1 = flat_rod_impact(1, e, 0.03, one);
    const Vec3 J2 = flat_rod_impact(2, e, 0.03, two);
    const Vec3 J5 = flat_rod_impact(5, e, 0.03, five);
    EXPECT_NEAR(J1.z, (1 + e) * 2.0 * 1.0, 1e-12);
    EXPECT_NEAR(norm(J2 - J1), 0.0, 1e-6 * norm(J1)) << "e=" << e;
    // Five contacts on a line are redundant: Gauss-Seidel converges slowly along the null space
    // of the contact set, so 200 sweeps reach 1e-3, not machine precision.
    EXPECT_NEAR(norm(J5 - J1), 0.0, 1e-3 * norm(J1)) << "e=" << e;
    EXPECT_NEAR(norm(five.omega), 0.0, 1e-3);
    EXPECT_NEAR(five.v.z, e * 1.0, 1e-3);
  }
}

TEST(ContactSolver, DefaultSweepsAreCloseForAFlatRod)
{
  // With the default 8 sweeps the rod falling flat on 5 contacts is within a few per cent.
  RigidBodyState one, five;
  const Vec3 J1 = flat_rod_impact(1, 0.1, 0.03, one);
  const Vec3 J5 = flat_rod_impact(5, 0.1, 0.03, five, 8);
  EXPECT_NEAR(J5.z, J1.z, 0.05 * J1.z);
}

TEST(ContactSolver, BeadChainDoesNotGainEnergy)
{
  // Newton's cradle: a bead strikes a row of touching beads (and variants with friction,
  // spin, unequal masses and a wall at the end).
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    ContactSolver solver;
    const int nbeads = 2 + trial % 7;
    const bool wall_at_end = trial % 3 == 0;
    const double r = 0.5;
    for (int k = 0; k < nbeads; ++k) {
      const Vec3 spin = Vec3(U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5) * (trial % 2 ? 4.0 : 0.0);
      const Vec3 v = k == 0 ? Vec3(1.0, 0.3 * (U(rng) - 0.5), 0) : Vec3(0.1 * (U(rng) - 0.5), 0, 0);
      solver.add_body(RigidBodyState::sphere(0.5 + U(rng), r, Vec3(2 * r * k, 0.05 * (U(rng) - 0.5), 0), v, spin));
    }
    const ContactMaterial mat{U(rng), U(rng)};
    for (int k = 0; k + 1 < nbeads; ++k) {
      const Vec3 d = solver.body(k + 1).com - solver.body(k).com;
      const Vec3 n = d / norm(d);
      solver.add_contact(k, k + 1, solver.body(k).com + n * r, n, mat);
    }
    if (wall_at_end) {
      const int wall = solver.add_body(RigidBodyState::wall(Vec3()));
      const Vec3 c = solver.body(nbeads - 1).com + Vec3(r, 0, 0);
      solver.add_contact(nbeads - 1, wall, c, Vec3(1, 0, 0), mat);
    }
    double E0 = 0;
    for (int k = 0; k < nbeads; ++k) E0 += kinetic_energy(solver.body(k));
    solver.solve(trial % 5 == 0 ? 100 : 8, 1e-9);
    double E1 = 0;
    for (int k = 0; k < nbeads; ++k) E1 += kinetic_energy(solver.body(k));
    EXPECT_LE(E1, E0 * (1 + 1e-12)) << "trial " << trial;
  }
}

TEST(ContactSolver, MinimumSeparationPushesOverlappingBodiesApart)
{
  ContactSolver solver;
  const int wall = solver.add_body(RigidBodyState::wall(Vec3()));
  const int bead = solver.add_body(RigidBodyState::sphere(1.0, 0.5, Vec3(0, 0, 0.49), Vec3(), Vec3()));
  solver.add_contact(wall, bead, Vec3(), Vec3(0, 0, 1), {0.3, 0.1}, 0.01);
  solver.solve(8, 1e-12);
  EXPECT_NEAR(solver.body(bead).v.z, 0.01, 1e-15);
}
