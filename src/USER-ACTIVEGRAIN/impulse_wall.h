// What pair gran/impulse needs from a wall fix (fix wall/impulse, fix wall/impulse/region): the
// geometry of the contacts of atoms with the wall, and a place to report the impulse the
// wall delivered. The pair style finds wall fixes by dynamic_cast over Modify's fix list and
// solves wall and particle contacts together.
#pragma once

#include "ag_contact_prediction.h"
#include "ag_impulse.h"
#include "contact_models.h"
#include "fix.h"
#include "style_inputs.h"

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
    ActiveGrain::ContactModel model;
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
  double wall_speed() const { return max_wall_speed; }
  // Largest acceleration of the wall (a vibrating plate's amplitude times its angular frequency
  // squared): with gravity, what sets the speed below which contacts rest (pair_gran_impulse.rst).
  virtual double peak_acceleration() const { return 0.0; }

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
  static constexpr int COMPONENTS[NUM_SURFACE_QUANTITIES] = {ActiveGrain::VEC3_SIZE, ActiveGrain::VEC3_SIZE,
                                                               ActiveGrain::VEC3_SIZE};

 protected:
  // fix: the wall fix itself, whose virial (fix_modify virial yes) the contacts are tallied into.
  ImpulseWall(class Fix *fix, int nsurfaces) :
      wall_fix(fix), delivered(nsurfaces), impacts(nsurfaces), energy(nsurfaces)
  {
    std::fill(fix->virial, fix->virial + ActiveGrain::NSYMMETRIC, 0.0);
  }
  int num_surface_outputs() const;
  // An impact threshold that no contact reaches: no impacts are tallied.
  static constexpr double NO_IMPACTS = -1.0;
  // Start a force computation's tally. A wall with a drive gives its phase (radians) and the
  // approach speed above which a contact is an impact; without one, no impacts are tallied.
  // Also clears the energies, the virial and the wall speed.
  void clear_delivered(double phase = 0.0, double threshold = NO_IMPACTS);
  void note_wall_speed(double speed) { max_wall_speed = std::max(max_wall_speed, speed); }
  // Output k of the per-surface blocks (k counts from the first block), summed over ranks.
  double surface_output(MPI_Comm world, int k) const;

 private:
  class Fix *wall_fix;
  std::vector<ActiveGrain::Vec3> delivered;    // this rank's impulse per surface, last force computation
  std::vector<ActiveGrain::Vec3> impacts;      // ... impacts, sum cos, sum sin of the drive phase
  std::vector<ActiveGrain::Vec3> energy;       // ... work, dissipated, overlap correction
  double drive_phase = 0.0, impact_speed = NO_IMPACTS, max_wall_speed = 0.0;
};

// Error unless the pair style that resolves wall contacts is defined and atoms have radii.
void check_wall_host(LAMMPS *lmp, const std::string &style);

}    // namespace LAMMPS_NS
