// What pair gran/impulse needs from a wall fix (fix wall/impulse, fix wall/impulse/region): the
// geometry of the contacts of atoms with the wall, and a place to report the impulse the
// wall delivered. The pair style finds wall fixes by dynamic_cast over Modify's fix list and
// solves wall and particle contacts together.
#pragma once

#include "ag_contact_prediction.h"
#include "ag_impulse.h"
#include "fix.h"

#include <algorithm>
#include <mpi.h>
#include <string>
#include <vector>

namespace LAMMPS_NS {

class ImpulseWall {
 public:
  struct Contact {
    int atom;                               // owned or ghost atom index
    int surface;                            // which surface of the fix (for its output)
    ActiveGrain::Vec3 normal;               // unit, from the wall into the atom
    ActiveGrain::Vec3 point;                // contact point (on the atom's surface)
    double gap;                             // surface separation, < 0 for an overlap
    ActiveGrain::Vec3 wall_velocity;        // velocity of the wall at the point
    ActiveGrain::Vec3 wall_acceleration;    // ... and its acceleration
    ActiveGrain::ContactMaterial material;
  };

  // noexcept(false) like LAMMPS's Pointers, so that a Fix can also be an ImpulseWall.
  virtual ~ImpulseWall() noexcept(false) = default;
  // Append the contacts of the atoms (owned or ghost) of the fix's group with atoms[i] != 0
  // whose gap is below reach and may close within the step (gap_may_close, from the atom's
  // velocity and spin_speed[i], its spin's surface speed). Called once per force computation.
  virtual void find_wall_contacts(double reach, const std::vector<char> &atoms,
                                  const std::vector<double> &spin_speed, std::vector<Contact> &contacts) = 0;
  // The impulse delivered to an atom through a surface in this force computation, at a contact
  // that approached at speed approach (> 0) before the solve: an impact, if faster than the
  // wall's impact threshold, is tallied at the wall's drive phase.
  void add_delivered_impulse(int surface, const ActiveGrain::Vec3 &J, double approach);
  // Energies of a contact through a surface in this force computation (ENERGY): the wall's work
  // J . v_wall, the energy dissipated and the energy the overlap correction added.
  void add_energy(int surface, double work, double dissipated, double overlap);
  // Virial of a contact force (fix_modify virial yes): arm from the contact point to the atom's
  // centre, times the force on the atom (as fix wall/region tallies it). Global only.
  void add_virial(const ActiveGrain::Vec3 &arm, const ActiveGrain::Vec3 &force);
  // Largest speed of the wall at the atoms it looked at in this force computation (for the
  // pair style's skin warning: a wall closes gaps at its own speed).
  double wall_speed() const { return wall_speed_; }

  // Global outputs of the wall fixes (compute_vector), one layout for both: first the fix's own
  // state (fix wall/impulse: base z, lid z, plate velocity; fix wall/impulse/region: none), then
  // one block per SurfaceQuantity: for every surface in the fix's order (wall/impulse: base,
  // lid), the quantity's components, all in the last force computation:
  //   IMPULSE  x, y, z of the impulse delivered through the surface;
  //   IMPACTS  impacts (contacts approaching faster than the impact threshold that got an
  //            impulse), and the sums of cos and sin of the drive phase at them (the lock-in
  //            order parameter R = |<exp(i phase)>| over any window is |sums| / impacts, each
  //            summed over the window, e.g. with fix ave/time).
  //   ENERGY   the work the surface did on the atoms (sum of J . v_wall over its contacts), the
  //            energy dissipated at its contacts, and the energy the overlap correction added at
  //            them (docs/pair_gran_impulse.rst: energy balance).
  // A quantity added later goes after the last one: the indices of the existing ones never
  // change.
  enum SurfaceQuantity { IMPULSE = 0, IMPACTS, ENERGY, NUM_SURFACE_QUANTITIES };
  static constexpr int COMPONENTS[NUM_SURFACE_QUANTITIES] = {3, 3, 3};

 protected:
  // fix: the wall fix itself, whose virial (fix_modify virial yes) the contacts are tallied into.
  ImpulseWall(class Fix *fix, int nsurfaces) :
      fix_(fix), delivered_(nsurfaces), impacts_(nsurfaces), energy_(nsurfaces)
  {
    std::fill(fix->virial, fix->virial + 6, 0.0);
  }
  int num_surface_outputs() const;
  // Start a force computation's tally. A wall with a drive gives its phase (radians) and the
  // approach speed above which a contact is an impact; without one, no impacts are tallied.
  // Also clears the energies, the virial and the wall speed.
  void clear_delivered(double drive_phase = 0.0, double impact_speed = -1.0);
  void note_wall_speed(double speed) { wall_speed_ = std::max(wall_speed_, speed); }
  // Output k of the per-surface blocks (k counts from the first block), summed over ranks.
  double surface_output(MPI_Comm world, int k) const;

 private:
  class Fix *fix_;
  std::vector<ActiveGrain::Vec3> delivered_;    // this rank's impulse per surface, last force computation
  std::vector<ActiveGrain::Vec3> impacts_;      // ... impacts, sum cos, sum sin of the drive phase
  std::vector<ActiveGrain::Vec3> energy_;       // ... work, dissipated, overlap correction
  double drive_phase_ = 0.0, impact_speed_ = -1.0, wall_speed_ = 0.0;
};

// Restitution and friction of a wall against each atom type: "e E mu MU" for all types, then
// "type T E MU" (T may be a range like 2*3) to override some. Parsed by both wall fixes.
class WallMaterials : protected Pointers {
 public:
  WallMaterials(LAMMPS *lmp, const std::string &style) : Pointers(lmp), style_(style) {}
  // Consume a material keyword at arg[iarg]; returns the next index, or iarg if not one.
  int parse(int narg, char **arg, int iarg);
  // Errors unless every type has its coefficients.
  void check_complete() const;
  const ActiveGrain::ContactMaterial &of_type(int type) const { return per_type_[type]; }

 private:
  ActiveGrain::ContactMaterial checked(const char *e, const char *mu) const;
  std::string style_;
  std::vector<ActiveGrain::ContactMaterial> per_type_;
  std::vector<bool> set_;
  double e_all_ = -1.0, mu_all_ = -1.0;
};

// Error unless the pair style that resolves wall contacts is defined and atoms have radii.
void check_wall_host(LAMMPS *lmp, const std::string &style);

// Error unless e is in [0, 1] and mu >= 0: shared by the pair style and the wall fixes.
void check_material(Error *error, const std::string &style, double e, double mu);

// Largest radius of the atoms of type `type` that fix pour or fix deposit will insert during a
// run (0 if none), read as GRANULAR's pair styles read it (the fixes' extract("radius")).
// With groupbit (a fix's group), only inserting fixes whose atoms join that group count.
double inserted_radius(LAMMPS *lmp, int type, int groupbit = 0);

// Largest radius of the atoms of group groupbit present now, on all ranks, or to be inserted into
// it by fix pour/deposit (all types).
double largest_radius(LAMMPS *lmp, int groupbit);

}    // namespace LAMMPS_NS
