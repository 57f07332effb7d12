// Which rank decides a rigid body: counts it (rod computes) or solves its contacts (pair
// gran/impulse), so that every body is handled on exactly one rank.
#pragma once

#include "atom.h"
#include "lmptype.h"

#include <unordered_map>

namespace LAMMPS_NS {

// The rank that owns the body's lowest-tag atom decides it. A rank that owns an atom of a body
// sees all of the body as owned or ghost atoms (ghost cutoff), so every such rank finds the same
// lowest tag.
class LowestTagRule {
 public:
  void clear() { lowest_tag.clear(); }
  // An atom (any copy, owned or ghost) of body body_id.
  void add(tagint body_id, tagint atom_tag)
  {
    auto found = lowest_tag.emplace(body_id, atom_tag);
    if (!found.second && atom_tag < found.first->second) found.first->second = atom_tag;
  }
  // The owned copy of the body's lowest-tag atom, or -1 where another rank decides the body.
  int deciding_atom(Atom *atom, tagint body_id) const
  {
    const int i = atom->map(lowest_tag.at(body_id));    // map() prefers the owned copy
    return (i >= 0 && i < atom->nlocal) ? i : -1;
  }

 private:
  std::unordered_map<tagint, tagint> lowest_tag;    // per body ID seen
};

}    // namespace LAMMPS_NS
