// The rods that have atoms in a group on this rank, regrouped from their constituent atoms
// (owned and ghost) through the RigidBodyProvider, with each rod's polar axis and each owned
// atom's share of its rod's projected area. Shared by the rod computes.
#pragma once

#include "ag_projected_area.h"
#include "ag_rigid_body.h"
#include "atom.h"
#include "pointers.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class RigidBodyProvider;

class LocalRods : protected Pointers {
 public:
  struct Rod {
    tagint id;                       // body ID, the same on every rank
    bool counted_here;               // this rank owns the rod's lowest-tag atom: count it once
    ActiveGrain::RigidBodyState body;
    ActiveGrain::Vec3 axis;          // unit 3-D axis, tail to nose
    ActiveGrain::Vec3 polar;         // polar axis p: the in-plane direction of axis, unit length
    double area;                     // projected area of the whole rod
  };

  // `error_prefix` starts the compute's error messages (its STYLE); without `required`, no rod
  // fix means no rods.
  LocalRods(LAMMPS *lmp, const char *error_prefix, bool required);

  // Regroup the rods of the atoms in groupbit.
  void update(int groupbit);

  const std::vector<Rod> &rods() const { return rod_list; }
  // Index into rods() of owned atom i's rod, or -1 for an atom that is not in a rod.
  int rod_of_atom(int i) const { return rod_index[i]; }
  // Owned rod atom i's share of its rod's projected area.
  double area_share(int i) const { return area_shares[i]; }

 private:
  std::string style;
  bool rods_required;
  RigidBodyProvider *provider = nullptr;
  std::vector<Rod> rod_list;
  std::vector<int> rod_index;         // per owned atom
  std::vector<double> area_shares;    // per owned atom

  RigidBodyProvider *find_provider();
};

}    // namespace LAMMPS_NS
