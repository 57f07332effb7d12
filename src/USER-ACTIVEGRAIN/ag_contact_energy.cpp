#include "ag_contact_energy.h"

namespace ActiveGrain {

ContactEnergy contact_energy(const ContactSolver &solver, int c, const Vec3 &velocity_before,
                             double approach, const Vec3 &wall_velocity)
{
  const ContactSolver::Contact &contact = solver.contact(c);
  const double change = dot(contact.impulse, (velocity_before + contact.velocity_after) * 0.5 + contact.gain);
  const double restituted = contact.model.normal.e * approach;
  ContactEnergy energy;
  if (contact.min_separation > restituted)
    energy.overlap_work = 0.5 * (contact.min_separation * contact.min_separation - restituted * restituted) /
        dot(contact.n, contact.K * contact.n);
  energy.dissipated = energy.overlap_work - change;
  energy.wall_work = dot(contact.impulse, wall_velocity);
  return energy;
}

}    // namespace ActiveGrain
