/* -*- c++ -*- ----------------------------------------------------------
   ActiveGrain: fix wall/impulse, a base plate and a lid (z planes) that vibrate together.
------------------------------------------------------------------------- */
#ifdef FIX_CLASS
// clang-format off
FixStyle(wall/impulse,FixWallImpulse);
// clang-format on
#else

#ifndef LMP_FIX_WALL_IMPULSE_H
#define LMP_FIX_WALL_IMPULSE_H

#include "ag_rough_surface.h"
#include "fix.h"
#include "impulse_wall.h"

namespace LAMMPS_NS {

class FixWallImpulse : public Fix, public ImpulseWall {
 public:
  FixWallImpulse(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void reset_dt() override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  double compute_scalar() override;
  double compute_vector(int) override;

  void find_wall_contacts(double reach, const std::vector<char> &atoms,
                          const std::vector<double> &spin_speed, std::vector<Contact> &contacts) override;
  double peak_acceleration() const override;

 private:
  enum Surface { BASE = 0, LID, NUM_SURFACES };
  // The fix's own state at the head of its global vector (ImpulseWall: the layout).
  enum State { BASE_Z = 0, LID_Z, PLATE_VZ, NUM_STATE };
  enum class Lid { NONE, MOVING, FIXED };

  void check_time_step(bool warn);
  void check_deck();
  bool warned_flat = false;
  double time_now() const;
  double base_z(double t) const;
  double base_vz(double t) const;
  double base_az(double t) const;

  double z0, gap, amplitude, frequency, phase;
  Lid lid;
  // The plates' clock: LAMMPS's simulation time, unless a restart file set it. LAMMPS keeps its
  // time as an origin (time, step) plus steps times dt; a restart file written during a run holds
  // that run's origin, which the next run's setup drops (Integrate::init moves the origin's step
  // to the present one, so the time since it is lost). This fix stores its origin in the restart
  // file and counts from it: the drive continues bit for bit. dt changes move the origin.
  bool own_clock;
  double clock_time, clock_dt;
  bigint clock_step;
  // Frozen roughness of each plate (flat unless keyword rough): rms slope, correlation length and
  // seed as given; the surfaces are made in init(), when the box is known.
  double rough_slope, rough_length;
  int rough_seed;
  ActiveGrain::RoughSurface surface[NUM_SURFACES];
  WallContactModels models;
};

}    // namespace LAMMPS_NS

#endif
#endif
