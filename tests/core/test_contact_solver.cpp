// Many contacts at once: isolated contacts by Stronge's law, islands by a compliant impact.
#include "ag_contact_energy.h"
#include "ag_contact_solver.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

using namespace ActiveGrain;
using namespace ActiveGrain::testing;

TEST(ContactSolver, SingleContactGivesExactlyTheLaw)
{
  // With a resting speed too: an isolated contact is never resting (ag_resting_solve.h).
  ContactSolver::Settings resting;
  resting.resting_speed = 1e3;
  std::mt19937 rng(11);
  for (int trial = 0; trial < 400; ++trial) {
    const RigidBodyState a = random_body(rng), b = random_body(rng);
    const Vec3 c = b.com + random_unit(rng) * 0.5;
    Vec3 n = random_unit(rng);
    if (dot(b.velocity_at(c) - a.velocity_at(c), n) > 0) n = -n;
    const ContactModel mat{0.6, 0.7};
    ContactSolver solver;
    const int ia = solver.add_body(a);
    const int ib = solver.add_body(b);
    solver.add_contact(ia, ib, c, n, mat);
    solver.solve(trial % 2 ? resting : ContactSolver::Settings());
    const Vec3 expected = collision_impulse(a, b, c, n, mat);
    EXPECT_NEAR(norm(solver.impulse(0) - expected), 0.0, 1e-12 * (1 + norm(expected)));
    RigidBodyState b_after = b;
    b_after.apply_impulse(expected, c);
    EXPECT_NEAR(norm(solver.body(1).v - b_after.v), 0.0, 1e-12 * (1 + norm(b_after.v)));
  }
}

namespace {

// A rod (mass m, length L, axis x) landing flat on a still plate with contacts at n equally
// spaced points of its underside, x = -1.8 ... 1.8 (a line contact sampled by n spheres).
RigidBodyState flat_rod()
{
  const double m = 2.0, L = 4.5;
  RigidBodyState rod;
  rod.inv_mass = 1.0 / m;
  rod.inv_inertia = Mat3::diagonal(Vec3(1 / 0.02, 12.0 / (m * L * L), 12.0 / (m * L * L)));
  rod.com = Vec3(0, 0, 0.5);
  return rod;
}

ContactSolver line_contact(const RigidBodyState &rod, int n, const ContactModel &model,
                           int resolution = ContactSolver::Settings().resolution)
{
  ContactSolver solver;
  const int plate = solver.add_body(RigidBodyState::wall(Vec3()));
  const int body = solver.add_body(rod);
  for (int k = 0; k < n; ++k) {
    const double x = n == 1 ? 0.0 : 1.8 * (2 * k - (n - 1)) / (n - 1);    // exactly symmetric
    solver.add_contact(plate, body, Vec3(x, 0, 0), Vec3(0, 0, 1), model);
  }
  ContactSolver::Settings settings;
  settings.resolution = resolution;
  solver.solve(settings);
  return solver;
}

// Relative difference of two states of a body of size 1: |dv| + |d omega|, over a speed scale.
double state_difference(const RigidBodyState &a, const RigidBodyState &b, double scale)
{
  return (norm(a.v - b.v) + norm(a.omega - b.omega)) / scale;
}

}    // namespace

TEST(ContactSolver, OneContactOfAnIslandGetsStrongesImpact)
{
  // An island whose other contact separates: its one engaged spring integrates the impact along
  // Stronge's path. Frictionless (closed form exact) the error falls as 1/resolution; with
  // friction, against Stronge's integrated impact, within 1% at the default resolution.
  for (double mu : {0.0, 0.5}) {
    for (int resolution : {100, 150, 1000}) {
      std::mt19937 rng(3);
      std::uniform_real_distribution<double> U(0.0, 1.0);
      double worst = 0.0;
      int cases = 0;
      for (int trial = 0; trial < 3000 && cases < 300; ++trial) {
        const RigidBodyState plate = RigidBodyState::wall(Vec3(0, 0, 0.1)), b = random_body(rng);
        const Vec3 c = b.com + random_unit(rng) * 0.5, c2 = b.com - random_unit(rng) * 0.5;
        Vec3 n = random_unit(rng);
        const Vec3 n2 = random_unit(rng);
        if (dot(b.velocity_at(c) - plate.v, n) > 0) n = -n;
        const ContactModel model{trial % 4 == 0 ? 0.0 : U(rng), mu * U(rng)};
        if (dot(b.velocity_at(c2) - plate.v, n2) < 0.5) continue;    // must stay clear
        ContactSolver solver;
        solver.add_body(plate);
        solver.add_body(b);
        solver.add_contact(0, 1, c, n, model);
        solver.add_contact(0, 1, c2, n2, model);
        ContactSolver::Settings settings;
        settings.resolution = resolution;
        solver.solve(settings);
        ASSERT_FALSE(solver.contact(0).isolated);
        if (norm(solver.impulse(1)) > 0.0) continue;
        const Vec3 expected = collision_impulse(plate, b, c, n, model);
        worst = std::max(worst, norm(solver.impulse(0) - expected) / norm(expected));
        ++cases;
      }
      std::printf("[ measured ] mu <= %.1f, resolution %4d: largest relative impulse error %.2g (%d impacts)\n",
                  mu, resolution, worst, cases);
      EXPECT_GT(cases, 200);
      if (mu == 0.0) {
        EXPECT_LT(worst, 3.0 / resolution);
      } else if (resolution >= 150) {
        EXPECT_LT(worst, 1e-2);
      }
    }
  }
}

TEST(ContactSolver, IslandReboundIsSecondOrderInTheSubStep)
{
  // A bead landing on a plate whose second contact stays clear: the engaged spring turns from
  // loading to its stiff unloading (stiffness 1/e^2) within a few sub-steps. The sub-steps
  // shrink before the turn, so the rebound converges at second order; without that, the drift
  // across the turn skipped most of the unloading (e = 0.1: 20% off at resolution 20).
  for (double e : {0.05, 0.1, 0.3, 0.6}) {
    double error[2];
    for (int k = 0; k < 2; ++k) {
      ContactSolver solver;
      solver.add_body(RigidBodyState::wall(Vec3()));
      solver.add_body(RigidBodyState::sphere(1.0, 0.5, Vec3(0, 0, 0.5), Vec3(0, 0, -1), Vec3()));
      solver.add_contact(0, 1, Vec3(0, 0, 0), Vec3(0, 0, 1), {e, 0.0});
      solver.add_contact(0, 1, Vec3(0.5, 0, 0.5), Vec3(-1, 0, 0), {e, 0.0});
      ContactSolver::Settings settings;
      settings.resolution = 20 << k;
      solver.solve(settings);
      ASSERT_FALSE(solver.contact(0).isolated);
      error[k] = std::fabs(solver.body(1).v.z - e);
    }
    std::printf("[ measured ] e %.2f: rebound error %.2g at resolution 20, %.2g at 40\n", e, error[0], error[1]);
    EXPECT_LT(error[0], 3e-3) << "e " << e;
    EXPECT_LT(error[1], 0.35 * error[0] + 1e-9) << "e " << e;
  }
}

TEST(ContactSolver, SymmetricLineContactBouncesLikeOneCentralContact)
{
  for (double e : {0.0, 0.1, 0.3, 1.0}) {
    RigidBodyState rod = flat_rod();
    rod.v = Vec3(0, 0, -1.0);
    for (int n : {2, 5, 9}) {
      const ContactSolver s = line_contact(rod, n, {e, 0.03});
      EXPECT_NEAR(s.body(1).v.z, e, 3.0 / ContactSolver::Settings().resolution) << "e " << e << ", " << n << " contacts";
      EXPECT_NEAR(norm(s.body(1).omega), 0.0, 1e-9);
      EXPECT_NEAR(norm(s.body(1).v - Vec3(0, 0, s.body(1).v.z)), 0.0, 1e-12);
    }
  }
}

TEST(ContactSolver, LineContactConvergesWithTheNumberOfSpheres)
{
  // A rod landing flat while sliding and spinning: the body's velocities after the impact
  // converge as the line contact is sampled by more spheres (equal springs share the load as an
  // elastic foundation does), whatever the friction. First order: n points on a line carry its
  // moment of inertia with a relative error ~2/n.
  for (double mu : {0.03, 0.3}) {
    RigidBodyState rod = flat_rod();
    rod.v = Vec3(0.3, 0.2, -1.0);
    rod.omega = Vec3(0.3, 0.4, 0.5);
    std::vector<RigidBodyState> after;
    for (int n : {3, 5, 9, 17, 33}) after.push_back(line_contact(rod, n, {0.1, mu}).body(1));
    const double coarse = state_difference(after[1], after[2], 1.0);    // 5 vs 9
    const double fine = state_difference(after[3], after[4], 1.0);      // 17 vs 33
    std::printf("[ measured ] mu %.2f: 5 vs 9 spheres %.3g, 17 vs 33 spheres %.3g\n", mu, coarse, fine);
    EXPECT_LT(fine, 0.5 * coarse);
    EXPECT_LT(fine, 3e-2);
  }
}

TEST(ContactSolver, StickingLineContactStopsTheSlip)
{
  // High friction: the whole line sticks, shared among the contacts without overshoot; the rod
  // leaves without slip at its contacts (as one central sticking contact would make it), but for
  // the few % the shared sticking impulses lag behind at the default resolution.
  RigidBodyState rod = flat_rod();
  rod.v = Vec3(0.05, 0.02, -1.0);
  for (int n : {1, 5, 9}) {
    const ContactSolver s = line_contact(rod, n, {0.3, 2.0});
    for (int k = 0; k < s.num_contacts(); ++k) {
      const ContactSolver::Contact &c = s.contact(k);
      const Vec3 u = s.body(1).velocity_at_arm(c.r2);
      EXPECT_NEAR(norm(u - c.n * dot(u, c.n)), 0.0, 0.05 * 0.05) << n << " contacts";
    }
  }
}

namespace {

// A tapered rod (axis in the plate plane, slightly tilted) lying on a vibrating plate with
// several of its spheres, sliding and spinning, touched by beads from the side and one from
// above: contacts that share bodies, with slip that changes direction during the solve.
struct Cluster {
  std::vector<RigidBodyState> bodies;
  struct Touch { int body1, body2; Vec3 point, n; ContactModel model; double min_separation; };
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
  const ContactModel plate{0.1 + 0.5 * P(rng), 0.03};    // the paper's rod-plate friction
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
    for (auto &t : cl.touches) t.model.tangential.mu = 0.0;
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
ContactSolver solve_in_order(const Cluster &cl, const std::vector<int> &order,
                             int resolution = ContactSolver::Settings().resolution,
                             ContactSolver::Result *result = nullptr)
{
  ContactSolver solver;
  for (const RigidBodyState &b : cl.bodies) solver.add_body(b);
  for (int k : order) {
    const Cluster::Touch &t = cl.touches[k];
    solver.add_contact(t.body1, t.body2, t.point, t.n, t.model, t.min_separation);
  }
  ContactSolver::Settings settings;
  settings.resolution = resolution;
  const ContactSolver::Result r = solver.solve(settings);
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

std::vector<int> identity_order(const Cluster &cl)
{
  std::vector<int> order(cl.touches.size());
  std::iota(order.begin(), order.end(), 0);
  return order;
}

}    // namespace

TEST(ContactSolver, BodyVelocitiesDoNotDependOnContactOrder)
{
  // Every sub-step takes all impulses from one state: forward, reversed and shuffled orders
  // agree to round-off, with friction, spinning rods, beads and overlaps. (Round-off grows
  // where it flips a decision, stick or slide, within a sub-step: measured up to ~5e-7, while
  // the sub-step's own error is ~2e-3, BodyVelocitiesConvergeWithResolution.)
  std::mt19937 rng(7);
  double largest = 0.0;
  int exact = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Cluster cl = random_cluster(rng);
    const std::vector<int> forward = identity_order(cl);
    std::vector<int> reversed(forward.rbegin(), forward.rend()), shuffled = forward;
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    ContactSolver::Result result;
    const ContactSolver a = solve_in_order(cl, forward, ContactSolver::Settings().resolution, &result);
    EXPECT_TRUE(result.converged) << "trial " << trial;
    const double difference = std::max(velocity_difference(a, solve_in_order(cl, reversed)),
                                       velocity_difference(a, solve_in_order(cl, shuffled)));
    largest = std::max(largest, difference);
    exact += difference < 1e-12;
  }
  std::printf("[ measured ] velocity differences between contact orders: %d of 300 clusters below "
              "1e-12, largest %.2g\n", exact, largest);
  EXPECT_GE(exact, 250);
  EXPECT_LT(largest, 1e-5);
}

TEST(ContactSolver, BodyVelocitiesConvergeWithResolution)
{
  // The only numerical setting: the sub-step. Differences to a fine resolution fall as it
  // grows; at the default (150) they are a small fraction of the cluster's speeds (~1 here).
  std::mt19937 rng(17);
  double coarse = 0.0, standard = 0.0, finer = 0.0;
  for (int trial = 0; trial < 100; ++trial) {
    const Cluster cl = random_cluster(rng);
    const ContactSolver fine = solve_in_order(cl, identity_order(cl), 3000);
    coarse = std::max(coarse, velocity_difference(fine, solve_in_order(cl, identity_order(cl), 100)));
    standard = std::max(standard, velocity_difference(fine, solve_in_order(cl, identity_order(cl))));
    finer = std::max(finer, velocity_difference(fine, solve_in_order(cl, identity_order(cl), 300)));
  }
  std::printf("[ measured ] largest velocity difference to resolution 3000: %.2g at 100, %.2g at the "
              "default, %.2g at 300\n", coarse, standard, finer);
  EXPECT_LT(finer, 0.5 * coarse);
  EXPECT_LT(standard, 1e-2);
}

TEST(ContactSolver, CoupledContactsDoNotGainEnergy)
{
  // Without overlap corrections an impact never adds kinetic energy (in the frame of the moving
  // plate, where it does no work).
  std::mt19937 rng(9);
  for (int trial = 0; trial < 300; ++trial) {
    Cluster cl = random_cluster(rng);
    for (auto &t : cl.touches) t.min_separation = 0.0;
    ContactSolver before;
    for (const RigidBodyState &b : cl.bodies) before.add_body(b);
    const Vec3 plate = cl.bodies[0].v;
    const ContactSolver after = solve_in_order(cl, identity_order(cl));
    EXPECT_LE(total_energy(after, plate), total_energy(before, plate) * (1 + 1e-9)) << "trial " << trial;
  }
}

TEST(ContactSolver, DenseClusterSettlesWithoutTheSlowTail)
{
  // A hexagonal patch of 64 touching beads on a rising plate, jostled: one island of 225
  // contacts. Its impact ends once nothing is loaded and nothing approaches faster than 1% of the
  // fastest approach before it (slower re-collisions are found again next step): no contact is
  // left approaching faster, and the impact does not gain energy.
  std::mt19937 rng(1);
  std::normal_distribution<double> G;
  const Vec3 plate_velocity(0, 0, 0.05);
  ContactSolver solver;
  solver.add_body(RigidBodyState::wall(plate_velocity));
  std::vector<Vec3> centres;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) {
      centres.emplace_back(i + 0.5 * (j % 2), j * std::sqrt(3.0) / 2, 0.5);
      solver.add_body(RigidBodyState::sphere(1.0, 0.5, centres.back(), Vec3(G(rng), G(rng), G(rng)) * 0.01,
                                             Vec3(G(rng), G(rng), G(rng)) * 0.01));
    }
  for (std::size_t a = 0; a < centres.size(); ++a) {
    solver.add_contact(0, a + 1, centres[a] - Vec3(0, 0, 0.5), Vec3(0, 0, 1), {0.3, 0.01});
    for (std::size_t b = a + 1; b < centres.size(); ++b) {
      const Vec3 d = centres[b] - centres[a];
      if (norm(d) < 1.0 + 1e-9) solver.add_contact(a + 1, b + 1, (centres[a] + centres[b]) * 0.5, d / norm(d), {0.3, 0.05});
    }
  }
  auto approach = [&](int c) {
    const ContactSolver::Contact &k = solver.contact(c);
    return -dot(solver.body(k.body2).velocity_at_arm(k.r2) - solver.body(k.body1).velocity_at_arm(k.r1), k.n);
  };
  double fastest = 0.0;
  for (int c = 0; c < solver.num_contacts(); ++c) fastest = std::max(fastest, approach(c));
  const double energy_before = total_energy(solver, plate_velocity);
  const ContactSolver::Result result = solver.solve();
  double left = 0.0;
  for (int c = 0; c < solver.num_contacts(); ++c) left = std::max(left, approach(c));
  std::printf("[ measured ] %d contacts: %d sub-steps, fastest approach left %.3g of the first\n",
              solver.num_contacts(), result.substeps, left / fastest);
  EXPECT_TRUE(result.converged);
  EXPECT_LE(left, 1e-2 * fastest * (1 + 1e-9));
  EXPECT_LE(total_energy(solver, plate_velocity), energy_before * (1 + 1e-12));
}

TEST(ContactSolver, AnIslandSolvedElsewhereLeavesTheOthersAsTheyWere)
{
  // Two clusters in one solver, the second's contacts solved elsewhere (by a solver that sees its
  // island whole, IslandExchange): the first solves as before, bit for bit, the second's bodies
  // stay as they were, and the other solver's results, set back, give the energy ledger the
  // numbers of one solve of both.
  std::mt19937 rng(23);
  for (int trial = 0; trial < 50; ++trial) {
    const Cluster first = random_cluster(rng), second = random_cluster(rng);
    auto add = [](ContactSolver &solver, const Cluster &cl) {
      const int offset = solver.num_bodies();
      for (const RigidBodyState &b : cl.bodies) solver.add_body(b);
      for (const Cluster::Touch &t : cl.touches)
        solver.add_contact(t.body1 + offset, t.body2 + offset, t.point, t.n, t.model, t.min_separation);
    };
    ContactSolver both, split, elsewhere;
    add(both, first);
    add(both, second);
    add(split, first);
    add(split, second);
    add(elsewhere, second);
    const int n1 = static_cast<int>(first.touches.size()), n2 = static_cast<int>(second.touches.size());
    for (int c = n1; c < n1 + n2; ++c) split.solve_elsewhere(c);
    both.solve();
    split.solve();
    elsewhere.solve();
    for (int c = 0; c < n1; ++c) {
      EXPECT_EQ(split.impulse(c).x, both.impulse(c).x) << "trial " << trial;
      EXPECT_EQ(split.impulse(c).z, both.impulse(c).z) << "trial " << trial;
    }
    const int b1 = static_cast<int>(first.bodies.size());
    for (int b = 0; b < static_cast<int>(second.bodies.size()); ++b)
      EXPECT_EQ(norm(split.body(b1 + b).v - second.bodies[b].v), 0.0) << "trial " << trial;
    for (int c = 0; c < n2; ++c) {
      const ContactSolver::Contact &solved = elsewhere.contact(c);
      split.set_solution(n1 + c, solved.impulse, solved.late, solved.velocity_after);
      EXPECT_NEAR(norm(solved.impulse - both.impulse(n1 + c)), 0.0, 1e-12 * (1 + norm(both.impulse(n1 + c))));
      const Vec3 before = relative_velocity(std::vector<RigidBodyState>{second.bodies}, elsewhere.contact(c));
      const ContactEnergy in_both = contact_energy(both, n1 + c, before, 0.0);
      const ContactEnergy in_split = contact_energy(split, n1 + c, before, 0.0);
      EXPECT_NEAR(in_split.dissipated, in_both.dissipated, 1e-12 * (1 + std::fabs(in_both.dissipated)));
    }
  }
}

TEST(ContactSolver, BeadChainDoesNotGainEnergyAndConservesMomentum)
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
    const ContactModel mat{U(rng), U(rng)};
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
    Vec3 P0, L0;
    for (int k = 0; k < nbeads; ++k) {
      E0 += kinetic_energy(solver.body(k));
      P0 += linear_momentum(solver.body(k));
      L0 += angular_momentum(solver.body(k), Vec3());
    }
    solver.solve();
    double E1 = 0;
    Vec3 P1, L1;
    for (int k = 0; k < nbeads; ++k) {
      E1 += kinetic_energy(solver.body(k));
      P1 += linear_momentum(solver.body(k));
      L1 += angular_momentum(solver.body(k), Vec3());
    }
    EXPECT_LE(E1, E0 * (1 + 1e-12)) << "trial " << trial;
    if (!wall_at_end) {
      EXPECT_NEAR(norm(P1 - P0), 0.0, 1e-12 * (1 + norm(P0))) << "trial " << trial;
      EXPECT_NEAR(norm(L1 - L0), 0.0, 1e-12 * (1 + norm(L0))) << "trial " << trial;
    }
  }
}

TEST(ContactSolver, MinimumSeparationPushesOverlappingBodiesApart)
{
  ContactSolver solver;
  const int wall = solver.add_body(RigidBodyState::wall(Vec3()));
  const int bead = solver.add_body(RigidBodyState::sphere(1.0, 0.5, Vec3(0, 0, 0.49), Vec3(), Vec3()));
  solver.add_contact(wall, bead, Vec3(), Vec3(0, 0, 1), {0.3, 0.1}, 0.01);
  solver.solve();
  EXPECT_NEAR(solver.body(bead).v.z, 0.01, 1e-15);
}

TEST(ContactSolver, OverlapsInAnIslandOpenAtTheirMinimumSeparation)
{
  // A rod resting on a plate with overlapping spheres, touched by beads: every overlap leaves at
  // least at its minimum separation velocity.
  std::mt19937 rng(21);
  for (int trial = 0; trial < 100; ++trial) {
    Cluster cl = random_cluster(rng);
    for (auto &t : cl.touches) t.min_separation = 0.05;
    ContactSolver::Result result;
    const ContactSolver s = solve_in_order(cl, identity_order(cl), ContactSolver::Settings().resolution, &result);
    EXPECT_TRUE(result.converged);
    for (int k = 0; k < s.num_contacts(); ++k) {
      const ContactSolver::Contact &c = s.contact(k);
      const Vec3 u = s.body(c.body2).velocity_at_arm(c.r2) - s.body(c.body1).velocity_at_arm(c.r1);
      EXPECT_GE(dot(u, c.n), 0.05 * (1 - 1e-2)) << "trial " << trial << " contact " << k;
    }
  }
}

// A contact's gain (the relative velocity other forces add before it closes) enters the law as
// part of the approach, alone or in an island: a flat rod falling at 1 on a line contact with a
// gain of 0.2 towards the plate leaves at e (1 + 0.2) less the gain, without turning.
TEST(ContactSolver, GainIsPartOfTheApproach)
{
  const ContactModel model{0.5, 0.3};
  for (int n : {1, 5}) {
    RigidBodyState rod = flat_rod();
    rod.v = Vec3(0, 0, -1);
    ContactSolver solver;
    const int plate = solver.add_body(RigidBodyState::wall(Vec3()));
    const int body = solver.add_body(rod);
    for (int k = 0; k < n; ++k) {
      const double x = n == 1 ? 0.0 : 1.8 * (2 * k - (n - 1)) / (n - 1);
      solver.add_contact(plate, body, Vec3(x, 0, 0), Vec3(0, 0, 1), model, 0.0, Vec3(0, 0, -0.2));
    }
    solver.solve();
    const double tolerance = n == 1 ? 1e-12 : 1e-3;    // the compliant impact's resolution
    EXPECT_NEAR(solver.body(body).v.z, 0.5 * 1.2 + 0.2, tolerance) << n << " contacts";
    EXPECT_NEAR(norm(solver.body(body).omega), 0.0, 1e-9) << n << " contacts";
  }
}

namespace {

// The flat rod of line_contact over a still plate with two contacts of its underside, at the
// centre (x = 0) and at the nose (x = 1.8), which close at the given times of a step of 1.
struct TwoContactLanding {
  RigidBodyState rod = flat_rod();
  ContactModel model{0.5, 0.0};
  double centre_time = 0.1, nose_time = 0.6;

  Vec3 point(int k) const { return Vec3(k == 0 ? 0.0 : 1.8, 0, 0); }
  ContactSolver solve(double window) const
  {
    ContactSolver solver;
    const int plate = solver.add_body(RigidBodyState::wall(Vec3()));
    const int body = solver.add_body(rod);
    solver.add_contact(plate, body, point(0), Vec3(0, 0, 1), model, 0.0, Vec3(), centre_time);
    solver.add_contact(plate, body, point(1), Vec3(0, 0, 1), model, 0.0, Vec3(), nose_time);
    ContactSolver::Settings settings;
    settings.window = window;
    settings.step = 1.0;
    solver.solve(settings);
    return solver;
  }
};

double approach_at(const RigidBodyState &body, const Vec3 &point)
{
  return -body.velocity_at(point).z;
}

}    // namespace

TEST(ContactSolver, IslandContactsMeetInTheOrderTheyClose)
{
  // Further apart than the window, the contacts are two impacts, each by Stronge's law alone:
  // the centre's at its time, then the nose's at the time its gap closes at the velocities the
  // first impact left (a falling rod spun nose down). Each contact's late impulse is its
  // impulse times that time.
  TwoContactLanding landing;
  landing.rod.v = Vec3(0.2, 0, -1);
  landing.rod.omega = Vec3(0, 1.5, 0);
  landing.model.tangential.mu = 0.3;
  landing.nose_time = 0.4;
  const ContactSolver solver = landing.solve(0.01);
  const RigidBodyState plate = RigidBodyState::wall(Vec3());
  RigidBodyState rod = landing.rod;
  const double nose_gap = approach_at(rod, landing.point(1)) * landing.nose_time;
  const Vec3 first = collision_impulse(plate, rod, landing.point(0), Vec3(0, 0, 1), landing.model);
  rod.apply_impulse(first, landing.point(0));
  const double nose_time =
      landing.centre_time + (nose_gap - approach_at(landing.rod, landing.point(1)) * landing.centre_time) /
                                approach_at(rod, landing.point(1));
  ASSERT_GT(nose_time, landing.nose_time);    // the first impact slowed the nose: it closes later
  ASSERT_LT(nose_time, 1.0);
  const Vec3 second = collision_impulse(plate, rod, landing.point(1), Vec3(0, 0, 1), landing.model);
  rod.apply_impulse(second, landing.point(1));
  EXPECT_NEAR(norm(solver.impulse(0) - first), 0.0, 1e-12);
  EXPECT_NEAR(norm(solver.impulse(1) - second), 0.0, 1e-12);
  EXPECT_NEAR(norm(solver.body(1).v - rod.v), 0.0, 1e-12);
  EXPECT_NEAR(norm(solver.body(1).omega - rod.omega), 0.0, 1e-12);
  EXPECT_NEAR(norm(solver.contact(0).late - first * landing.centre_time), 0.0, 1e-12);
  EXPECT_NEAR(norm(solver.contact(1).late - second * nose_time), 0.0, 1e-12);
  // Within one window they are one compliant impact, as with the window left at the step.
  landing.nose_time = landing.centre_time + 0.005;
  const ContactSolver together = landing.solve(0.01), whole_step = landing.solve(ContactSolver::Settings().window);
  EXPECT_EQ(norm(together.body(1).v - whole_step.body(1).v), 0.0);
  EXPECT_GT(norm(together.body(1).v - rod.v), 1e-3);
}

TEST(ContactSolver, LaterContactsThatNoLongerCloseWithinTheStepWait)
{
  // The centre's impact stops the rod's fall: a nose that only fell with it separates, and one
  // that also spun down now closes after the step. Neither gets an impulse; the centre's is
  // Stronge's alone.
  for (double spin : {0.0, 0.5}) {
    TwoContactLanding landing;
    landing.rod.v = Vec3(0, 0, -1);
    landing.rod.omega = Vec3(0, spin, 0);
    landing.model.normal.e = spin == 0.0 ? 0.5 : 0.0;
    const ContactSolver solver = landing.solve(0.01);
    const Vec3 first = collision_impulse(RigidBodyState::wall(Vec3()), landing.rod, landing.point(0),
                                         Vec3(0, 0, 1), landing.model);
    EXPECT_NEAR(norm(solver.impulse(0) - first), 0.0, 1e-12) << "spin " << spin;
    EXPECT_EQ(norm(solver.impulse(1)), 0.0) << "spin " << spin;
    EXPECT_GT(norm(landing.solve(ContactSolver::Settings().window).impulse(1)), 0.0) << "spin " << spin;
  }
}

TEST(ContactSolver, ImpactsInOrderDoNotGainEnergyNorDependOnContactOrder)
{
  // Random clusters whose contacts close at random times of the step: impacts in order never add
  // kinetic energy (in the plate's frame), and listing the contacts in another order changes
  // nothing but round-off.
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int ordered = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Cluster cl = random_cluster(rng);
    for (auto &t : cl.touches) t.min_separation = 0.0;
    std::vector<double> times(cl.touches.size());
    for (double &t : times) t = trial % 5 == 0 ? 0.0 : U(rng);
    auto solve = [&](const std::vector<int> &order) {
      ContactSolver solver;
      for (const RigidBodyState &b : cl.bodies) solver.add_body(b);
      for (int k : order) {
        const Cluster::Touch &t = cl.touches[k];
        solver.add_contact(t.body1, t.body2, t.point, t.n, t.model, 0.0, Vec3(), times[k]);
      }
      ContactSolver::Settings settings;
      settings.window = 0.05;
      settings.step = 1.0;
      solver.solve(settings);
      return solver;
    };
    ContactSolver before;
    for (const RigidBodyState &b : cl.bodies) before.add_body(b);
    const std::vector<int> forward = identity_order(cl);
    const ContactSolver after = solve(forward);
    const Vec3 plate = cl.bodies[0].v;
    EXPECT_LE(total_energy(after, plate), total_energy(before, plate) * (1 + 1e-9)) << "trial " << trial;
    const std::vector<int> reversed(forward.rbegin(), forward.rend());
    EXPECT_LT(velocity_difference(after, solve(reversed)), 1e-5) << "trial " << trial;
    ordered += *std::max_element(times.begin(), times.end()) - *std::min_element(times.begin(), times.end()) > 0.05;
  }
  EXPECT_GT(ordered, 200);
}
