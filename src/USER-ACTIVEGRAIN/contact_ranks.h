// Which rank solves which contact (pair gran/impulse), so that every physical contact is solved
// once, and all contacts of a rigid body together on one rank, on any number of ranks: a rigid
// body's contacts on its solver rank (LowestTagRule), from one copy of each of its atoms (the
// owned one, else the ghost image nearest the body's lowest-tag atom); contacts between beads
// from the owned bead.
#pragma once

#include "pointers.h"

#include <vector>

namespace LAMMPS_NS {

class RigidBodyProvider;

class ContactRanks : protected Pointers {
 public:
  explicit ContactRanks(LAMMPS *lmp) : Pointers(lmp) {}

  // Rigid body IDs of all owned and ghost atoms and which of them this rank solves. Without
  // providers every owned atom is solved here (a half neighbor list).
  void assign(const std::vector<RigidBodyProvider *> &providers);

  // The ID of atom i's rigid body (the same on every rank), 0 for an atom in none.
  tagint body_id(int i) const { return body_ids[i]; }
  // This rank solves atom i's wall contacts (and, for a body's atom, the contacts its body decides).
  bool solves_atom(int i) const { return solved_here[i]; }
  // Atom i's body (its bead, or its rigid body) is decided on this rank: the bead is owned here,
  // the rigid body's lowest-tag atom is (LowestTagRule). Its contacts found on other ranks make
  // an island that crosses ranks (IslandExchange).
  bool decides_body_of(int i) const { return decided_here[i]; }
  const std::vector<char> &solved_atoms() const { return solved_here; }
  // This rank solves the contact of i with neighbor j (from i's side of the neighbor list), so
  // that each physical contact is solved on one rank, once: a contact with a rigid body's atom
  // from that atom if its body has the lower ID of the two and i is the copy solved here; a pair
  // of beads from the owned bead i (with a full list or a ghost j listed on both ranks, only from
  // the lower tag).
  bool solves_pair(int i, int j) const { return may_solve_pair(i, j) && solved_here[i]; }
  // ... all of it but whether i is the copy solved here, which can change from step to step:
  // fixed between neighbor list builds (NearPairs).
  bool may_solve_pair(int i, int j) const
  {
    const tagint body_i = body_ids[i], body_j = body_ids[j];
    if (body_i || body_j) return body_i && (!body_j || body_i < body_j);
    if (i >= assigned_nlocal) return false;
    if (rigid_bodies || (!newton_pair && j >= assigned_nlocal)) return assigned_tag[i] < assigned_tag[j];
    return true;
  }

  // On several ranks, the solver rank of a body sees all its atoms and their contacts only if
  // its ghost shell reaches a neighbor cutoff beyond the body's far end: an error naming
  // `style` otherwise.
  void check_ghost_cutoff(const char *style);

  double memory_usage() const;

 private:
  bool rigid_bodies = false;    // a full neighbor list with ghosts
  // Of the atoms as assign() saw them (this force computation's).
  int assigned_nlocal = 0;
  const tagint *assigned_tag = nullptr;
  bool newton_pair = false;
  std::vector<tagint> body_ids;     // per owned or ghost atom: its body's ID, 0 for a bead
  std::vector<char> solved_here;    // per owned or ghost atom: solves_atom()
  std::vector<char> decided_here;   // per owned or ghost atom: decides_body_of()
};

}    // namespace LAMMPS_NS
