#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(polar/rod,ComputePolarRod);
// clang-format on
#else

#ifndef LMP_COMPUTE_POLAR_ROD_H
#define LMP_COMPUTE_POLAR_ROD_H

#include "compute.h"
#include "local_rods.h"

namespace LAMMPS_NS {

class ComputePolarRod : public Compute {
 public:
  ComputePolarRod(class LAMMPS *, int, char **);
  ~ComputePolarRod() override;
  void init() override;
  double compute_scalar() override;
  void compute_vector() override;
  void compute_local() override;
  double memory_usage() override;
  int pack_forward_comm(int n, int *list, double *buf, int pbc_flag, int *pbc) override
  {
    return rods.pack_positions(n, list, buf, pbc_flag, pbc);
  }
  void unpack_forward_comm(int n, int first, double *buf) override { rods.unpack_positions(n, first, buf); }

 private:
  LocalRods rods;
  double **rod_table = nullptr;    // per-rod local rows
  int max_rows = 0;
};

}    // namespace LAMMPS_NS

#endif
#endif
