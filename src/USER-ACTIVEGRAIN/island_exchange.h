// Islands of contacts that cross MPI sub-domains, solved whole (pair gran/impulse). Every
// physical contact is found on one rank (ContactRanks), but one island's contacts can be found
// on several: a bead at a sub-domain boundary touches beads found from both sides. Each rank
// solving its part alone would make the answer depend on the decomposition. So in each step
// every rank names the bodies of its contacts that another rank decides; the islands that hold
// such a body, on any rank, are gathered to rank 0 as data (bodies by their keys, contacts with
// their order keys), solved there as one problem in the contacts' global order, and their results
// go back to the ranks that found the contacts. An island that no other rank touches is solved
// where it is found. Either way it is the problem one rank would solve. On one rank nothing is
// exchanged.
#pragma once

#include "ag_contact_solver.h"
#include "ag_hash.h"
#include "contact_assembly.h"
#include "pointers.h"

#include <cstdint>
#include <vector>

namespace LAMMPS_NS {

class SolverBodies;

class IslandExchange : protected Pointers {
 public:
  explicit IslandExchange(LAMMPS *lmp) : Pointers(lmp) {}

  // Marks the solver's contacts whose islands cross ranks as solved elsewhere and packs them.
  void split(ActiveGrain::ContactSolver &solver, const SolverBodies &bodies, const ContactAssembly &assembly);
  // Solves the crossing islands on rank 0 and gives each rank's solver its contacts' results.
  // Returns that solve's result on rank 0 (an empty one on the others).
  ActiveGrain::ContactSolver::Result solve(ActiveGrain::ContactSolver &solver,
                                           const ActiveGrain::SolverSettings &settings, ContactOrder order);
  // Contacts of this rank solved in a gathered island, last step.
  int num_crossing() const { return static_cast<int>(crossing.size()); }
  double memory_usage() const;

 private:
  // A contact as it travels: its bodies by key (0: a wall's, never merged) and state, the contact
  // as this rank's solver holds it (its body indices are this rank's), and its order key.
  struct CrossingContact {
    std::uint64_t key1, key2;
    ActiveGrain::RigidBodyState body1, body2;
    ActiveGrain::SolverContact contact;
    std::uint64_t shuffle;
    std::int64_t identity[4];    // ContactAssembly::ContactIdentity
  };
  struct Solution {
    ActiveGrain::Vec3 impulse, late, velocity_after;
  };

  bool share_away_bodies(const ActiveGrain::ContactSolver &solver, const SolverBodies &bodies);
  void mark_crossing_islands(ActiveGrain::ContactSolver &solver, const SolverBodies &bodies,
                             const ContactAssembly &assembly);
  ActiveGrain::ContactSolver::Result solve_gathered(const ActiveGrain::SolverSettings &settings, ContactOrder order);

  bool any_crossing = false;                // some rank has a contact with a body decided elsewhere
  ActiveGrain::KeyIndex shared;             // keys of bodies whose contacts are found on several ranks
  std::vector<std::uint64_t> away_keys, all_away_keys;
  std::vector<int> root;                    // per solver body (union-find)
  std::vector<char> crossing_root;          // per root body
  std::vector<CrossingContact> crossing;    // this rank's, in its solver's order
  std::vector<int> crossing_index;          // their indices in the solver
  std::vector<Solution> solutions;          // for them
  // Rank 0: everything gathered, its solver, and where each of its contacts came from.
  std::vector<CrossingContact> gathered;
  std::vector<Solution> gathered_solutions;
  std::vector<int> counts, displacements, gather_order;
  ActiveGrain::ContactSolver gathered_solver;
  ActiveGrain::KeyIndex merged;             // body key -> gathered solver body
};

}    // namespace LAMMPS_NS
