// One contact of the contact solver (ag_contact_solver.h) between two of its rigid bodies, as
// the solver's algorithms share it. No LAMMPS in here.
#pragma once

#include "ag_impulse.h"

#include <cstdint>
#include <vector>

namespace ActiveGrain {

struct SolverContact {
  int body1 = 0, body2 = 0;       // solver body indices; the normal points from 1 to 2
  Vec3 r1, r2;                    // lever arms: contact point minus each body's centre of mass
  Vec3 n;                         // unit normal
  ContactModel model;
  double min_separation = 0.0;    // normal velocity the contact must at least leave with
  // Relative velocity the contact gains from other forces (gravity, a wall's acceleration)
  // between the time of the bodies' velocities and the moment it closes: the law acts on the
  // relative velocity at that moment.
  Vec3 gain;
  double time = 0.0;              // when within the step it closes (0: touching at the start)
  std::uint64_t key = 0;          // from its identity, the same whatever the order (ag_resting_solve.h)
  // Its island is solved by another solver (one that sees the island whole); the solve leaves
  // it, and its bodies' velocities, alone, and set_solution() brings its result.
  bool solved_elsewhere = false;
  // Filled by the solve:
  Mat3 K;
  bool isolated = false;          // the only contact of both its (movable) bodies
  Vec3 impulse;                   // on body 2 (minus on body 1)
  Vec3 late;                      // the sum of impulse times when in the step it acted
  Vec3 velocity_after;            // relative velocity at the contact after the solve (gain apart)
  // Of a contact that shares a body (not isolated): n.K.n, and its friction's tangential step.
  double knn = 0.0;
  TangentialStep tangential;
};

// The contact's relative velocity (body 2 minus body 1) at the moment it closes. Contact: a
// SolverContact, or what a solver keeps of one (its body1, body2, r1, r2 and gain).
template <class Contact>
inline Vec3 relative_velocity(const std::vector<RigidBodyState> &bodies, const Contact &c)
{
  return bodies[c.body2].velocity_at_arm(c.r2) - bodies[c.body1].velocity_at_arm(c.r1) + c.gain;
}

// Impulse J on body 2 and -J on body 1 at the contact.
template <class Contact>
inline void apply_impulse(std::vector<RigidBodyState> &bodies, const Contact &c, const Vec3 &J)
{
  bodies[c.body1].apply_impulse_at_arm(-J, c.r1);
  bodies[c.body2].apply_impulse_at_arm(J, c.r2);
}

}    // namespace ActiveGrain
