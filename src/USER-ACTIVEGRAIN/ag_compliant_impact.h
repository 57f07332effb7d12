// The compliant impact of an island's contacts (ag_contact_solver.h). No LAMMPS in here.
//
// Every contact of the island is a spring that starts to compress at once; it loads with unit
// stiffness and unloads along Walton & Braun's line of stiffness 1/e^2, which returns e^2 of its
// compression work (Stronge's energetic restitution); its friction is Stronge's (stick while the
// cone allows, else mu times the normal impulse against the current slip). The impact is
// integrated in a fictitious time until every spring is unloaded and no contact approaches
// faster than SolverSettings::settled_approach of the island's fastest approach before it. This
// is the Darboux-Keller multiple-impact model (Liu, Zhao & Brogliato 2008) with linear springs of
// equal stiffness:
//   - one contact alone gives exactly Stronge's impact (the same path in impulse space);
//   - the result does not depend on the common stiffness (it only rescales the time), so the
//     model adds no parameter; equal springs share a line contact's load as an elastic
//     foundation does, linearly along the line, for any number of spheres;
//   - every sub-step is a Jacobi step (all impulses from one state): the order of the contacts
//     does not enter, only the sub-step size, which resolution sets; it shrinks to the stiff
//     unloading's before a spring turns, so the rebound converges at second order;
//   - springs with hysteresis and Coulomb friction never add energy.
// With the compliant tangential law (ag_contact_model.h) a contact also has a tangential spring,
// of stiffness ratio times the normal spring's loading stiffness, in series with its Coulomb
// slider: its stretch follows the contact point's slip while the spring's force stays within mu
// times the normal force, the slider takes the rest, and the spring pushes back, so that the slip
// can reverse within the impact (Maw, Barber and Fawcett's rebound; Stronge's rough compliant
// bodies). What is left in it when the normal force ends is dissipated. The sub-steps resolve
// its oscillation too. An island with such springs ends no higher in kinetic energy than it began
// (in the frames of the walls, as the energy ledger counts): where the sub-stepping's error would
// add some, all its impulses are scaled back together to the largest fraction that adds none.
#pragma once

#include "ag_jacobi_step.h"
#include "ag_solver_contact.h"
#include "ag_solver_settings.h"

#include <cstddef>
#include <limits>
#include <vector>

namespace ActiveGrain {

class CompliantImpact {
 public:
  // A contact's spring: unit stiffness while loading; unloading along the line of stiffness
  // 1/e^2 that ends (zero force) at compression peak (1 - e^2); a plastic contact (e = 0)
  // unloads at once.
  struct Spring {
    double e = 0.0;    // the contact's restitution
    double compression = 0.0, peak = 0.0;    // its compression, and its largest so far
    bool unloading = false;

    double offset() const { return peak * (1.0 - e * e); }    // where its force starts
    double force() const;
    // (A plastic contact that approaches again at its peak reloads with unit stiffness.)
    double stiffness() const { return unloading && e > 0.0 ? 1.0 / (e * e) : 1.0; }
    // Unloading once the compression shrinks, loading again beyond its peak.
    void compress(double change);
    // What a loading spring close to its turn adds to its stiffness: up to its unloading's.
    double turning_extra() const;
  };
  // The springs as classify() finds them.
  struct Engagement {
    bool engaged = false;    // a spring is loaded, or approaches at or past its offset
    bool loaded = false;     // a spring is loaded
    bool changed = false;    // a spring's stiffness or loading changed since the last classify()
    // Free flight until the nearest approaching spring reaches its offset.
    double to_contact = std::numeric_limits<double>::infinity();
    double fastest_approach = 0.0;
  };

  void resize(std::size_t num_bodies);    // before a solve of num_bodies bodies
  // The island's impact (indices into contacts): updates the bodies' velocities and adds to the
  // contacts' impulses. Returns the sub-steps it took, -1 if stopped at settings.max_substeps.
  int solve(std::vector<RigidBodyState> &bodies, std::vector<SolverContact> &contacts,
            const std::vector<int> &island, const SolverSettings &settings);

  // The stages of solve(), public to be tested alone. start() sets the island they act on (its
  // contact k: the island's k-th) until the next start().
  void start(std::vector<RigidBodyState> &bodies, std::vector<SolverContact> &contacts,
             const std::vector<int> &island, const SolverSettings &settings);
  Engagement classify();
  bool ended(const Engagement &found) const;
  void fly(double time);    // free flight (no spring engaged): only the compressions move
  // pi / resolution of the fastest engaged oscillation; changed: as classify() found.
  double substep_size(bool changed);
  void kick(double dtau);    // the loaded springs' impulses in one Jacobi step
  void take_back();          // the part of a plastic contact's kick past its peak
  void drift(double dtau);   // the compressions move with the new velocities

  Spring &spring(std::size_t k) { return springs[k]; }
  const Vec3 &velocity(std::size_t k) const { return velocities[k]; }    // relative, at contact k

 private:
  JacobiStep jacobi;
  // The island (start()): its bodies' and contacts' lists, and its contacts in them.
  std::vector<RigidBodyState> *solver_bodies = nullptr;
  std::vector<SolverContact> *solver_contacts = nullptr;
  const std::vector<int> *island_contacts = nullptr;
  double phase_per_substep = 0.0;     // of the stiffest engaged oscillation
  bool plastic = false;               // whether a contact has e = 0
  double approaching_below = 0.0;     // the normal velocity below which a contact approaches
  double settled_speed = 0.0;         // the approach that counts as settled (ended())
  double previous_dtau = 0.0;         // the last drift: a kick spans half of it and half the next
  // The sub-steps of the engaged springs, and with those turning; computed again only when one
  // of them changes (most sub-steps keep all).
  double engaged_dtau = 0.0, turning_dtau = 0.0;
  std::vector<double> body_stiffness;       // per body: engaged spring stiffness on it
  // Per island contact:
  std::vector<Spring> springs;
  std::vector<Vec3> velocities;             // relative velocity
  std::vector<double> engaged_stiffness;    // its engaged spring's, or 0
  std::vector<double> forces;               // its spring's force in the sub-step
  std::vector<char> loaded, turning;        // whether loaded, and close to its turn
  std::vector<int> taken_back;              // the plastic contacts take_back() pushes
  // The compliant tangential law's: whether a contact of the island has it, the springs'
  // stretches (per island contact), the tangential stiffness per body, and what the energy
  // check at the end needs of the start (island bodies' velocities, the contacts' impulses).
  bool compliant = false;
  std::vector<Vec3> stretch;
  std::vector<double> body_tangential;
  std::vector<Vec3> start_v, start_omega, start_velocity, start_impulse;

  std::size_t size() const { return island_contacts->size(); }
  SolverContact &contact(std::size_t k) const { return (*solver_contacts)[(*island_contacts)[k]]; }
  Vec3 contact_velocity(std::size_t k) const { return relative_velocity(*solver_bodies, contact(k)); }
  void count_loaded();
  double stiffest_substep(bool with_turning);
  bool find_turning(bool &changed);    // whether a spring turns; changed: if one started or stopped
  Vec3 tangential_impulse(std::size_t k, double dp, double span);    // the friction of a kick
  void keep_within_start_energy();
};

}    // namespace ActiveGrain
