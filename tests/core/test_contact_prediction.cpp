// Predictive contact: which gaps close within a step, when, and what the law must see.
#include "ag_contact_prediction.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

using namespace ActiveGrain;

namespace {
const Vec3 UP(0, 0, 1);    // normal from body 1 (below) to body 2
constexpr double DT = 1e-4;
constexpr double BETA = 0.2;
}    // namespace

TEST(ContactPrediction, GapClosingAtConstantSpeedClosesWhenItsTravelCoversIt)
{
  const double gap = 2e-7, speed = 4e-3;    // covered after 5e-5 s, half the step
  const ContactPrediction p = predict_contact(gap, Vec3(0, 0, -speed), UP, DT, BETA, 0.0, Vec3());
  ASSERT_TRUE(p.closes);
  EXPECT_DOUBLE_EQ(p.time_to_contact, gap / speed);
  EXPECT_DOUBLE_EQ(p.approach, speed);
  EXPECT_EQ(p.min_separation, 0.0);
  EXPECT_EQ(norm(p.gain), 0.0);
}

TEST(ContactPrediction, GapThatTheStepDoesNotCoverStaysOpen)
{
  const double speed = 4e-3;
  EXPECT_FALSE(predict_contact(1.01 * speed * DT, Vec3(0, 0, -speed), UP, DT, BETA, 0.0, Vec3()).closes);
  EXPECT_TRUE(predict_contact(0.99 * speed * DT, Vec3(0, 0, -speed), UP, DT, BETA, 0.0, Vec3()).closes);
  EXPECT_FALSE(predict_contact(1e-9, Vec3(0, 0, speed), UP, DT, BETA, 0.0, Vec3()).closes);    // parting
  // Sliding along the surface does not close a gap.
  EXPECT_FALSE(predict_contact(1e-9, Vec3(1.0, 0, 0), UP, DT, BETA, 0.0, Vec3()).closes);
}

TEST(ContactPrediction, OverlapMustOpenAtBetaTimesOverlapPerStep)
{
  const double overlap = 3e-8;
  const ContactPrediction p = predict_contact(-overlap, Vec3(), UP, DT, BETA, 0.0, Vec3());
  ASSERT_TRUE(p.closes);
  EXPECT_EQ(p.time_to_contact, 0.0);
  EXPECT_DOUBLE_EQ(p.min_separation, BETA * overlap / DT);
}

TEST(ContactPrediction, AnOverlapWithinTheSlopIsTouchingAndOnlyTheExcessIsPushed)
{
  const double slop = 2e-8;
  const ContactPrediction within = predict_contact(-0.5 * slop, Vec3(), UP, DT, BETA, slop, Vec3());
  ASSERT_TRUE(within.closes);
  EXPECT_EQ(within.time_to_contact, 0.0);
  EXPECT_EQ(within.min_separation, 0.0);
  const double overlap = 3e-8;
  const ContactPrediction beyond = predict_contact(-overlap, Vec3(), UP, DT, BETA, slop, Vec3());
  EXPECT_DOUBLE_EQ(beyond.min_separation, BETA * (overlap - slop) / DT);
}

TEST(ContactPrediction, GravityActsUntilTheContactCloses)
{
  // A bead falling onto a resting plate (body 1): the relative acceleration of body 2 is -g.
  const Vec3 g(0, 0, -9.81);
  const double speed = 0.01, gap = 0.3 * speed * DT;
  const ContactPrediction p = predict_contact(gap, Vec3(0, 0, -speed), UP, DT, BETA, 0.0, g);
  ASSERT_TRUE(p.closes);
  // Velocities are half a step old: the approach at the step's start includes g dt/2.
  const double approach_now = speed + 9.81 * 0.5 * DT;
  EXPECT_DOUBLE_EQ(p.time_to_contact, gap / approach_now);
  EXPECT_NEAR(p.gain.z, -9.81 * (0.5 * DT + p.time_to_contact), 1e-18);
  EXPECT_NEAR(p.approach, speed + 9.81 * (0.5 * DT + p.time_to_contact), 1e-15);
}

TEST(ContactPrediction, AWallsAccelerationCountsAgainstTheContact)
{
  // The plate (body 1) accelerates upwards into a bead at rest relative to it: the bead's
  // approach grows by the plate's acceleration times the time to contact.
  const Vec3 plate(0, 0, 300.0);
  const double speed = 0.02, gap = 0.5 * speed * DT;
  const ContactPrediction p = predict_contact(gap, Vec3(0, 0, -speed), UP, DT, BETA, 0.0, Vec3(), plate);
  ASSERT_TRUE(p.closes);
  EXPECT_DOUBLE_EQ(p.gain.z, -300.0 * p.time_to_contact);
  EXPECT_DOUBLE_EQ(p.approach, speed + 300.0 * p.time_to_contact);
}

TEST(ContactPrediction, TheCheapTestsNeverRuleOutAContactThatCloses)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int closing = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Vec3 n = ActiveGrain::testing::random_unit(rng);
    const Vec3 u = ActiveGrain::testing::random_unit(rng) * (0.05 * (1.0 + U(rng)));
    const double gap = 5e-6 * U(rng);
    const ContactPrediction p = predict_contact(gap, u, n, DT, BETA, 0.0, Vec3());
    if (!p.closes) continue;
    ++closing;
    EXPECT_TRUE(gap_may_close(gap, u, 0.0, DT));
    EXPECT_FALSE(stays_open(gap, u, n, DT));
  }
  EXPECT_GT(closing, 1000);
}

TEST(ContactPrediction, SpinLetsAGapCloseThatTheCentresAloneCannot)
{
  // Centres at rest, but surfaces spinning at 1 m/s can close a gap of 0.5 mm in 1e-3 s.
  EXPECT_FALSE(gap_may_close(5e-4, Vec3(), 0.0, 1e-3));
  EXPECT_TRUE(gap_may_close(5e-4, Vec3(), 1.0, 1e-3));
  EXPECT_TRUE(gap_may_close(-1e-9, Vec3(), 0.0, 1e-3));    // an overlap always may
}
