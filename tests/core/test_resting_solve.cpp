// Resting contacts solved together (ag_resting_solve.h) and the impacts around them
// (ag_contact_solver.h with a resting speed).
#include "ag_contact_solver.h"
#include "ag_hash.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <random>

using namespace ActiveGrain;
using namespace ActiveGrain::testing;

namespace {

constexpr double RESTING_SPEED = 0.01;

ContactSolver::Settings resting_settings(double tolerance = ContactSolver::Settings().resting_tolerance)
{
  ContactSolver::Settings settings;
  settings.resting_speed = RESTING_SPEED;
  settings.resting_tolerance = tolerance;
  return settings;
}

// A hexagonal patch of rows x columns touching beads (diameter 1) on a plate, squeezed in the
// plane by fixed side walls, jostled with velocities of about speed: one island of bead-bead,
// bead-plate and bead-wall contacts.
struct Packing {
  std::vector<RigidBodyState> bodies;    // plate, then beads
  struct Touch {
    int body1, body2;
    Vec3 point, n;
    ContactMaterial material;
  };
  std::vector<Touch> touches;
};

Packing hexagonal_packing(int rows, int columns, double speed, double mu, std::mt19937 &rng)
{
  std::normal_distribution<double> G;
  Packing p;
  p.bodies.push_back(RigidBodyState::wall(Vec3()));
  std::vector<Vec3> centres;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      centres.emplace_back(i + 0.5 * (j % 2), j * std::sqrt(3.0) / 2, 0.5);
      p.bodies.push_back(RigidBodyState::sphere(1.0, 0.5, centres.back(), Vec3(G(rng), G(rng), G(rng)) * speed,
                                                Vec3(G(rng), G(rng), G(rng)) * speed));
    }
  for (std::size_t a = 0; a < centres.size(); ++a) {
    const int body = static_cast<int>(a) + 1;
    p.touches.push_back({0, body, centres[a] - Vec3(0, 0, 0.5), Vec3(0, 0, 1), {0.3, mu}});
    const double x = centres[a].x;
    if (x < 0.25) p.touches.push_back({0, body, centres[a] - Vec3(0.5, 0, 0), Vec3(1, 0, 0), {0.3, mu}});
    if (x > columns - 1.25) p.touches.push_back({0, body, centres[a] + Vec3(0.5, 0, 0), Vec3(-1, 0, 0), {0.3, mu}});
    for (std::size_t b = a + 1; b < centres.size(); ++b) {
      const Vec3 d = centres[b] - centres[a];
      if (norm(d) < 1.0 + 1e-9)
        p.touches.push_back({body, static_cast<int>(b) + 1, (centres[a] + centres[b]) * 0.5, d / norm(d), {0.3, mu}});
    }
  }
  return p;
}

ContactSolver solve_packing(const Packing &p, const std::vector<int> &order, const ContactSolver::Settings &settings,
                            ContactSolver::Result *result = nullptr)
{
  ContactSolver solver;
  for (const RigidBodyState &b : p.bodies) solver.add_body(b);
  for (int k : order) {
    const Packing::Touch &t = p.touches[k];
    const int c = solver.add_contact(t.body1, t.body2, t.point, t.n, t.material);
    solver.set_key(c, mix64(static_cast<std::uint64_t>(k)));    // the touch, whatever the order
  }
  const ContactSolver::Result r = solver.solve(settings);
  if (result) *result = r;
  return solver;
}

std::vector<int> identity_order(std::size_t n)
{
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  return order;
}

double largest_velocity_difference(const ContactSolver &a, const ContactSolver &b)
{
  double largest = 0;
  for (int k = 0; k < a.num_bodies(); ++k)
    largest = std::max(largest, norm(a.body(k).v - b.body(k).v) + 0.5 * norm(a.body(k).omega - b.body(k).omega));
  return largest;
}

double kinetic(const ContactSolver &s)
{
  double E = 0;
  for (int b = 0; b < s.num_bodies(); ++b) E += kinetic_energy(s.body(b));
  return E;
}

double fastest_approach(const ContactSolver &s)
{
  double fastest = 0;
  for (int c = 0; c < s.num_contacts(); ++c)
  {
    const ContactSolver::Contact &k = s.contact(c);
    const Vec3 u = s.body(k.body2).velocity_at_arm(k.r2) - s.body(k.body1).velocity_at_arm(k.r1);
    fastest = std::max(fastest, -dot(u, k.n));
  }
  return fastest;
}

}    // namespace

TEST(RestingSolve, SlowPackingConvergesWithNothingApproachingAndNoEnergyGained)
{
  // 80 touching beads squeezed between side walls on a plate, every contact approaching slower
  // than the resting speed: one resting solve; after it no contact approaches faster than the
  // tolerance, and no energy is gained (a plastic solve at still walls).
  std::mt19937 rng(3);
  for (double mu : {0.0, 0.5}) {
    const Packing p = hexagonal_packing(8, 10, 0.2 * RESTING_SPEED, mu, rng);
    ContactSolver before;
    for (const RigidBodyState &b : p.bodies) before.add_body(b);
    ContactSolver::Result result;
    ContactSolver::Settings settings = resting_settings();
    settings.max_resting_sweeps = 20000;    // from rest, without the last step's impulses
    const ContactSolver s = solve_packing(p, identity_order(p.touches.size()), settings, &result);
    std::printf("[ measured ] mu %.1f: %d contacts, %d sweeps, fastest approach left %.2g of the resting speed\n",
                mu, s.num_contacts(), result.resting_sweeps, fastest_approach(s) / RESTING_SPEED);
    EXPECT_TRUE(result.resting_converged);
    EXPECT_LE(fastest_approach(s), 10 * ContactSolver::Settings().resting_tolerance * RESTING_SPEED);
    EXPECT_LE(kinetic(s), kinetic(before) * (1 + 1e-12));
  }
}

TEST(RestingSolve, TheToleranceBoundsWhatAContactLacksAndALooserOneTakesFewerSweeps)
{
  // The same squeezed packing with friction at three tolerances: after each solve no contact
  // approaches faster than the tolerance times the resting speed, and a looser tolerance stops
  // after fewer sweeps.
  std::mt19937 rng(5);
  const Packing p = hexagonal_packing(8, 10, 0.2 * RESTING_SPEED, 0.3, rng);
  int sweeps_before = 1 << 30;
  for (double tolerance : {1e-3, 1e-2, 1e-1}) {
    ContactSolver::Result result;
    ContactSolver::Settings settings = resting_settings(tolerance);
    settings.max_resting_sweeps = 20000;
    const ContactSolver s = solve_packing(p, identity_order(p.touches.size()), settings, &result);
    std::printf("[ measured ] tolerance %.0e: %d sweeps, fastest approach left %.2g of the resting speed\n",
                tolerance, result.resting_sweeps, fastest_approach(s) / RESTING_SPEED);
    EXPECT_TRUE(result.resting_converged);
    EXPECT_LE(fastest_approach(s), tolerance * RESTING_SPEED);
    EXPECT_LT(result.resting_sweeps, sweeps_before);
    sweeps_before = result.resting_sweeps;
  }
}

TEST(RestingSolve, BodyVelocitiesDoNotDependOnContactOrder)
{
  // Forward, reversed and shuffled orders of a squeezed packing agree bit for bit, frictionless
  // and with friction (where the answer is not unique: the sweeps visit the contacts colour by
  // colour in the order of their keys, whatever the order they came in), converged or not.
  std::mt19937 rng(5);
  for (double mu : {0.0, 0.3}) {
    double largest = 0.0;
    for (int trial = 0; trial < 5; ++trial) {
      const Packing p = hexagonal_packing(6, 8, 0.3 * RESTING_SPEED, mu, rng);
      const std::vector<int> forward = identity_order(p.touches.size());
      std::vector<int> reversed(forward.rbegin(), forward.rend()), shuffled = forward;
      std::shuffle(shuffled.begin(), shuffled.end(), rng);
      const ContactSolver::Settings settings = resting_settings();
      const ContactSolver a = solve_packing(p, forward, settings);
      largest = std::max({largest, largest_velocity_difference(a, solve_packing(p, reversed, settings)),
                          largest_velocity_difference(a, solve_packing(p, shuffled, settings))});
    }
    std::printf("[ measured ] mu %.1f: largest velocity difference between orders %.2g of the resting speed\n",
                mu, largest / RESTING_SPEED);
    EXPECT_LT(largest, 1e-10 * RESTING_SPEED);
  }
}

TEST(RestingSolve, AColumnOnAPlateStopsAndItsBottomCarriesItsWeight)
{
  // A column of 12 beads on a plate under gravity: each step gravity gives every bead g dt
  // downwards and the column must stop, the load crossing it sweep by sweep from zero.
  const double g_dt = 0.2 * RESTING_SPEED;
  const int n = 12;
  Packing p;
  p.bodies.push_back(RigidBodyState::wall(Vec3()));
  for (int k = 0; k < n; ++k)
    p.bodies.push_back(RigidBodyState::sphere(1.0, 0.5, Vec3(0, 0, 0.5 + k), Vec3(0, 0, -g_dt), Vec3()));
  for (int k = 0; k < n; ++k) p.touches.push_back({k, k + 1, Vec3(0, 0, k), Vec3(0, 0, 1), {0.5, 0.3}});
  const ContactSolver::Settings settings = resting_settings();
  ContactSolver::Result result;
  const ContactSolver column = solve_packing(p, identity_order(n), settings, &result);
  std::printf("[ measured ] a column of %d beads: %d sweeps\n", n, result.resting_sweeps);
  EXPECT_TRUE(result.resting_converged);
  for (int b = 1; b <= n; ++b) EXPECT_NEAR(norm(column.body(b).v), 0.0, settings.resting_tolerance * RESTING_SPEED * n);
  EXPECT_NEAR(dot(column.impulse(0), Vec3(0, 0, 1)), n * g_dt, 0.05 * n * g_dt);
}

TEST(RestingSolve, AnImpactIntoARestingPackingKeepsStrongesLawAndGainsNoEnergy)
{
  // A bead strikes a squeezed, slow packing: its contact is an impact (Stronge's law, as if
  // alone, then the packing takes the momentum as resting contacts); no energy is gained and
  // the whole island's momentum along the plate conserves where no wall touches.
  std::mt19937 rng(8);
  for (double mu : {0.0, 0.4}) {
    Packing p = hexagonal_packing(4, 5, 0.1 * RESTING_SPEED, mu, rng);
    const Vec3 centre = p.bodies[1].com - Vec3(1.0, 0, 0);
    p.bodies.push_back(RigidBodyState::sphere(1.0, 0.5, centre, Vec3(0.5, 0.1, 0), Vec3(0, 0, 1)));
    const int striker = static_cast<int>(p.bodies.size()) - 1;
    p.touches.push_back({striker, 1, centre + Vec3(0.5, 0, 0), Vec3(1, 0, 0), {0.8, mu}});
    ContactSolver before;
    for (const RigidBodyState &b : p.bodies) before.add_body(b);
    ContactSolver::Result result;
    const ContactSolver s = solve_packing(p, identity_order(p.touches.size()), resting_settings(), &result);
    EXPECT_TRUE(result.resting_converged);
    EXPECT_LE(kinetic(s), kinetic(before) * (1 + 1e-12));
    // the striker's impact, alone: Stronge's law on its relative velocity before
    const Vec3 J = collision_impulse(before.body(striker), before.body(1), centre + Vec3(0.5, 0, 0), Vec3(1, 0, 0),
                                     {0.8, mu});
    EXPECT_GT(dot(J, Vec3(1, 0, 0)), 0.0);
    EXPECT_LE(fastest_approach(s), 10 * ContactSolver::Settings().resting_tolerance * RESTING_SPEED);
  }
}
