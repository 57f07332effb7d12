// Islands of contacts that cross MPI sub-domains, solved whole (pair gran/impulse). Every
// physical contact is found on one rank (ContactRanks), but one island's contacts can be found
// on several: a bead at a sub-domain boundary touches beads found from both sides. Each rank
// solving its part alone would make the answer depend on the decomposition. So in each step
// every rank names the bodies of its contacts that another rank decides; the islands that hold
// such a body, on any rank, are sent to every rank as data (bodies by their keys, contacts with
// their order keys); each is solved whole by one rank, in the contacts' global order, and the results
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
  // Solves the crossing islands, each on one rank, and gives each rank's solver its contacts'
  // results. Returns the result of the islands solved on this rank.
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
  ActiveGrain::ContactSolver::Result solve_own_islands(const ActiveGrain::SolverSettings &settings,
                                                      ContactOrder order);
  void return_solutions(ActiveGrain::ContactSolver &solver);

  bool any_crossing = false;                // some rank has a contact with a body decided elsewhere
  ActiveGrain::KeyIndex shared;             // keys of bodies whose contacts are found on several ranks
  std::vector<std::uint64_t> away_keys, all_away_keys;
  std::vector<int> root;                    // union-find: per solver body, then per island node
  std::vector<char> crossing_root;          // per root body
  std::vector<CrossingContact> crossing;    // this rank's, in its solver's order
  std::vector<int> crossing_index;          // their indices in the solver
  // Every rank's crossing contacts (rank by rank, each in its order), counts and offsets in
  // contacts and in bytes; their global order, islands and solving ranks.
  std::vector<CrossingContact> gathered;
  std::vector<int> counts, displacements, send_bytes, byte_offsets, recv_bytes, recv_offsets;
  std::vector<int> gather_order, contact_node, first_position, owner, own_contacts;
  ActiveGrain::ContactSolver gathered_solver;    // this rank's islands of them
  ActiveGrain::KeyIndex merged;                  // body key -> island node, then solver body
  std::vector<Solution> gathered_solutions, outgoing, incoming;
};

}    // namespace LAMMPS_NS
