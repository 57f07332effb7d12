// The contact solver's thresholds (SolverSettings) change the outcome as documented.
#include "ag_contact_solver.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace ActiveGrain;
using namespace ActiveGrain::testing;

namespace {

// A rod (axis x, length 4.5, mass 2) lying flat 0.5 above a still plate, with contacts at
// x = +-1.8 of its underside.
ContactSolver flat_rod_on_plate(const Vec3 &v, const ContactModel &model, double min_separation,
                                const Vec3 &gain = Vec3(), double nose_time = 0.0)
{
  const double m = 2.0, L = 4.5;
  RigidBodyState rod;
  rod.inv_mass = 1.0 / m;
  rod.inv_inertia = Mat3::diagonal(Vec3(1 / 0.02, 12.0 / (m * L * L), 12.0 / (m * L * L)));
  rod.com = Vec3(0, 0, 0.5);
  rod.v = v;
  ContactSolver solver;
  const int plate = solver.add_body(RigidBodyState::wall(Vec3()));
  const int body = solver.add_body(rod);
  solver.add_contact(plate, body, Vec3(-1.8, 0, 0), Vec3(0, 0, 1), model, min_separation);
  solver.add_contact(plate, body, Vec3(1.8, 0, 0), Vec3(0, 0, 1), model, min_separation, gain, nose_time);
  return solver;
}

}    // namespace

TEST(SolverSettings, SettledApproachEndsTheImpact)
{
  // A jostled patch of beads on a plate: the impact ends once nothing approaches faster than
  // settled_approach of the fastest approach before it; a smaller one leaves less, with more
  // sub-steps.
  std::mt19937 rng(3);
  std::normal_distribution<double> G;
  ContactSolver patch;
  patch.add_body(RigidBodyState::wall(Vec3()));
  std::vector<Vec3> centres;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      centres.emplace_back(i + 0.5 * (j % 2), j * std::sqrt(3.0) / 2, 0.5);
      patch.add_body(RigidBodyState::sphere(1.0, 0.5, centres.back(), Vec3(G(rng), G(rng), G(rng)) * 0.01,
                                            Vec3(G(rng), G(rng), G(rng)) * 0.01));
    }
  for (std::size_t a = 0; a < centres.size(); ++a) {
    patch.add_contact(0, a + 1, centres[a] - Vec3(0, 0, 0.5), Vec3(0, 0, 1), {0.3, 0.01});
    for (std::size_t b = a + 1; b < centres.size(); ++b) {
      const Vec3 d = centres[b] - centres[a];
      if (norm(d) < 1.0 + 1e-9) patch.add_contact(a + 1, b + 1, (centres[a] + centres[b]) * 0.5, d / norm(d), {0.3, 0.05});
    }
  }
  double fastest = 0.0;
  for (int c = 0; c < patch.num_contacts(); ++c) fastest = std::max(fastest, -separation(patch, c));
  std::vector<int> substeps;
  for (double settled : {1e-1, 1e-2, 1e-3}) {
    ContactSolver solver = patch;
    ContactSolver::Settings settings;
    settings.settled_approach = settled;
    const ContactSolver::Result result = solver.solve(settings);
    double left = 0.0;
    for (int c = 0; c < solver.num_contacts(); ++c) left = std::max(left, -separation(solver, c));
    std::printf("[ measured ] settled_approach %.0e: %d sub-steps, fastest approach left %.3g of the first\n",
                settled, result.substeps, left / fastest);
    EXPECT_LE(left, settled * fastest * (1 + 1e-9));
    if (!substeps.empty()) {
      EXPECT_GE(result.substeps, substeps.back());
    }
    substeps.push_back(result.substeps);
  }
  EXPECT_LT(substeps.front(), substeps.back());
}

TEST(SolverSettings, RestingGainTellsRestingContactsFromImpacts)
{
  // A rod falling flat at 1 whose nose contact gains 1 towards the plate by the time it closes,
  // late in the step: approaching at 2, twice its gain, it rests (touching from the start, one
  // impact with the tail's) by default, and is a later impact below a resting gain of 2.
  const Vec3 gain(0, 0, -1);
  ContactSolver::Settings settings;
  settings.window = 0.01;
  settings.step = 1.0;
  ContactSolver resting = flat_rod_on_plate(Vec3(0, 0, -1), {0.5, 0.0}, 0.0, gain, 0.6);
  ContactSolver together = flat_rod_on_plate(Vec3(0, 0, -1), {0.5, 0.0}, 0.0, gain, 0.6);
  resting.solve(settings);
  together.solve();    // the whole step one impact
  EXPECT_EQ(norm(resting.body(1).v - together.body(1).v), 0.0);
  EXPECT_EQ(norm(resting.body(1).omega - together.body(1).omega), 0.0);
  settings.resting_gain = 1.5;
  ContactSolver ordered = flat_rod_on_plate(Vec3(0, 0, -1), {0.5, 0.0}, 0.0, gain, 0.6);
  ordered.solve(settings);
  EXPECT_GT(norm(ordered.body(1).omega - together.body(1).omega), 1e-3);
}

TEST(SolverSettings, MaxImpactsInOrderLeavesLaterContactsForTheNextStep)
{
  // A bead falling onto a floor while a lid comes down on it later in the step: its first impact
  // is the floor's, its second the lid's. With one impact in order at most, the lid waits.
  auto bounce = [](int max_impacts) {
    ContactSolver solver;
    const int floor = solver.add_body(RigidBodyState::wall(Vec3()));
    const int lid = solver.add_body(RigidBodyState::wall(Vec3(0, 0, -2)));
    const int bead = solver.add_body(RigidBodyState::sphere(1.0, 0.5, Vec3(0, 0, 0.5), Vec3(0, 0, -1), Vec3()));
    solver.add_contact(floor, bead, Vec3(), Vec3(0, 0, 1), {1.0, 0.0});
    solver.add_contact(lid, bead, Vec3(0, 0, 1), Vec3(0, 0, -1), {1.0, 0.0}, 0.0, Vec3(), 0.5);
    ContactSolver::Settings settings;
    settings.window = 0.01;
    settings.step = 1.0;
    settings.max_impacts_in_order = max_impacts;
    solver.solve(settings);
    return solver;
  };
  const ContactSolver one = bounce(1), two = bounce(2);
  EXPECT_NEAR(one.body(2).v.z, 1.0, 1e-12);    // bounced off the floor only
  EXPECT_EQ(norm(one.impulse(1)), 0.0);
  EXPECT_GT(norm(two.impulse(1)), 0.0);
  EXPECT_LT(two.body(2).v.z, -2.0);    // sent down faster than the lid
}

TEST(SolverSettings, OverlapSweepsAndToleranceSetHowExactlyOverlapsOpen)
{
  // A rod resting on a plate with two overlaps: the Jacobi sweeps share each push between the two
  // contacts, so they open gradually, to within overlap_tolerance of the minimum separation
  // velocity, or as far as max_overlap_sweeps get.
  const double min_separation = 0.01;
  auto open = [&](const ContactSolver::Settings &settings, ContactSolver::Result &result) {
    ContactSolver solver = flat_rod_on_plate(Vec3(), {0.3, 0.2}, min_separation);
    result = solver.solve(settings);
    return std::min(separation(solver, 0), separation(solver, 1));
  };
  ContactSolver::Settings settings;
  ContactSolver::Result result;
  const double exact = open(settings, result);
  EXPECT_GE(exact, (1 - settings.overlap_tolerance) * min_separation);
  EXPECT_LE(result.shortfall, settings.overlap_tolerance);
  settings.overlap_tolerance = 0.5;
  const double loose = open(settings, result);
  EXPECT_GE(loose, 0.5 * min_separation);
  EXPECT_LT(loose, 0.9 * exact);
  settings = ContactSolver::Settings();
  settings.max_overlap_sweeps = 1;
  const double one_sweep = open(settings, result);
  EXPECT_EQ(result.shortfall, 1.0);    // before its only sweep, the overlaps did not open at all
  EXPECT_LT(one_sweep, 0.9 * exact);
}
