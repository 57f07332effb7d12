// The frictional restitutive impulse between two rigid bodies at one contact (SPEC section 4):
// Stronge's model with static Coulomb friction. No LAMMPS in here.
//
// Restitution definition: Stronge's energetic coefficient e. The work done by the normal impulse
// during restitution is -e^2 times the work it does during compression. When the slip direction
// stays constant through the impact (or the contact sticks throughout), this equals Newton's and
// Poisson's definitions and the closed-form stick/slide impulse is used. When slip would stop,
// reverse or turn during the impact, the impact is integrated in impulse space (normal impulse as
// the independent variable), which keeps friction dissipative at every instant. No collision can
// increase kinetic energy.
#pragma once

#include "ag_rigid_body.h"

namespace ActiveGrain {

struct ContactMaterial {
  double e = 0.0;     // restitution (Stronge's energetic coefficient), in [0, 1]
  double mu = 0.0;    // static Coulomb friction coefficient, >= 0
};

// The matrix K with du = K J for an impulse J on body 2 (-J on body 1) at a contact whose lever
// arms are r1 = c - x1 and r2 = c - x2:
// K = (1/m1 + 1/m2) 1 - [r1]x I1^-1 [r1]x - [r2]x I2^-1 [r2]x.
Mat3 contact_matrix(const RigidBodyState &body1, const Vec3 &r1, const RigidBodyState &body2,
                    const Vec3 &r2);

// Change of kinetic energy of both bodies when impulse J (on body 2) acts at a contact with
// relative velocity u and matrix K: J.(u + K J / 2).
double impulse_energy_change(const Mat3 &K, const Vec3 &u, const Vec3 &J);

// The contact law on relative velocity u (body 2 minus body 1 at the contact), unit normal n from
// body 1 to body 2. target_separation (>= 0) is the normal velocity restitution aims for: for an
// isolated impact e * max(0, -u.n); a multi-contact solver passes e times the pre-solve approach
// speed, or a minimum separation velocity. Restitution (Stronge) returns at most the work of
// compression; if the contact still separates slower than target_separation after it, the
// normal impulse continues to it, so the law is continuous where the target crosses the
// approach speed. Returns the impulse on body 2; J.n >= 0.
Vec3 contact_law_impulse(const Mat3 &K, const Vec3 &u, const Vec3 &n, const ContactMaterial &material,
                         double target_separation);

// The same contact inside a coupled solve (contacts sharing a body): the impulse that leaves the
// contact with normal velocity target_separation (none if u.n already reaches it) and either no
// slip, if the friction cone allows, or Coulomb friction mu j_n against the final slip. It
// depends on u only through the conditions on the final velocity, so projected Gauss-Seidel
// sweeps of it converge to body velocities that do not depend on their order. It equals
// contact_law_impulse wherever the slip keeps its direction through the impact.
// K_inverse: K's inverse, computed once per solve.
Vec3 coupled_contact_impulse(const Mat3 &K, const Mat3 &K_inverse, const Vec3 &u, const Vec3 &n,
                             const ContactMaterial &material, double target_separation);

// One isolated collision between body 1 and body 2 at contact point c with normal n (1 -> 2).
// Returns the impulse J on body 2 (-J on body 1); zero if the bodies separate at c.
Vec3 collision_impulse(const RigidBodyState &body1, const RigidBodyState &body2, const Vec3 &point,
                       const Vec3 &n, const ContactMaterial &material);

}    // namespace ActiveGrain
