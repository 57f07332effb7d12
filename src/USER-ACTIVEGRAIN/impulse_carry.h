// The half of a step's contact impulses still due (pair gran/impulse): the contact force of the
// last step also acts in the next initial_integrate. Across a run boundary or a restart, setup()
// restores it instead of solving anew; it travels with the atoms (a per-atom store, fix
// STORE/IMPULSE) as force, torque, their time step and the step they belong to. A time step
// change rescales it, so that each impulse still acts in full. The global virial of that step
// comes back at setup too.
#pragma once

#include "impulse_delivery.h"
#include "pointers.h"

namespace LAMMPS_NS {

class ImpulseCarry : protected Pointers {
 public:
  explicit ImpulseCarry(LAMMPS *lmp) : Pointers(lmp) {}

  // The per-atom store (fix STORE/IMPULSE, found again after a restart).
  void create_store();
  void delete_store();
  // The forces of this step's contacts, as they were added to the atoms.
  void store(const ImpulseDelivery &delivery);
  // At a run's setup: the forces still due from the step the run continues from (if any), as
  // they were bit for bit unless the time step has changed since.
  void restore(ImpulseDelivery &delivery);
  // A new time step while forces of the old one are in atom->f (the timestep command, fix dt/reset).
  void rescale_for_dt();
  void keep_virial(const double *virial);
  void restore_virial(double *virial) const;

 private:
  // Columns of the store: the force and torque of the step's contacts, the time step they belong
  // to (their impulse is force times it: a time step change keeps the impulse), and the step.
  enum SavedColumn { SAVED_FORCE = 0, SAVED_TORQUE = 3, SAVED_DT = 6, SAVED_STEP, NUM_SAVED };

  class FixStoreImpulse *pending = nullptr;
  double force_dt = 0.0;    // time step of the contact forces now in atom->f (0: none)
  double last_virial[ImpulseDelivery::NUM_VIRIAL] = {};
  bigint last_virial_step = -1;
};

}    // namespace LAMMPS_NS
