// The pairs of pair gran/impulse's neighbor list that can touch soon, screened once and kept
// while no two atoms can have closed the rest of their margin. LAMMPS's list holds every pair
// within the radius sum plus the skin (with rods, a full list: each pair of beads twice); in a
// time step only pairs a few microns apart can close, so the list is first cut down to the pairs
// this rank may solve (ContactRanks::may_solve_pair) with a gap below the margin. A pair left out
// was at least the margin apart; it cannot close within the step while twice the largest
// displacement since then, plus twice the largest |v| + |omega| r times dt, stays below the
// margin. Screening the near pairs each step therefore finds exactly the contacts the whole list
// would.
#pragma once

#include "pointers.h"

#include <utility>
#include <vector>

namespace LAMMPS_NS {

class ContactRanks;
class NeighList;

class NearPairs : protected Pointers {
 public:
  explicit NearPairs(LAMMPS *lmp) : Pointers(lmp) {}

  // Up to date for this step: rebuilt from list after a neighbor list build, or when atoms
  // moving at up to fastest (|v| + |omega| r over owned and ghost atoms) could close the margin
  // within the step.
  void refresh(NeighList *list, const ContactRanks &ranks, double margin, double fastest);
  const std::vector<std::pair<int, int>> &pairs() const { return screened; }
  // Screen anew at the next refresh (the atoms may have been sorted without a list build).
  void invalidate() { list_built = NOT_BUILT; }

  double memory_usage() const;

 private:
  void build(NeighList *list, const ContactRanks &ranks);
  double largest_change() const;

  static constexpr bigint NOT_BUILT = -1;    // list_built before the first build, or to screen anew

  std::vector<std::pair<int, int>> screened;    // (i, j) from i's side of the neighbor list
  bigint list_built = NOT_BUILT;            // neighbor list build (step) the pairs come from
  int nall_built = 0;
  double built_margin = 0.0;
  std::vector<double> x_built, radius_built;    // per atom, as they were at the build
};

}    // namespace LAMMPS_NS
