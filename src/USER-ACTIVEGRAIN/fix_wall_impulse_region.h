/* -*- c++ -*- ----------------------------------------------------------
   ActiveGrain: fix wall/impulse/region, side walls of any shape from a LAMMPS region.
------------------------------------------------------------------------- */
#ifdef FIX_CLASS
// clang-format off
FixStyle(wall/impulse/region,FixWallImpulseRegion);
// clang-format on
#else

#ifndef LMP_FIX_WALL_IMPULSE_REGION_H
#define LMP_FIX_WALL_IMPULSE_REGION_H

#include "fix.h"
#include "impulse_wall.h"

#include <string>

namespace LAMMPS_NS {

class FixWallImpulseRegion : public Fix, public ImpulseWall {
 public:
  FixWallImpulseRegion(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  void find_wall_contacts(double reach, const std::vector<char> &atoms,
                          const std::vector<double> &spin_speed, std::vector<Contact> &contacts) override;

 private:
  std::string region_id;
  class Region *region;
  WallContactModels models;
  bool motion_reset;    // the restart file's region motion does not fit this region
};

}    // namespace LAMMPS_NS

#endif
#endif
