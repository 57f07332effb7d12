// The contact solver's bodies for this step's atoms (pair gran/impulse): a rod's rigid body for
// the atoms a provider claims, a solid sphere for a bead (its ghost images share it), a body of
// infinite mass for an atom held by fix freeze. Each body is made once, for the first of its
// atoms met in the step; the body's velocity at a contact comes from it, the atom's from the atom.
#pragma once

#include "ag_contact_solver.h"
#include "ag_hash.h"
#include "pointers.h"

#include <utility>
#include <vector>

namespace LAMMPS_NS {

class ContactRanks;
class RigidBodyProvider;

class SolverBodies : protected Pointers {
 public:
  SolverBodies(LAMMPS *lmp, ActiveGrain::ContactSolver &solver, const ContactRanks &ranks) :
      Pointers(lmp), solver(solver), ranks(ranks)
  {
  }

  // The fixes found at init: rigid-body providers, fix freeze's group (0: none), fix gravity.
  void init(const std::vector<RigidBodyProvider *> &providers, int freeze_groupbit,
            const std::vector<class Fix *> &gravities);
  // A new step: no bodies yet; this step's accelerations of fix gravity.
  void begin_step();

  int body_of_atom(int i);
  // A solver body's key, the same on every rank (2 tag for a bead, 2 ID + 1 for a rigid body),
  // 0 for a wall's; and whether another rank decides it (ContactRanks::decides_body_of).
  std::uint64_t key_of(int body) const { return body < (int) keys.size() ? keys[body] : 0; }
  bool decided_elsewhere(int body) const { return body < (int) keys.size() && elsewhere[body]; }
  // Lever arm from body's centre of mass to point, from atom i's own image of the body.
  ActiveGrain::Vec3 lever_arm(int i, int body, const ActiveGrain::Vec3 &point) const;
  // Atom i's velocity at a point of its surface, from the atom's own velocity and spin.
  ActiveGrain::Vec3 atom_velocity_at(int i, const ActiveGrain::Vec3 &point) const;
  // Atom i's acceleration from fix gravity (velocity units per time).
  ActiveGrain::Vec3 gravity_of_atom(int i) const;
  double largest_gravity() const;    // of this step's fix gravity accelerations
  bool frozen(int i) const;
  // Owned atom i's rigid body takes the late impulse (true), or the atom is in none.
  bool add_late_impulse(int i, const ActiveGrain::Vec3 &late, const ActiveGrain::Vec3 &late_angular) const;

  double memory_usage() const;

 private:
  ActiveGrain::ContactSolver &solver;
  const ContactRanks &ranks;
  std::vector<RigidBodyProvider *> providers;
  int freeze_groupbit = 0;
  std::vector<class Fix *> gravities;
  std::vector<std::pair<int, ActiveGrain::Vec3>> gravity_now;    // group bit, acceleration
  ActiveGrain::KeyIndex body_index;    // 2*tag (bead) or 2*body_id+1 (rigid body)
  std::vector<int> atom_body;          // solver body of each atom, -1 before lookup
  std::vector<std::uint64_t> keys;     // per solver body (0 for walls' bodies)
  std::vector<char> elsewhere;         // per solver body: decided_elsewhere()
};

}    // namespace LAMMPS_NS
