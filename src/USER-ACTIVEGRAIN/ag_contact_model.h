// The contact law as sub-models, as LAMMPS's GranularModel has them (docs/model.rst, contacts):
// a normal law, Stronge's energetic restitution, and a tangential law with Coulomb friction:
// sticking (a contact that the cone allows to stop slipping stops, storing nothing) or compliant
// (a tangential spring at the contact point stores the slip while it sticks and gives it back, as
// in Stronge's impacts of rough compliant bodies; ag_compliant_impact.h). Every algorithm (the isolated impact, the compliant impact, the
// resting solve, the overlap correction, the energy ledger) asks them what a contact does; each
// sub-model checks its own coefficients. No LAMMPS in here.
#pragma once

#include "ag_math.h"
#include "ag_tangential_step.h"

#include <algorithm>
#include <string>
#include <type_traits>

namespace ActiveGrain {

struct NormalModel {
  double e = 0.0;    // Stronge's energetic restitution: the restitution's work is e^2 of the compression's

  // The normal velocity a contact that approaches at `approach` (> 0: approaching) leaves with:
  // e times the approach, or an overlap's minimum separation velocity if that is larger.
  double target_separation(double approach, double min_separation) const
  {
    return std::max(e * std::max(0.0, approach), min_separation);
  }
  bool plastic() const { return e == 0.0; }
  std::string invalid() const;    // what is wrong with its coefficients, or empty
};

enum class TangentialLaw { STICK, COMPLIANT };

struct TangentialModel {
  double mu = 0.0;    // static Coulomb friction coefficient
  TangentialLaw law = TangentialLaw::STICK;
  // Compliant: the tangential spring's stiffness over the normal spring's while it loads (for
  // elastic spheres of one material, Mindlin's 2 (1 - nu) / (2 - nu)).
  double stiffness_ratio = 0.0;

  bool compliant() const { return law == TangentialLaw::COMPLIANT; }

  // The tangential impulse over a step of normal impulse dp at relative velocity u, as `step`
  // (the contact's tangent plane) integrates it: the one that stops the slip if the cone allows
  // (stuck = true), else mu dp against the slip.
  Vec3 friction(const TangentialStep &step, const Vec3 &u, double dp, bool &stuck) const;
  // The radius of the friction cone at normal impulse pn.
  double limit(double pn) const { return mu * pn; }
  std::string invalid() const;
};

struct ContactModel {
  NormalModel normal;
  TangentialModel tangential;

  // Its coefficients in one fixed order (restart files; the first two are pair_coeff's), and
  // their names (fix adapt's; the law is 0 for stick, 1 for compliant).
  static constexpr int NUM_COEFFS = 4;
  static constexpr const char *COEFF_NAMES[NUM_COEFFS] = {"e", "mu", "tangential", "stiffness_ratio"};
  void to_coeffs(double *coeffs) const;
  static ContactModel from_coeffs(const double *coeffs);
  // Unlike types without a pair_coeff of their own: geometric means of each coefficient.
  static ContactModel mixed(const ContactModel &a, const ContactModel &b);
  std::string invalid() const;    // the first sub-model's complaint, or empty
};

// Contacts travel between ranks as bytes.
static_assert(std::is_trivially_copyable<ContactModel>::value, "ContactModel is sent as bytes");

}    // namespace ActiveGrain
