// The contact law as sub-models, as LAMMPS's GranularModel has them (docs/model.rst, contacts):
// a normal law, Stronge's energetic restitution, and a tangential law, Coulomb friction that
// sticks whenever its cone allows. Every algorithm (the isolated impact, the compliant impact, the
// resting solve, the overlap correction, the energy ledger) asks them what a contact does; each
// sub-model checks its own coefficients. No LAMMPS in here.
#pragma once

#include "ag_math.h"

#include <algorithm>
#include <string>
#include <type_traits>

namespace ActiveGrain {

class TangentialStep;

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

struct TangentialModel {
  double mu = 0.0;    // static Coulomb friction coefficient

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

  // Its coefficients in one fixed order (pair_coeff, restart files), and their keywords.
  static constexpr int NUM_COEFFS = 2;
  static constexpr const char *COEFF_NAMES[NUM_COEFFS] = {"e", "mu"};
  void to_coeffs(double *coeffs) const;
  static ContactModel from_coeffs(const double *coeffs);
  // Unlike types without a pair_coeff of their own: geometric means of each coefficient.
  static ContactModel mixed(const ContactModel &a, const ContactModel &b);
  std::string invalid() const;    // the first sub-model's complaint, or empty
};

// Contacts travel between ranks as bytes.
static_assert(std::is_trivially_copyable<ContactModel>::value, "ContactModel is sent as bytes");

}    // namespace ActiveGrain
