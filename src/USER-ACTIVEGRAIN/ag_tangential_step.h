// What a step of friction needs of a contact: its tangent plane, and the impulse that stops its
// slip. The sticking law (ag_contact_model.h) and the integrated impacts (ag_impulse.h,
// ag_compliant_impact.h) step with it. No LAMMPS in here.
#pragma once

#include "ag_math.h"

namespace ActiveGrain {

// A contact's tangent plane as a step of friction sees it: the frame's tangents, K restricted to
// the plane and inverted (symmetric), and the tangential components of K n.
struct TangentPlane {
  Vec3 tangent1, tangent2;
  double inv11 = 0, inv12 = 0, inv22 = 0, kn1 = 0, kn2 = 0;
};

// The tangential part of an impact at a fixed contact, integrated in small steps of normal
// impulse (an integrated impact, or one contact of a compliant multi-contact impact): what a
// step needs to stop the slip (K restricted to the tangent plane, inverted, and the tangential
// velocity change per unit normal impulse).
class TangentialStep {
 public:
  TangentialStep() = default;
  TangentialStep(const Mat3 &K, const Vec3 &n);

  // Tangential over normal impulse that keeps a stuck contact stuck: it stays stuck while this
  // is within the friction cone.
  double sticking_ratio() const { return stick_ratio; }

  // Tangential impulse over a step with normal impulse dp that stops the slip of u, if the
  // friction cone allows it (stuck = true); otherwise the largest friction impulse mu dp
  // against the slip (the current one, plus what dp drives within the step).
  Vec3 friction(const Vec3 &u, double mu, double dp, bool &stuck) const;
  const TangentPlane &plane() const { return tangent_plane; }

 private:
  // The tangential impulse that stops a slip of components -b1, -b2 along the tangents.
  Vec3 stick(double b1, double b2) const;

  TangentPlane tangent_plane;
  double stick_ratio = 0;    // sticking_ratio()
};

}    // namespace ActiveGrain
