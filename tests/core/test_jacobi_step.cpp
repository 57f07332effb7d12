// A Jacobi step: impulses from one state, summed per body and applied once.
#include "ag_jacobi_step.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

using namespace ActiveGrain;
using namespace ActiveGrain::testing;

TEST(JacobiStep, PushedImpulsesMoveEachBodyOnceAsTheirSum)
{
  // A wall (0) and three bodies: island contacts wall-1, 1-2 and wall-1 again, and a contact
  // 3-wall outside the island.
  std::mt19937 rng(31);
  std::vector<RigidBodyState> bodies{RigidBodyState::wall(Vec3(0, 0, 0.1)), random_body(rng), random_body(rng),
                                     random_body(rng)};
  std::vector<SolverContact> contacts(4);
  const int ends[4][2] = {{3, 0}, {0, 1}, {1, 2}, {0, 1}};
  for (int i = 0; i < 4; ++i) {
    contacts[i].body1 = ends[i][0];
    contacts[i].body2 = ends[i][1];
    contacts[i].r1 = random_unit(rng) * 0.5;
    contacts[i].r2 = random_unit(rng) * 0.5;
  }
  const std::vector<int> island{1, 2, 3};
  JacobiStep step;
  step.resize(bodies.size());
  step.start_island(bodies, contacts, island);
  EXPECT_EQ(step.island_bodies(), (std::vector<int>{0, 1, 2}));

  // Shares: body 1 carries all three island contacts, body 2 one; a wall counts as 1.
  step.clear_counts();
  for (std::size_t k = 0; k < island.size(); ++k) step.count(k);
  EXPECT_EQ(step.share(0), 3);
  EXPECT_EQ(step.share(1), 3);
  step.clear_counts();
  step.count(1);
  EXPECT_EQ(step.share(0), 1);
  EXPECT_EQ(step.share(1), 1);

  // Contacts 0 and 1 of the island push; contact 2 does not.
  const std::vector<RigidBodyState> start = bodies;
  std::vector<RigidBodyState> expected = bodies;
  const Vec3 J0 = random_unit(rng), J1 = random_unit(rng) * 2.0;
  for (const auto &[k, J] : {std::pair<int, Vec3>{0, J0}, {1, J1}}) {
    const SolverContact &c = contacts[island[k]];
    expected[c.body1].apply_impulse_at_arm(-J, c.r1);
    expected[c.body2].apply_impulse_at_arm(J, c.r2);
  }
  step.start_step();
  step.add(0, J0);
  step.add(1, J1);
  EXPECT_EQ(step.pushed(), (std::vector<int>{0, 1}));
  step.push();
  EXPECT_EQ(norm(contacts[1].impulse - J0), 0.0);
  EXPECT_EQ(norm(contacts[2].impulse - J1), 0.0);
  EXPECT_EQ(norm(contacts[3].impulse), 0.0);
  EXPECT_EQ(norm(bodies[1].v - start[1].v), 0.0);    // not moved until move_bodies()
  step.move_bodies();
  for (int b = 0; b < 4; ++b) {
    EXPECT_NEAR(norm(bodies[b].v - expected[b].v), 0.0, 1e-14) << "body " << b;
    EXPECT_NEAR(norm(bodies[b].omega - expected[b].omega), 0.0, 1e-13) << "body " << b;
  }
  EXPECT_EQ(norm(bodies[0].v - Vec3(0, 0, 0.1)), 0.0);    // the wall does not move
  // Every island contact touches a moved body; after forget_moved() none does.
  for (std::size_t k = 0; k < island.size(); ++k) EXPECT_TRUE(step.moved(k));
  step.forget_moved();
  for (std::size_t k = 0; k < island.size(); ++k) EXPECT_FALSE(step.moved(k));
  // The sums start from zero again: a second step moves only by its own impulse.
  RigidBodyState alone = bodies[1];
  const RigidBodyState untouched = bodies[2];
  alone.apply_impulse_at_arm(J0, contacts[3].r2);
  step.start_step();
  step.add(2, J0);
  step.push();
  step.move_bodies();
  EXPECT_EQ(norm(bodies[1].v - alone.v), 0.0);
  EXPECT_EQ(norm(bodies[1].omega - alone.omega), 0.0);
  EXPECT_EQ(norm(bodies[2].v - untouched.v), 0.0);
  EXPECT_EQ(norm(contacts[3].impulse - J0), 0.0);
  EXPECT_EQ(norm(contacts[1].impulse - J0), 0.0);
}
