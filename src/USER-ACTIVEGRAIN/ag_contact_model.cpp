#include "ag_contact_model.h"

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
  if (compliant() && !(stiffness_ratio > 0.0 && std::isfinite(stiffness_ratio)))
    return "tangential compliant stiffness ratio = " + shortest(stiffness_ratio) + " must be > 0";
  return {};
}

void ContactModel::to_coeffs(double *coeffs) const
{
  coeffs[0] = normal.e;
  coeffs[1] = tangential.mu;
  coeffs[2] = tangential.compliant() ? 1.0 : 0.0;
  coeffs[3] = tangential.stiffness_ratio;
}

ContactModel ContactModel::from_coeffs(const double *coeffs)
{
  ContactModel model;
  model.normal.e = coeffs[0];
  model.tangential.mu = coeffs[1];
  model.tangential.law = coeffs[2] != 0.0 ? TangentialLaw::COMPLIANT : TangentialLaw::STICK;
  model.tangential.stiffness_ratio = coeffs[3];
  return model;
}

// The laws mix too: a pair is compliant if either type is, with the geometric mean of the ratios
// of the compliant ones.
ContactModel ContactModel::mixed(const ContactModel &a, const ContactModel &b)
{
  ContactModel mean;
  mean.normal.e = std::sqrt(a.normal.e * b.normal.e);
  mean.tangential.mu = std::sqrt(a.tangential.mu * b.tangential.mu);
  const TangentialModel &ta = a.tangential, &tb = b.tangential;
  if (ta.compliant() || tb.compliant()) {
    mean.tangential.law = TangentialLaw::COMPLIANT;
    mean.tangential.stiffness_ratio = !ta.compliant() ? tb.stiffness_ratio
        : !tb.compliant()                             ? ta.stiffness_ratio
                                                      : std::sqrt(ta.stiffness_ratio * tb.stiffness_ratio);
  }
  return mean;
}

std::string ContactModel::invalid() const
{
  const std::string normal_invalid = normal.invalid();
  return normal_invalid.empty() ? tangential.invalid() : normal_invalid;
}

}    // namespace ActiveGrain
