// Many simultaneous contacts between rigid bodies (SPEC section 4b). No LAMMPS in here.
//
// A contact alone on its bodies (walls aside) is one two-body impact: Stronge's law of
// ag_impulse.h, exactly. Contacts that share a movable body (a rod lying on a plate touches it
// with several spheres; a bead in a packing touches its neighbours) form an island, and their
// rigid-body problem has no unique answer: the contact impulses of a line contact are not
// unique, and with friction neither are the bodies' velocities (how the normal impulse is
// shared sets the friction torque). So an island is solved as what a real contact does: a
// compliant impact. Every contact of the island is a spring that starts to compress at once;
// it loads with unit stiffness and unloads along Walton & Braun's line of stiffness 1/e^2,
// which returns e^2 of its compression work (Stronge's energetic restitution); its friction
// is Stronge's (stick while the cone allows, else mu times the normal impulse against the
// current slip). The impact is integrated in a fictitious time until every spring is unloaded
// and no contact approaches faster than 1% of the island's fastest approach before it (slower
// re-collisions, the long tail of a dense cluster, are found again at the next time step). This
// is the Darboux-Keller multiple-impact model (Liu, Zhao & Brogliato 2008) with linear springs
// of equal stiffness:
//   - one contact alone gives exactly Stronge's impact (the same path in impulse space);
//   - the result does not depend on the common stiffness (it only rescales the time), so the
//     model adds no parameter; equal springs share a line contact's load as an elastic
//     foundation does, linearly along the line, for any number of spheres;
//   - every sub-step is a Jacobi step (all impulses from one state): the order of the contacts
//     does not enter, only the sub-step size, which resolution sets; it shrinks to the stiff
//     unloading's before a spring turns, so the rebound converges at second order;
//   - springs with hysteresis and Coulomb friction never add energy.
// Within a time step the island's contacts meet in the order they close (Settings::window): the
// contacts that close first make one compliant impact, and the others meet the bodies as it
// left them, at the times their gaps close at the new velocities, or not in this step. Without
// that, contacts that close at different moments of a long step would share one impact, and a
// rod landing tail first and nose later would be stopped at both ends at once.
// Overlapping contacts must then open at least at their minimum separation velocity: pushes with
// Stronge's friction, Jacobi again, after the impact (the overlap correction, the only energy
// source; a body resting on a plate under gravity sits on it).
//
// Every solve starts from the state alone (no warm start), so restarts continue a run exactly
// and every rank count solves the same problem.
#pragma once

#include "ag_impulse.h"

#include <limits>
#include <vector>

namespace ActiveGrain {

class ContactSolver {
 public:
  struct Contact {
    int body1 = 0, body2 = 0;       // solver body indices; the normal points from 1 to 2
    Vec3 r1, r2;                    // lever arms: contact point minus each body's centre of mass
    Vec3 n;                         // unit normal
    ContactMaterial material;
    double min_separation = 0.0;    // normal velocity the contact must at least leave with
    // Relative velocity the contact gains from other forces (gravity, a wall's acceleration)
    // between the time of the bodies' velocities and the moment it closes: the law acts on the
    // relative velocity at that moment.
    Vec3 gain;
    double time = 0.0;              // when within the step it closes (0: touching at the start)
    // Filled by solve():
    Mat3 K;
    bool isolated = false;          // the only contact of both its (movable) bodies
    Vec3 impulse;                   // on body 2 (minus on body 1)
    Vec3 late;                      // the sum of impulse times when in the step it acted
    // The compliant impact's state: the spring's compression, its largest compression, and
    // whether it unloads.
    TangentialStep tangential;
    double knn = 0.0, compression = 0.0, peak = 0.0;
    bool unloading = false;
  };
  struct Settings {
    int resolution = 150;    // sub-steps per half oscillation of the stiffest engaged contact
    int max_substeps = 1000000;    // per island; then the island's impact stops where it is
    // Island contacts that close within window of the first are one compliant impact; the rest
    // follow in order. Infinite: all contacts of an island are one impact, whenever they close.
    double window = std::numeric_limits<double>::infinity();
    double step = std::numeric_limits<double>::infinity();    // contacts closing later wait
  };
  struct Result {
    int substeps = 0;         // most sub-steps an island's impact needed (0: none coupled)
    double shortfall = 0.0;   // largest separation velocity still missing at an overlap,
                              // relative to its minimum separation velocity
    bool converged = true;    // every impact ended within max_substeps
  };

  void clear();
  int add_body(const RigidBodyState &body);
  // Contact at a point (lever arms from the bodies' centres of mass).
  int add_contact(int body1, int body2, const Vec3 &point, const Vec3 &n,
                  const ContactMaterial &material, double min_separation = 0.0,
                  const Vec3 &gain = Vec3(), double time = 0.0);
  // Contact with explicit lever arms (periodic images: the caller applies the minimum image).
  int add_contact_arms(int body1, int body2, const Vec3 &r1, const Vec3 &r2, const Vec3 &n,
                       const ContactMaterial &material, double min_separation = 0.0,
                       const Vec3 &gain = Vec3(), double time = 0.0);

  // Isolated contacts by Stronge's law, then each island by a compliant impact. Updates the
  // bodies' velocities.
  Result solve(const Settings &settings);
  Result solve();    // with the default settings

  int num_bodies() const { return static_cast<int>(bodies_.size()); }
  int num_contacts() const { return static_cast<int>(contacts_.size()); }
  const RigidBodyState &body(int i) const { return bodies_[i]; }
  const Contact &contact(int c) const { return contacts_[c]; }
  const Vec3 &impulse(int c) const { return contacts_[c].impulse; }

 private:
  // The stages of solve().
  void prepare();
  void solve_isolated();
  void find_islands();
  int solve_island(const std::vector<int> &island, const Settings &settings);    // -1: capped
  // Both after collect_bodies(island).
  int compliant_impact(const std::vector<int> &island, const Settings &settings);    // -1: capped
  double separate_overlaps(const std::vector<int> &island);    // returns the shortfall left

  Vec3 relative_velocity(const Contact &c) const;    // at the moment the contact closes
  Vec3 impact_alone(const Contact &c, double min_separation) const;
  void apply(const Contact &c, const Vec3 &J);
  void collect_bodies(const std::vector<int> &island);
  // A Jacobi step: push() the step impulses of some island contacts, then move_bodies(); the
  // bodies stay marked as moved until forget_moved().
  void push(const std::vector<int> &island, const std::vector<int> &pushed);
  void move_bodies();
  void forget_moved();
  bool moved(const Contact &c) const;    // whether a body of the contact moved
  // Bodies' counts of the island's contacts in a Jacobi step: a share of each body's impulse.
  int share(const Contact &c) const;

  std::vector<RigidBodyState> bodies_;
  std::vector<Contact> contacts_;
  std::vector<std::vector<int>> islands_;    // contacts that share movable bodies, in order
  int num_islands_ = 0;                      // (the first num_islands_ lists of islands_)
  std::vector<int> island_root_;             // per body (union-find)
  std::vector<int> island_of_root_;          // per root body: its island, -1 before it has one
  std::vector<int> contacts_of_body_;        // per body: its contacts (isolated ones: 1)
  // Scratch of the compliant impact, per body and per island contact.
  std::vector<double> body_stiffness_;       // engaged spring stiffness on the body
  std::vector<int> body_contacts_;           // loaded (or pushed) contacts on the body
  std::vector<double> engaged_stiffness_;    // per island contact: its engaged spring's, or 0
  std::vector<double> force_;                // ... its spring's force in the sub-step
  std::vector<char> loaded_, turning_;       // ... whether loaded, and close to its turn
  std::vector<Vec3> step_impulse_;           // one Jacobi step's impulse per island contact
  std::vector<int> pushed_, taken_back_;     // the island contacts a Jacobi step pushes
  std::vector<Vec3> body_momentum_, body_angular_;    // ... summed per body (push)
  std::vector<char> moved_;                  // per body: pushed since forget_moved()
  std::vector<int> moved_bodies_;            // those bodies
  std::vector<int> island_bodies_;           // the island's bodies, each once
  std::vector<char> in_island_;              // per body: scratch of collect_bodies
  std::vector<Vec3> velocity_;               // relative velocity per island contact
  std::vector<double> gap_;                  // per island contact, at the latest impact's time
  std::vector<double> approach_;             // ... its approach speed
  std::vector<double> floor_;                // ... the approach below which it waits
  std::vector<Vec3> impulse_before_;         // ... its impulse before the present impact
  std::vector<int> wave_;                    // the island contacts of one impact
};

}    // namespace ActiveGrain
