// The rods that have atoms in a group on this rank, regrouped from their constituent atoms
// (owned and ghost) through the RigidBodyProvider, with each rod's polar axis and each owned
// atom's share of its rod's projected area. Shared by the rod computes.
#pragma once

#include "ag_projected_area.h"
#include "ag_rigid_body.h"
#include "pointers.h"

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

  // `style` names the compute in errors; without `rods_required`, no rod fix means no rods.
  LocalRods(LAMMPS *lmp, const char *style, bool rods_required);

  // Regroup the rods of the atoms in groupbit.
  void update(int groupbit);

  const std::vector<Rod> &rods() const { return rods_; }
  // Index into rods() of owned atom i's rod, or -1 for an atom that is not in a rod.
  int rod_of_atom(int i) const { return rod_of_atom_[i]; }
  // Owned rod atom i's share of its rod's projected area.
  double area_share(int i) const { return area_share_[i]; }

 private:
  std::string style_;
  bool rods_required_;
  RigidBodyProvider *provider_ = nullptr;
  std::vector<Rod> rods_;
  std::vector<int> rod_of_atom_;
  std::vector<double> area_share_;

  RigidBodyProvider *find_provider();
};

}    // namespace LAMMPS_NS
