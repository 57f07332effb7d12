// A Jacobi step over some contacts of an island: every impulse taken from the same state, summed
// per body so that each body's inverse mass and inertia are applied once. The compliant impact
// and the overlap correction take their steps with one each. No LAMMPS in here.
#pragma once

#include "ag_solver_contact.h"

#include <cstddef>
#include <vector>

namespace ActiveGrain {

class JacobiStep {
 public:
  // Before a solve of num_bodies bodies: the per-body scratch, zero.
  void resize(std::size_t num_bodies);
  // The island the next steps act on (indices into contacts), until the next start_island();
  // "contact k" below is the island's k-th.
  void start_island(std::vector<RigidBodyState> &bodies, std::vector<SolverContact> &contacts,
                    const std::vector<int> &island);
  const std::vector<int> &island_bodies() const { return bodies_of_island; }    // each once

  // Counts per body of the contacts that share its impulses (share()).
  void clear_counts();
  void count(std::size_t k);
  // The counted contacts on contact k's busier movable body (1 at least): a sticking contact's
  // impulse is divided by it, so that the contacts of a body together do not overshoot.
  int share(std::size_t k) const;

  // A step: start_step(), add() the impulses, then push() them into the contacts and the bodies'
  // sums and move_bodies(). The bodies stay marked as moved until forget_moved().
  void start_step();
  void add(std::size_t k, const Vec3 &J);
  Vec3 &impulse(std::size_t k) { return step_impulse[k]; }
  const std::vector<int> &pushed() const { return step_contacts; }    // the contacts add() took
  void push() { push(step_contacts); }
  void push(const std::vector<int> &which);    // these contacts' step impulses (again, rescaled)
  void move_bodies();
  void forget_moved();
  bool moved(std::size_t k) const;    // whether a body of contact k moved

 private:
  // The island's (start_island): its bodies' and contacts' lists, and its contacts in them.
  std::vector<RigidBodyState> *solver_bodies = nullptr;
  std::vector<SolverContact> *solver_contacts = nullptr;
  const std::vector<int> *island_contacts = nullptr;
  std::vector<int> bodies_of_island;
  std::vector<char> in_island;                      // per body: scratch of start_island
  std::vector<int> body_contacts;                   // per body: counted contacts
  std::vector<Vec3> step_impulse;                   // per island contact
  std::vector<int> step_contacts;                   // the island contacts of the step
  std::vector<Vec3> body_momentum, body_angular;    // per body: the pushed impulses' sums
  std::vector<char> body_moved;                     // per body: pushed since forget_moved()
  std::vector<int> moved_bodies;                    // those bodies

  SolverContact &contact(std::size_t k) const { return (*solver_contacts)[(*island_contacts)[k]]; }
  bool is_static(int b) const { return (*solver_bodies)[b].is_static(); }
};

}    // namespace ActiveGrain
