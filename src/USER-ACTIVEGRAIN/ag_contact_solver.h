// Many simultaneous contacts between rigid bodies (docs/model.rst, "Contacts: frictional impulses"). No LAMMPS in here.
//
// A contact alone on its bodies (walls aside) is one two-body impact: Stronge's law of
// ag_impulse.h, exactly. Contacts that share a movable body (a rod lying on a plate touches it
// with several spheres; a bead in a packing touches its neighbours) form an island, and their
// rigid-body problem has no unique answer: the contact impulses of a line contact are not
// unique, and with friction neither are the bodies' velocities (how the normal impulse is
// shared sets the friction torque). So an island is solved as what a real contact does: a
// compliant impact (ag_compliant_impact.h), every contact a spring with Stronge's restitution
// and friction, all integrated together in Jacobi steps (ag_jacobi_step.h).
// Within a time step the island's contacts meet in the order they close (Settings::window): the
// contacts that close first make one compliant impact, and the others meet the bodies as it
// left them, at the times their gaps close at the new velocities, or not in this step. Without
// that, contacts that close at different moments of a long step would share one impact, and a
// rod landing tail first and nose later would be stopped at both ends at once.
// Overlapping contacts must then open at least at their minimum separation velocity: pushes with
// Stronge's friction, in Jacobi steps again, after the impact (the overlap correction, the only
// energy source; a body resting on a plate under gravity sits on it).
// Every threshold that changes the outcome is a field of Settings (ag_solver_settings.h).
//
// Every solve starts from the state alone (no warm start), so restarts continue a run exactly
// and every rank count solves the same problem.
#pragma once

#include "ag_compliant_impact.h"
#include "ag_impulse.h"
#include "ag_jacobi_step.h"
#include "ag_resting_solve.h"
#include "ag_solver_contact.h"
#include "ag_solver_settings.h"

#include <algorithm>
#include <vector>

namespace ActiveGrain {

class ContactSolver {
 public:
  using Contact = SolverContact;
  using Settings = SolverSettings;
  struct Result {
    int substeps = 0;         // most sub-steps an island's impact needed (0: none coupled)
    double shortfall = 0.0;   // largest separation velocity still missing at an overlap,
                              // relative to its minimum separation velocity
    bool converged = true;    // every impact ended within max_substeps
    int resting_sweeps = 0;            // most sweeps an island's resting solve needed
    bool resting_converged = true;     // every resting solve converged within max_resting_sweeps
    // This result and another solve's (of other islands), as one.
    void merge(const Result &other)
    {
      substeps = std::max(substeps, other.substeps);
      shortfall = std::max(shortfall, other.shortfall);
      converged = converged && other.converged;
      resting_sweeps = std::max(resting_sweeps, other.resting_sweeps);
      resting_converged = resting_converged && other.resting_converged;
    }
  };

  void clear();
  int add_body(const RigidBodyState &body);
  // Contact at a point (lever arms from the bodies' centres of mass).
  int add_contact(int body1, int body2, const Vec3 &point, const Vec3 &n,
                  const ContactModel &model, double min_separation = 0.0,
                  const Vec3 &gain = Vec3(), double time = 0.0);
  // Contact with explicit lever arms (periodic images: the caller applies the minimum image).
  int add_contact_arms(int body1, int body2, const Vec3 &r1, const Vec3 &r2, const Vec3 &n,
                       const ContactModel &model, double min_separation = 0.0,
                       const Vec3 &gain = Vec3(), double time = 0.0);

  // Isolated contacts by Stronge's law (integrated as a compliant impact where the tangential
  // law is compliant), then each island by compliant impacts in order and its
  // overlap correction. Updates the bodies' velocities.
  Result solve(const Settings &settings);
  Result solve();    // with the default settings

  int num_bodies() const { return static_cast<int>(bodies.size()); }
  int num_contacts() const { return static_cast<int>(contacts.size()); }
  const RigidBodyState &body(int i) const { return bodies[i]; }
  const Contact &contact(int c) const { return contacts[c]; }
  const Vec3 &impulse(int c) const { return contacts[c].impulse; }
  // The key that orders the contact in a resting solve (ag_resting_solve.h), from its identity.
  void set_key(int c, std::uint64_t key) { contacts[c].key = key; }
  // Contact c's island is solved by another solver, which sees all of it (an island whose
  // contacts are found on several MPI ranks): solve() skips it, and set_solution() brings the
  // other solver's impulse, late impulse and velocity after.
  void solve_elsewhere(int c) { contacts[c].solved_elsewhere = true; }
  void set_solution(int c, const Vec3 &impulse, const Vec3 &late, const Vec3 &velocity_after);

 private:
  // The stages of solve().
  void prepare();
  void solve_isolated(const Settings &settings);
  void record_velocities_after();
  void find_islands();
  int group_by_bodies(const std::vector<int> &subset, std::vector<std::vector<int>> &groups);
  int solve_island(const std::vector<int> &island, const Settings &settings);    // -1: capped
  int impacts_in_order(const std::vector<int> &island, const Settings &settings);    // -1: capped
  int solve_impacts_then_resting(const std::vector<int> &island, const Settings &settings, Result &result);
  double separate_overlaps(const std::vector<int> &island, const Settings &settings);    // the shortfall left
  double overlap_shortfall(const std::vector<int> &island, const Settings &settings) const;

  Vec3 impact_alone(const Contact &c, double min_separation) const;
  void solve_alone(int c, double min_separation, const Settings &settings);
  Vec3 compliant_alone(Contact &c, const Vec3 &before, double min_separation) const;
  void measure_approaches(const std::vector<int> &island);
  double closing_time(const Contact &c, double approach_speed, const Settings &settings) const;

  std::vector<RigidBodyState> bodies;
  std::vector<Contact> contacts;
  std::vector<std::vector<int>> islands;    // contacts that share movable bodies, in order
  int num_islands = 0;                      // (the first num_islands lists of islands)
  std::vector<int> island_root;             // per body (union-find)
  std::vector<int> island_of_root;          // per root body: its island, -1 before it has one
  std::vector<int> contacts_of_body;        // per body: its contacts (isolated ones: 1)
  std::vector<int> coupled;                 // the contacts that are not isolated
  std::vector<int> impacts;                 // an island's contacts that are not resting
  std::vector<std::vector<int>> impact_islands;    // ... grouped by the bodies they share
  RestingSolve resting_solve;
  CompliantImpact compliant_impact;
  JacobiStep overlap_step;                  // the overlap correction's
  // Scratch of the impacts in order, per island contact:
  std::vector<double> gap;                  // at the latest impact's time
  std::vector<double> approach;             // its approach speed
  std::vector<double> settled_below;        // the approach below which it waits
  std::vector<Vec3> impulse_before;         // its impulse before the present impact
  std::vector<int> wave;                    // the island contacts of one impact
  std::vector<int> alone;                   // one contact, as an island of its own
};

}    // namespace ActiveGrain
