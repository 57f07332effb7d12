#include "impulse_delivery.h"

#include "atom.h"
#include "comm.h"
#include "contact_assembly.h"
#include "impulse_wall.h"
#include "memory.h"
#include "pair.h"
#include "solver_bodies.h"
#include "update.h"

#include <cstring>

using namespace LAMMPS_NS;
using ActiveGrain::Vec3;

ImpulseDelivery::~ImpulseDelivery() { memory->destroy(contact_sums); }

void ImpulseDelivery::begin_step()
{
  const int nall = atom->nlocal + atom->nghost;
  if (nall > nmax) {
    nmax = atom->nmax;
    memory->destroy(contact_sums);
    memory->create(contact_sums, nmax, NUM_COLUMNS, "pair:contact_sums");
  }
  if (nall > 0) memset(&contact_sums[0][0], 0, sizeof(double) * NUM_COLUMNS * nall);
}

void ImpulseDelivery::distribute(const ActiveGrain::ContactSolver &solver, const ContactAssembly &assembly)
{
  const double to_force = 1.0 / update->dt;
  double **x = atom->x;
  auto push = [&](int i, const Vec3 &J, const Vec3 &point, const Vec3 &late) {
    const Vec3 arm = point - Vec3(x[i]);
    double *sums = contact_sums[i];
    (J * to_force).add_to(sums + FORCE);
    cross(arm, J * to_force).add_to(sums + TORQUE);
    if (norm2(late) == 0.0) return;
    late.add_to(sums + LATE);
    cross(arm, late).add_to(sums + LATE_ANGULAR);
  };
  for (int c = 0; c < solver.num_contacts(); c++) {
    const ContactAssembly::AtomContact &ac = assembly.atoms_of(c);
    const Vec3 &J = solver.impulse(c), &late = solver.contact(c).late;
    push(ac.atom2, J, ac.point, late);
    if (ac.atom1 >= 0) push(ac.atom1, -J, ac.point, -late);
    else ac.wall->add_delivered_impulse(ac.surface, J, ac.approach);
  }
}

// As GRANULAR tallies its forces: for a pair, the centre-to-centre vector times the force (half of
// it to each atom's per-atom virial); for a wall contact, the arm from the contact point to the
// atom's centre times the force, to the wall fix (as fix wall/region tallies it). Each contact
// once, on the rank that solved it.
void ImpulseDelivery::tally_virial(const ActiveGrain::ContactSolver &solver, const ContactAssembly &assembly,
                                   double *virial, bool global, bool per_atom)
{
  const double to_force = 1.0 / update->dt;
  double **x = atom->x;
  for (int c = 0; c < solver.num_contacts(); c++) {
    const ContactAssembly::AtomContact &ac = assembly.atoms_of(c);
    const Vec3 force = solver.impulse(c) * to_force;    // on atom2
    if (ac.atom1 < 0) {
      ac.wall->add_virial(Vec3(x[ac.atom2]) - ac.point, force);
      continue;
    }
    const Vec3 d = Vec3(x[ac.atom2]) - Vec3(x[ac.atom1]);
    if (global) ActiveGrain::add_outer_product(virial, d, force);
    if (per_atom)
      for (int i : {ac.atom1, ac.atom2}) ActiveGrain::add_outer_product(contact_sums[i] + VIRIAL, d, force, 0.5);
  }
}

void ImpulseDelivery::reverse_sum(Pair *pair, bool per_atom)
{
  reverse_columns = per_atom ? NUM_COLUMNS : VIRIAL;
  comm->reverse_comm(pair);
}

int ImpulseDelivery::pack_reverse(int n, int first, double *buf) const
{
  int m = 0;
  for (int i = first; i < first + n; i++)
    for (int k = 0; k < reverse_columns; k++) buf[m++] = contact_sums[i][k];
  return m;
}

void ImpulseDelivery::unpack_reverse(int n, int *list, const double *buf)
{
  int m = 0;
  for (int i = 0; i < n; i++) {
    const int j = list[i];
    for (int k = 0; k < reverse_columns; k++) contact_sums[j][k] += buf[m++];
  }
}

void ImpulseDelivery::apply_forces() const
{
  double **f = atom->f, **torque = atom->torque;
  for (int i = 0; i < atom->nlocal; i++)
    for (int k = 0; k < 3; k++) {
      f[i][k] += contact_sums[i][FORCE + k];
      torque[i][k] += contact_sums[i][TORQUE + k];
    }
}

// A bead by late / mass now, the atoms of a rigid body through its provider (the whole body moves
// and turns, in its final_integrate). Atoms held by fix freeze do not move.
void ImpulseDelivery::move_late_atoms(const SolverBodies &bodies) const
{
  double **x = atom->x;
  for (int i = 0; i < atom->nlocal; i++) {
    const double *sums = contact_sums[i];
    const Vec3 late(sums + LATE);
    if (norm2(late) == 0.0 || bodies.frozen(i)) continue;
    if (!bodies.add_late_impulse(i, late, Vec3(sums + LATE_ANGULAR))) (late * (-1.0 / atom->rmass[i])).add_to(x[i]);
  }
}

void ImpulseDelivery::add_atom_virial(double **vatom) const
{
  for (int i = 0; i < atom->nlocal; i++)
    for (int k = 0; k < NUM_VIRIAL; k++) vatom[i][k] += contact_sums[i][VIRIAL + k];
}

double ImpulseDelivery::memory_usage() const { return (double) NUM_COLUMNS * nmax * sizeof(double); }
