// How contact styles learn that an atom is a constituent of a rigid body (a rod), and that
// body's mass, centre of mass, inertia and velocity. Implemented by fix rigid/rod; found by
// pair gran/impulse and the wall fixes through Modify's fix list.
#pragma once

#include "ag_rigid_body.h"
#include "atom.h"
#include "domain.h"
#include "lmptype.h"

namespace LAMMPS_NS {

class RigidBodyProvider {
 public:
  // noexcept(false) like LAMMPS's Pointers, so that a Fix can also be a RigidBodyProvider.
  virtual ~RigidBodyProvider() noexcept(false) = default;
  // For atom i (owned or ghost): false if it belongs to no body of this provider; otherwise
  // the body's current state and a body ID that is the same on every rank and every atom of it.
  virtual bool body_of_atom(int i, ActiveGrain::RigidBodyState &body, tagint &body_id) const = 0;
  // For owned atom i: false if it belongs to no body of this provider; otherwise take a late
  // impulse delivered to the atom in this step's force computation (impulse times the time
  // after the step's start at which its contact closed) and its moment about the atom. Before
  // the step ends the body moves back by (sum of late impulses) / mass and turns back by the
  // inverse inertia times their moment, as if each impulse had acted when its contact closed.
  virtual bool add_late_impulse(int i, const ActiveGrain::Vec3 &late,
                                const ActiveGrain::Vec3 &late_angular) = 0;
};

// The copy of atom j (owned or ghost image) nearest atom i: how the styles pick one image of
// each atom of a body. Domain::closest_image(i, j) only walks the same-tag images after j, so
// the walk starts at the chain's head, atom->map(tag).
inline int nearest_copy(Atom *atom, Domain *domain, int i, int j)
{
  return domain->closest_image(i, atom->map(atom->tag[j]));
}

}    // namespace LAMMPS_NS
