// The energy ledger of a solve: what each contact dissipated, what the overlap correction added,
// what a wall worked. No LAMMPS in here.
//
// The bodies' kinetic energy (translation and rotation) changes by exactly the sum over contacts
// of J . (u_before + u_after) / 2, u the relative velocity at the contact, plus J . v_wall at wall
// contacts. The law sees u plus the contact's gain (gravity, the plate's acceleration until the
// contact closes), and so does this count: a contact loses J . (u + gain) averaged (an impact
// alone: (1 - e^2) of its energy of approach), a wall works with its velocity when the contact
// closes. Left out of the kinetic energy change: gravity's part of the gain, J . g (dt/2 + t_c),
// negligible. A contact whose overlap correction made it leave at its minimum separation velocity
// s, faster than restitution would (e times its approach a), is credited 1/2 m (s^2 - (e a)^2) to
// the correction (m = 1 / n.K.n, the contact's effective mass: exact for a frictionless contact
// alone); the rest is dissipation.
#pragma once

#include "ag_contact_solver.h"

namespace ActiveGrain {

struct ContactEnergy {
  double dissipated = 0.0;      // lost at the contact
  double overlap_work = 0.0;    // added by the overlap correction
  double wall_work = 0.0;       // J . v_wall, the work of a wall (body 1) on the contact
};

// Contact c of a solved solver, whose relative velocity before the solve was velocity_before and
// whose normal approach speed, gain included, was approach; wall_velocity is body 1's when the
// contact closed (zero between particles).
ContactEnergy contact_energy(const ContactSolver &solver, int c, const Vec3 &velocity_before,
                             double approach, const Vec3 &wall_velocity = Vec3());

}    // namespace ActiveGrain
