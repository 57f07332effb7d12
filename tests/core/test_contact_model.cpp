// The contact model's sub-models: what they decide for a contact, what they accept, and the
// coefficients they travel as (restart files, mixing).
#include "ag_contact_model.h"
#include "ag_impulse.h"

#include <gtest/gtest.h>

using namespace ActiveGrain;

TEST(ContactModel, NormalTargetIsRestitutionOfTheApproachOrTheOverlapsPush)
{
  const NormalModel normal{0.5};
  EXPECT_DOUBLE_EQ(normal.target_separation(2.0, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(normal.target_separation(2.0, 1.5), 1.5);    // the overlap's push is larger
  EXPECT_DOUBLE_EQ(normal.target_separation(-2.0, 0.0), 0.0);   // separating: nothing to restitute
  EXPECT_TRUE(NormalModel{0.0}.plastic());
  EXPECT_FALSE(normal.plastic());
}

// The sticking law's friction is the contact's tangential step with the model's mu: it stops a
// slip the cone allows, and slides at mu dp against a larger one.
TEST(ContactModel, TangentialFrictionSticksWithinTheConeAndSlidesBeyond)
{
  const RigidBodyState plate = RigidBodyState::wall(Vec3());
  const RigidBodyState bead = RigidBodyState::sphere(1.0, 1.0, Vec3(0, 0, 1), Vec3(), Vec3());
  const Vec3 n(0, 0, 1);
  const TangentialStep step(contact_matrix(plate, Vec3(), bead, Vec3(0, 0, -1)), n);
  const TangentialModel friction{0.5};
  const Vec3 slip(0.1, 0, 0);
  bool stuck = false;
  const Vec3 sticking = friction.friction(step, slip, 1.0, stuck);
  EXPECT_TRUE(stuck);
  EXPECT_NEAR(sticking.x, -0.1 / 3.5, 1e-15);    // a sphere's K_tt = (1 + 5/2) / m
  const Vec3 sliding = friction.friction(step, slip * 100.0, 1.0, stuck);
  EXPECT_FALSE(stuck);
  EXPECT_DOUBLE_EQ(sliding.x, -friction.limit(1.0));
}

TEST(ContactModel, EachSubModelRefusesItsOwnBadCoefficients)
{
  EXPECT_EQ(ContactModel({{0.5}, {0.2}}).invalid(), "");
  EXPECT_EQ(ContactModel({{1.5}, {0.2}}).invalid(), "restitution coefficient e = 1.5 must be in [0, 1]");
  EXPECT_EQ(ContactModel({{-0.25}, {0.2}}).invalid(), "restitution coefficient e = -0.25 must be in [0, 1]");
  EXPECT_EQ(ContactModel({{0.5}, {-1}}).invalid(), "friction coefficient mu = -1 must be >= 0");
  EXPECT_NE(NormalModel{std::nan("")}.invalid(), "");
}

TEST(ContactModel, CoefficientsRoundTripAndMixAsGeometricMeans)
{
  const ContactModel a{{0.36}, {0.04}}, b{{0.25}, {0.09}};
  double coeffs[ContactModel::NUM_COEFFS];
  a.to_coeffs(coeffs);
  const ContactModel back = ContactModel::from_coeffs(coeffs);
  EXPECT_EQ(back.normal.e, a.normal.e);
  EXPECT_EQ(back.tangential.mu, a.tangential.mu);
  const ContactModel mixed = ContactModel::mixed(a, b);
  EXPECT_DOUBLE_EQ(mixed.normal.e, 0.3);
  EXPECT_DOUBLE_EQ(mixed.tangential.mu, 0.06);
  EXPECT_STREQ(ContactModel::COEFF_NAMES[0], "e");
  EXPECT_STREQ(ContactModel::COEFF_NAMES[1], "mu");
}

TEST(ContactModel, TheCompliantLawNeedsAPositiveRatioAndMixesWithTheStickingOne)
{
  ContactModel soft{{0.5}, {0.2}};
  soft.tangential.law = TangentialLaw::COMPLIANT;
  soft.tangential.stiffness_ratio = 0.0;
  EXPECT_EQ(soft.invalid(), "tangential compliant stiffness ratio = 0 must be > 0");
  soft.tangential.stiffness_ratio = 0.64;
  EXPECT_EQ(soft.invalid(), "");
  double coeffs[ContactModel::NUM_COEFFS];
  soft.to_coeffs(coeffs);
  EXPECT_TRUE(ContactModel::from_coeffs(coeffs).tangential.compliant());
  EXPECT_EQ(ContactModel::from_coeffs(coeffs).tangential.stiffness_ratio, 0.64);
  const ContactModel rigid{{0.5}, {0.2}}, both = ContactModel::mixed(soft, rigid);
  EXPECT_TRUE(both.tangential.compliant());    // in series with a rigid one, the soft one counts
  EXPECT_DOUBLE_EQ(both.tangential.stiffness_ratio, 0.64);
  ContactModel other = soft;
  other.tangential.stiffness_ratio = 0.25;
  EXPECT_DOUBLE_EQ(ContactModel::mixed(soft, other).tangential.stiffness_ratio, 0.4);
  EXPECT_FALSE(ContactModel::mixed(rigid, rigid).tangential.compliant());
}
