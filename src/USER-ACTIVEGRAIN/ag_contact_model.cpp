#include "ag_contact_model.h"

#include "ag_impulse.h"

#include <charconv>
#include <cmath>

namespace ActiveGrain {

namespace {

// A coefficient as LAMMPS's messages print a number: the shortest text that reads back to it.
std::string shortest(double value)
{
  char text[32];
  const auto end = std::to_chars(text, text + sizeof(text), value).ptr;
  return std::string(text, end);
}

}    // namespace

std::string NormalModel::invalid() const
{
  if (!(e >= 0.0 && e <= 1.0)) return "restitution coefficient e = " + shortest(e) + " must be in [0, 1]";
  return {};
}

Vec3 TangentialModel::friction(const TangentialStep &step, const Vec3 &u, double dp, bool &stuck) const
{
  return step.friction(u, mu, dp, stuck);
}

std::string TangentialModel::invalid() const
{
  if (!(mu >= 0.0)) return "friction coefficient mu = " + shortest(mu) + " must be >= 0";
  return {};
}

void ContactModel::to_coeffs(double *coeffs) const
{
  coeffs[0] = normal.e;
  coeffs[1] = tangential.mu;
}

ContactModel ContactModel::from_coeffs(const double *coeffs)
{
  ContactModel model;
  model.normal.e = coeffs[0];
  model.tangential.mu = coeffs[1];
  return model;
}

ContactModel ContactModel::mixed(const ContactModel &a, const ContactModel &b)
{
  double ca[NUM_COEFFS], cb[NUM_COEFFS], mean[NUM_COEFFS];
  a.to_coeffs(ca);
  b.to_coeffs(cb);
  for (int k = 0; k < NUM_COEFFS; ++k) mean[k] = std::sqrt(ca[k] * cb[k]);
  return from_coeffs(mean);
}

std::string ContactModel::invalid() const
{
  const std::string normal_invalid = normal.invalid();
  return normal_invalid.empty() ? tangential.invalid() : normal_invalid;
}

}    // namespace ActiveGrain
