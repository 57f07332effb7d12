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

  // Regroup the rods of the atoms in groupbit, from ghost positions brought up to date first: an
  // atom that pair gran/impulse moves late in a step (its late impulse) has moved since the
  // step's communication, its ghost copies not. `caller` is the compute that calls this on every
  // rank; its comm_forward is POSITION_COLUMNS, and its pack_forward_comm and unpack_forward_comm
  // are pack_positions and unpack_positions.
  void update(class Compute *caller, int groupbit);
  // Fails, naming the compute's style, where rods are required and no rod fix is defined.
  void check_provider() { find_provider(); }
  static constexpr int POSITION_COLUMNS = 3;
  int pack_positions(int n, int *list, double *buf, int pbc_flag, int *pbc) const;
  void unpack_positions(int n, int first, const double *buf) const;

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
