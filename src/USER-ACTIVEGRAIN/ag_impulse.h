// The frictional restitutive impulse between two rigid bodies at one contact (docs/model.rst, contacts):
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

#include "ag_contact_model.h"
#include "ag_rigid_body.h"

namespace ActiveGrain {

// The matrix K with du = K J for an impulse J on body 2 (-J on body 1) at a contact whose lever
// arms are r1 = c - x1 and r2 = c - x2:
// K = (1/m1 + 1/m2) 1 - [r1]x I1^-1 [r1]x - [r2]x I2^-1 [r2]x.
Mat3 contact_matrix(const RigidBodyState &body1, const Vec3 &r1, const RigidBodyState &body2,
                    const Vec3 &r2);

// Change of kinetic energy of both bodies when impulse J (on body 2) acts at a contact with
// relative velocity u and matrix K: J.(u + K J / 2).
double impulse_energy_change(const Mat3 &K, const Vec3 &u, const Vec3 &J);

// An integrated impulse must not add energy through its discretisation: if J does (at relative
// velocity u0 before it), scale it to the largest multiple that does not. (The integrated
// impact's separation phase then adds what its target asks for: the overlap correction's energy.)
void cap_energy(const Mat3 &K, const Vec3 &u0, Vec3 &J);

// The contact law on relative velocity u (body 2 minus body 1 at the contact), unit normal n from
// body 1 to body 2. target_separation (>= 0) is the normal velocity restitution aims for:
// e * max(0, -u.n), or an overlap's minimum separation velocity if larger. Restitution (Stronge)
// returns at most the work of compression; if the contact still separates slower than
// target_separation after it, the normal impulse continues to it, so the law is continuous where
// the target crosses the approach speed. Returns the impulse on body 2; J.n >= 0.
Vec3 contact_law_impulse(const Mat3 &K, const Vec3 &u, const Vec3 &n, const ContactModel &model,
                         double target_separation);

// One isolated collision between body 1 and body 2 at contact point c with normal n (1 -> 2).
// Returns the impulse J on body 2 (-J on body 1); zero if the bodies separate at c.
Vec3 collision_impulse(const RigidBodyState &body1, const RigidBodyState &body2, const Vec3 &point,
                       const Vec3 &n, const ContactModel &model);

}    // namespace ActiveGrain
