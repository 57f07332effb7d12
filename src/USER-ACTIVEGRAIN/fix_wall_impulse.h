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
  double compute_scalar() override;
  double compute_vector(int) override;

  void find_wall_contacts(double reach, const std::vector<char> &atoms,
                          std::vector<Contact> &contacts) override;
  void add_delivered_impulse(int surface, const ActiveGrain::Vec3 &J) override;

 private:
  enum { BASE = 0, LID = 1 };
  enum class Lid { NONE, MOVING, FIXED };

  double time_now() const;
  double base_z(double t) const;
  double base_vz(double t) const;

  double z0, gap, amplitude, frequency, phase;
  Lid lid;
  // Frozen roughness of each plate (flat unless keyword rough): rms slope, correlation length and
  // seed as given; the surfaces are made in init(), when the box is known.
  double rough_slope, rough_length;
  int rough_seed;
  ActiveGrain::RoughSurface surface[2];
  WallMaterials materials;
  double delivered[2][3];    // this rank's impulse through base and lid, last force computation
};

}    // namespace LAMMPS_NS

#endif
#endif
