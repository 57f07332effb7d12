// The compliant impact's stages alone: the spring law, free flight, the plastic take-back.
#include "ag_compliant_impact.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace ActiveGrain;
using namespace ActiveGrain::testing;

namespace {

// A contact as the contact solver prepares one of an island.
SolverContact island_contact(const std::vector<RigidBodyState> &bodies, int body1, int body2, const Vec3 &point,
                             const Vec3 &n, const ContactModel &model)
{
  SolverContact c;
  c.body1 = body1;
  c.body2 = body2;
  c.r1 = point - bodies[body1].com;
  c.r2 = point - bodies[body2].com;
  c.n = n;
  c.model = model;
  c.K = contact_matrix(bodies[body1], c.r1, bodies[body2], c.r2);
  c.knn = dot(c.n, c.K * c.n);
  c.tangential = TangentialStep(c.K, c.n);
  return c;
}

// A bead falling at 1 between a floor (contact 0) and a lid (contact 1), touching both.
struct Sandwich {
  std::vector<RigidBodyState> bodies;
  std::vector<SolverContact> contacts;
  std::vector<int> island{0, 1};

  explicit Sandwich(double e)
  {
    bodies.push_back(RigidBodyState::wall(Vec3()));
    bodies.push_back(RigidBodyState::wall(Vec3()));
    bodies.push_back(RigidBodyState::sphere(1.0, 0.5, Vec3(0, 0, 0.5), Vec3(0, 0, -1), Vec3()));
    contacts.push_back(island_contact(bodies, 0, 2, Vec3(), Vec3(0, 0, 1), {e, 0.2}));
    contacts.push_back(island_contact(bodies, 1, 2, Vec3(0, 0, 1), Vec3(0, 0, -1), {e, 0.2}));
  }
};

}    // namespace

TEST(CompliantImpact, SpringUnloadsAlongItsLineAndReloadsBeyondItsPeak)
{
  const double e = 0.5;
  CompliantImpact::Spring spring;
  spring.e = e;
  spring.compress(1.0);
  EXPECT_EQ(spring.force(), 1.0);
  EXPECT_EQ(spring.stiffness(), 1.0);
  spring.compress(-0.125);    // unloads with stiffness 1/e^2 towards zero force at 1 - e^2
  EXPECT_TRUE(spring.unloading);
  EXPECT_EQ(spring.stiffness(), 1.0 / (e * e));
  EXPECT_DOUBLE_EQ(spring.force(), 1.0 - 0.125 / (e * e));
  EXPECT_EQ(spring.offset(), 1.0 - e * e);
  spring.compress(-0.25);
  EXPECT_EQ(spring.force(), 0.0);
  spring.compress(0.5);    // past its peak again: loading with unit stiffness
  EXPECT_FALSE(spring.unloading);
  EXPECT_EQ(spring.force(), 1.125);
  // A plastic spring unloads at once.
  CompliantImpact::Spring plastic;
  plastic.compress(1.0);
  plastic.compress(-1e-9);
  EXPECT_EQ(plastic.force(), 0.0);
  EXPECT_EQ(plastic.offset(), 1.0);
}

TEST(CompliantImpact, FreeFlightReachesTheNextContact)
{
  // The bead rebounds from the floor: once the floor's spring is unloaded, the lid's (left
  // behind by the floor's compression) is the next contact, and the bodies fly up to it.
  Sandwich sandwich(0.5);
  const SolverSettings settings;
  CompliantImpact impact;
  impact.resize(sandwich.bodies.size());
  impact.start(sandwich.bodies, sandwich.contacts, sandwich.island, settings);
  CompliantImpact::Engagement found = impact.classify();
  for (int substeps = 0; found.engaged && substeps < 10000; ++substeps) {
    const double dtau = impact.substep_size(found.changed);
    impact.kick(dtau);
    impact.take_back();
    impact.drift(dtau);
    found = impact.classify();
  }
  ASSERT_FALSE(found.engaged);
  ASSERT_FALSE(impact.ended(found));
  ASSERT_TRUE(std::isfinite(found.to_contact));
  const double lid_gap = impact.spring(1).offset() - impact.spring(1).compression;
  ASSERT_GT(lid_gap, 0.0);
  const double floor_before = impact.spring(0).compression, floor_un = dot(impact.velocity(0), Vec3(0, 0, 1));
  const Vec3 bead_velocity = sandwich.bodies[2].v;

  impact.fly(found.to_contact);
  EXPECT_NEAR(impact.spring(1).compression, impact.spring(1).offset(), 1e-15 * lid_gap);
  EXPECT_EQ(impact.spring(0).compression, floor_before - floor_un * found.to_contact);
  EXPECT_EQ(norm(sandwich.bodies[2].v - bead_velocity), 0.0);    // flight changes no velocity
  const CompliantImpact::Engagement next = impact.classify();
  EXPECT_TRUE(next.engaged || next.to_contact <= 1e-15 * found.to_contact);
}

TEST(CompliantImpact, FreeFlightOfAnUnderflowingGapReachesTheContact)
{
  // An elastic lid spring (offset 0) a denormal short of zero compression, approached at 3: the
  // flight time underflows to zero, and the flight still ends at the contact (not flying forever).
  Sandwich sandwich(1.0);
  sandwich.bodies[2].v = Vec3(0, 0, 3);
  const SolverSettings settings;
  CompliantImpact impact;
  impact.resize(sandwich.bodies.size());
  impact.start(sandwich.bodies, sandwich.contacts, sandwich.island, settings);
  impact.spring(1).peak = 1.0;
  impact.spring(1).unloading = true;
  impact.spring(1).compression = -std::numeric_limits<double>::denorm_min();
  const CompliantImpact::Engagement found = impact.classify();
  ASSERT_FALSE(found.engaged);
  ASSERT_FALSE(impact.ended(found));
  ASSERT_EQ(found.to_contact, 0.0);
  impact.fly(found.to_contact);
  EXPECT_EQ(impact.spring(1).compression, 0.0);
  EXPECT_EQ(impact.spring(0).compression, 0.0);
  EXPECT_TRUE(impact.classify().engaged);
}

TEST(CompliantImpact, TakeBackLeavesAPlasticContactAtRest)
{
  // A kick far too long for a plastic contact turns its approach into separation; the take-back
  // removes the part past its peak: the contact leaves at rest in the normal direction (with
  // friction, any bodies). An elastic contact keeps its kick.
  std::mt19937 rng(29);
  int overshot = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const double e = trial % 2 ? 0.0 : 0.5;
    std::vector<RigidBodyState> bodies{RigidBodyState::wall(Vec3()), random_body(rng)};
    const Vec3 point = bodies[1].com + random_unit(rng) * 0.5;
    Vec3 n = random_unit(rng);
    if (dot(bodies[1].velocity_at(point), n) > 0) n = -n;
    std::vector<SolverContact> contacts{island_contact(bodies, 0, 1, point, n, {e, 0.5})};
    const std::vector<int> island{0};
    const SolverSettings settings;
    CompliantImpact impact;
    impact.resize(bodies.size());
    impact.start(bodies, contacts, island, settings);
    const double approach = -dot(impact.velocity(0), n);
    impact.spring(0).compress(1.0);
    ASSERT_TRUE(impact.classify().loaded);
    // Force 1 over half of dtau (the first kick): four times the normal impulse that would stop
    // the approach without friction.
    const double dtau = 8.0 * approach / contacts[0].knn;
    impact.kick(dtau);
    const double after_kick = dot(relative_velocity(bodies, contacts[0]), n);
    if (after_kick <= 0.0) continue;    // friction held the normal velocity back
    ++overshot;
    impact.take_back();
    const double after = dot(relative_velocity(bodies, contacts[0]), n);
    if (e == 0.0) {
      EXPECT_NEAR(after, 0.0, 1e-12 * (1.0 + approach)) << "trial " << trial;
      EXPECT_TRUE(impact.spring(0).unloading);
    } else {
      EXPECT_EQ(after, after_kick) << "trial " << trial;
    }
  }
  EXPECT_GT(overshot, 150);
}

TEST(CompliantImpact, SolveRunsTheStagesToTheEnd)
{
  // A bead landing on a floor (a second contact at its side stays clear) rebounds at e. Between
  // floor and lid it never settles: each spring keeps the plastic offset of its first load and
  // reloads elastically along its unloading line, so the bead rattles between them until the
  // sub-steps run out (-1).
  for (double e : {0.0, 0.5, 1.0}) {
    std::vector<RigidBodyState> bodies{RigidBodyState::wall(Vec3()),
                                       RigidBodyState::sphere(1.0, 0.5, Vec3(0, 0, 0.5), Vec3(0, 0, -1), Vec3())};
    std::vector<SolverContact> contacts{island_contact(bodies, 0, 1, Vec3(), Vec3(0, 0, 1), {e, 0.2}),
                                        island_contact(bodies, 0, 1, Vec3(0.5, 0, 0.5), Vec3(-1, 0, 0), {e, 0.2})};
    const std::vector<int> island{0, 1};
    const SolverSettings settings;
    CompliantImpact impact;
    impact.resize(bodies.size());
    EXPECT_GT(impact.solve(bodies, contacts, island, settings), 0) << "e " << e;
    EXPECT_NEAR(bodies[1].v.z, e, 3.0 / settings.resolution) << "e " << e;
    EXPECT_EQ(norm(contacts[1].impulse), 0.0) << "e " << e;
  }
  Sandwich sandwich(0.5);
  SolverSettings settings;
  settings.max_substeps = 5000;
  CompliantImpact impact;
  impact.resize(sandwich.bodies.size());
  EXPECT_EQ(impact.solve(sandwich.bodies, sandwich.contacts, sandwich.island, settings), -1);
  EXPECT_LT(sandwich.contacts[1].impulse.z, 0.0);    // the lid took part (n = -z: it pushes down)
}
