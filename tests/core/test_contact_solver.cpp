// Many contacts at once: the block Gauss-Seidel solver.
#include "ag_contact_solver.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

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

TEST(ContactSolver, ToleranceOnBodyVelocitiesIsReachedForAFlatRod)
{
  // The residual is on the rod's velocity, which converges although the five redundant
  // impulses do not settle: at the default tolerance the rod leaves as from one contact.
  for (double e : {0.1, 0.3}) {
    RigidBodyState one, five;
    flat_rod_impact(1, e, 0.03, one);
    flat_rod_impact(5, e, 0.03, five, 200);
    EXPECT_NEAR(five.v.z, one.v.z, 1e-5);
    EXPECT_NEAR(norm(five.omega), 0.0, 1e-5);
  }
}

namespace {

// A tapered rod (axis in the plate plane, slightly tilted) lying on a vibrating plate with
// several of its spheres, sliding and spinning, touched by beads from the side and one from
// above: contacts that share bodies, with slip that changes direction during the solve.
struct Cluster {
  std::vector<RigidBodyState> bodies;
  struct Touch { int body1, body2; Vec3 point, n; ContactMaterial material; double min_separation; };
  std::vector<Touch> touches;
};

Cluster random_cluster(std::mt19937 &rng, bool frictionless = false)
{
  std::uniform_real_distribution<double> U(-1.0, 1.0), P(0.0, 1.0);
  Cluster cl;
  cl.bodies.push_back(RigidBodyState::wall(Vec3(0.0, 0.0, 0.5 * U(rng))));    // the plate
  RigidBodyState rod;
  rod.inv_mass = 1.0 / 24.7;
  const double tilt = 0.05 * U(rng), heading = 3.0 * U(rng);
  const Vec3 axis(std::cos(tilt) * std::cos(heading), std::cos(tilt) * std::sin(heading), std::sin(tilt));
  const Vec3 across = cross(Vec3(0, 0, 1), axis) / norm(cross(Vec3(0, 0, 1), axis));
  const Mat3 R = Mat3::from_columns(axis, across, cross(axis, across));
  rod.inv_inertia = R * Mat3::diagonal(Vec3(1.0 / 2.5, 1.0 / 40.0, 1.0 / 40.0)) * R.transpose();
  rod.com = Vec3(0, 0, 0.5);
  rod.v = Vec3(0.3 * U(rng), 0.3 * U(rng), -0.3 - 0.5 * P(rng));
  rod.omega = Vec3(0.5 * U(rng), 0.5 * U(rng), 0.5 * U(rng));
  cl.bodies.push_back(rod);
  const ContactMaterial plate{0.1 + 0.5 * P(rng), 0.03};    // the paper's rod-plate friction
  const int spheres = 2 + static_cast<int>(4 * P(rng));
  for (int k = 0; k < spheres; ++k) {
    const double s = -1.8 + 3.6 * k / (spheres - 1);
    const Vec3 point = rod.com + axis * s - Vec3(0, 0, 0.45);
    cl.touches.push_back({0, 1, point, Vec3(0, 0, 1), plate, k == 0 ? 0.01 : 0.0});
  }
  const int beads = static_cast<int>(3 * P(rng));
  for (int k = 0; k < beads; ++k) {
    const Vec3 side = across * (k % 2 ? 1.0 : -1.0);
    const Vec3 point = rod.com + axis * (1.5 * U(rng)) + side * 0.45;
    cl.bodies.push_back(RigidBodyState::sphere(1.4, 0.5, point + side * 0.5,
                                               -side * (0.5 + P(rng)) + Vec3(0.2 * U(rng), 0.2 * U(rng), 0),
                                               Vec3(U(rng), U(rng), U(rng))));
    const int bead = static_cast<int>(cl.bodies.size()) - 1;
    cl.touches.push_back({1, bead, point, side, {0.3, 0.05}, 0.0});
    cl.touches.push_back({0, bead, point + side * 0.5 - Vec3(0, 0, 0.5), Vec3(0, 0, 1), {0.3, 0.01}, 0.0});
  }
  if (frictionless)
    for (auto &t : cl.touches) t.material.mu = 0.0;
  return cl;
}

double total_energy(const ContactSolver &solver, const Vec3 &frame)
{
  double E = 0;
  for (int b = 0; b < solver.num_bodies(); ++b) {
    RigidBodyState moving = solver.body(b);
    moving.v -= frame;
    E += kinetic_energy(moving);
  }
  return E;
}

// Solve the cluster with its contacts in the given order.
ContactSolver solve_in_order(const Cluster &cl, const std::vector<int> &order, int sweeps, double tolerance,
                             ContactSolver::Result *result = nullptr)
{
  ContactSolver solver;
  for (const RigidBodyState &b : cl.bodies) solver.add_body(b);
  for (int k : order) {
    const Cluster::Touch &t = cl.touches[k];
    solver.add_contact(t.body1, t.body2, t.point, t.n, t.material, t.min_separation);
  }
  const ContactSolver::Result r = solver.solve(sweeps, tolerance);
  if (result) *result = r;
  return solver;
}

double velocity_difference(const ContactSolver &a, const ContactSolver &b)
{
  double largest = 0;
  for (int k = 0; k < a.num_bodies(); ++k)
    largest = std::max(largest, norm(a.body(k).v - b.body(k).v) + 2.0 * norm(a.body(k).omega - b.body(k).omega));
  return largest;
}

// Forward, reversed and shuffled orders, and a tighter tolerance, on random clusters.
struct OrderDependence {
  int clusters = 0, converged = 0;
  int agreeing = 0, close = 0;                      // converged, differences < 1e-6 (< 1e-2)
  double largest = 0.0;                             // largest difference where all converged
  double mean_sweeps = 0.0;
};

OrderDependence order_dependence(bool frictionless, unsigned seed)
{
  std::mt19937 rng(seed);
  OrderDependence out;
  long sweeps = 0;
  for (out.clusters = 0; out.clusters < 300; ++out.clusters) {
    const Cluster cl = random_cluster(rng, frictionless);
    std::vector<int> forward(cl.touches.size());
    std::iota(forward.begin(), forward.end(), 0);
    std::vector<int> reversed(forward.rbegin(), forward.rend()), shuffled = forward;
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    ContactSolver::Result ra, rb, rc, rd;
    const ContactSolver a = solve_in_order(cl, forward, 20000, 1e-10, &ra);
    const ContactSolver b = solve_in_order(cl, reversed, 20000, 1e-10, &rb);
    const ContactSolver c = solve_in_order(cl, shuffled, 20000, 1e-10, &rc);
    const ContactSolver d = solve_in_order(cl, forward, 20000, 1e-13, &rd);
    sweeps += ra.sweeps;
    if (!(ra.converged && rb.converged && rc.converged && rd.converged)) continue;
    out.converged++;
    const double difference =
        std::max({velocity_difference(a, b), velocity_difference(a, c), velocity_difference(a, d)});
    out.largest = std::max(out.largest, difference);
    if (difference < 1e-6) out.agreeing++;
    if (difference < 1e-2) out.close++;
  }
  out.mean_sweeps = double(sweeps) / out.clusters;
  return out;
}

}    // namespace

TEST(ContactSolver, FrictionlessBodyVelocitiesDoNotDependOnContactOrderOrSweeps)
{
  // Without friction the post-solve body velocities are unique (an LCP with a positive
  // semi-definite matrix) although the sphere impulses of a rod lying on a plate are not.
  const OrderDependence r = order_dependence(true, 7);
  std::printf("[ measured ] frictionless: largest velocity difference %.2g, mean sweeps to 1e-10 %.0f\n",
              r.largest, r.mean_sweeps);
  EXPECT_EQ(r.converged, r.clusters);
  EXPECT_LT(r.largest, 1e-7);
}

TEST(ContactSolver, FrictionalBodyVelocitiesAgreeWhereTheSolveConverges)
{
  // With Coulomb friction and redundant contacts uniqueness is not guaranteed (SPEC 4b): how
  // sliding contacts share the normal impulse can change the friction torque, and a few of
  // these harsh clusters (spinning rods, beads rolling on them) do not converge. Measured:
  // the shares below.
  const OrderDependence r = order_dependence(false, 7);
  std::printf("[ measured ] friction: %d of %d clusters converged; in every order %d of them agree to 1e-6, "
              "%d to 1e-2 (largest difference %.2g); mean sweeps to 1e-10 %.0f\n",
              r.converged, r.clusters, r.agreeing, r.close, r.largest, r.mean_sweeps);
  EXPECT_GE(r.converged, 0.95 * r.clusters);
  EXPECT_GE(r.agreeing, 0.5 * r.converged);
}

TEST(ContactSolver, ConvergedContactsMeetTheirConditions)
{
  // Every contact leaves at its target or later with no impulse, inside the friction cone,
  // sticking or sliding against its final slip (where the slip direction's root search finds it).
  std::mt19937 rng(8);
  int sliding = 0, against_final_slip = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Cluster cl = random_cluster(rng);
    std::vector<int> forward(cl.touches.size());
    std::iota(forward.begin(), forward.end(), 0);
    ContactSolver::Result result;
    const ContactSolver s = solve_in_order(cl, forward, 20000, 1e-12, &result);
    if (!result.converged) continue;
    for (int k = 0; k < s.num_contacts(); ++k) {
      const ContactSolver::Contact &c = s.contact(k);
      const Vec3 u = s.body(c.body2).velocity_at_arm(c.r2) - s.body(c.body1).velocity_at_arm(c.r1);
      const double un = dot(u, c.n), jn = dot(c.impulse, c.n);
      const Vec3 ut = u - c.n * un, jt = c.impulse - c.n * jn;
      const double scale = 1e-6 * (1 + c.target_separation);
      EXPECT_GE(un, c.target_separation - scale) << "trial " << trial;
      EXPECT_GE(jn, 0.0);
      if (jn > 1e-9) {
        EXPECT_NEAR(un, c.target_separation, scale) << "trial " << trial;
        EXPECT_LE(norm(jt), c.material.mu * jn * (1 + 1e-9));
        if (!c.isolated && norm(ut) > scale) {
          ++sliding;
          EXPECT_NEAR(norm(jt), c.material.mu * jn, 1e-6 * jn) << "trial " << trial;
          if (dot(jt, ut) < 0.0 && norm(cross(jt, ut)) <= 1e-5 * norm(jt) * norm(ut)) ++against_final_slip;
        }
      }
    }
  }
  std::printf("[ measured ] %d of %d sliding coupled contacts slide exactly against their final slip\n",
              against_final_slip, sliding);
  EXPECT_GT(sliding, 100);
  EXPECT_GE(against_final_slip, 0.95 * sliding);
}

TEST(ContactSolver, CoupledContactsDoNotGainEnergy)
{
  // Without overlap corrections, a converged solve never adds kinetic energy (in the frame of
  // the moving plate, where it does no work).
  std::mt19937 rng(9);
  for (int trial = 0; trial < 300; ++trial) {
    Cluster cl = random_cluster(rng);
    for (auto &t : cl.touches) t.min_separation = 0.0;
    std::vector<int> forward(cl.touches.size());
    std::iota(forward.begin(), forward.end(), 0);
    ContactSolver before;
    for (const RigidBodyState &b : cl.bodies) before.add_body(b);
    const Vec3 plate = cl.bodies[0].v;
    const ContactSolver after = solve_in_order(cl, forward, 100000, 1e-12);
    EXPECT_LE(total_energy(after, plate), total_energy(before, plate) * (1 + 1e-9)) << "trial " << trial;
  }
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
