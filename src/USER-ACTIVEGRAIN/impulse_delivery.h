// The contact impulses of a step, delivered to LAMMPS's atoms (pair gran/impulse): each impulse J
// as a force J/dt and its torque (velocity Verlet applies half in this step's final_integrate and
// half in the next initial_integrate), the late impulse J t_c of a contact that closed a time t_c
// into the step (its atoms move J t_c / m less), and the contacts' virial. Sums per owned and
// ghost atom reach the owners by reverse communication.
#pragma once

#include "ag_contact_solver.h"
#include "pointers.h"

namespace LAMMPS_NS {

class ContactAssembly;
class SolverBodies;

class ImpulseDelivery : protected Pointers {
 public:
  // A virial's components, in LAMMPS's order xx, yy, zz, xy, xz, yz.
  static constexpr int NUM_VIRIAL = ActiveGrain::NSYMMETRIC;
  // Per atom: contact force and torque, late impulse and its moment about the atom, and the
  // atom's share of its contacts' virial (with per-atom virial only).
  enum Column { FORCE = 0, TORQUE = 3, LATE = 6, LATE_ANGULAR = 9, VIRIAL = 12, NUM_COLUMNS = VIRIAL + NUM_VIRIAL };

  explicit ImpulseDelivery(LAMMPS *lmp) : Pointers(lmp) {}
  ~ImpulseDelivery() override;

  // Zero sums for this step's owned and ghost atoms.
  void begin_step();
  // The solved impulses as forces, torques and late impulses of their atoms (and walls).
  void distribute(const ActiveGrain::ContactSolver &solver, const ContactAssembly &assembly);
  // The contacts' virial: global into `virial`, per atom into the sums (see tally_virial).
  void tally_virial(const ActiveGrain::ContactSolver &solver, const ContactAssembly &assembly,
                    double *virial, bool global, bool per_atom);
  // Ghost atoms' sums to their owners: all columns with per-atom virial, else up to VIRIAL.
  void reverse_sum(class Pair *pair, bool per_atom);
  int pack_reverse(int n, int first, double *buf) const;
  void unpack_reverse(int n, int *list, const double *buf);
  // Owned atoms take the forces and torques; late impulses move them back; per-atom virial.
  void apply_forces() const;
  void move_late_atoms(const SolverBodies &bodies) const;
  void add_atom_virial(double **vatom) const;

  double *sums_of(int i) const { return contact_sums[i]; }
  double memory_usage() const;

 private:
  int nmax = 0;
  int reverse_columns = NUM_COLUMNS;
  double **contact_sums = nullptr;
};

}    // namespace LAMMPS_NS
