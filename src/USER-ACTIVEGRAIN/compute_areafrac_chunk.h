#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(areafrac/chunk,ComputeAreafracChunk);
// clang-format on
#else

#ifndef LMP_COMPUTE_AREAFRAC_CHUNK_H
#define LMP_COMPUTE_AREAFRAC_CHUNK_H

#include "compute_chunk.h"
#include "local_rods.h"

namespace LAMMPS_NS {

class ComputeAreafracChunk : public ComputeChunk {
 public:
  ComputeAreafracChunk(class LAMMPS *, int, char **);
  ~ComputeAreafracChunk() override;
  void init() override;
  void compute_array() override;
  double memory_usage() override;
  int pack_forward_comm(int n, int *list, double *buf, int pbc_flag, int *pbc) override
  {
    return rods.pack_positions(n, list, buf, pbc_flag, pbc);
  }
  void unpack_forward_comm(int n, int first, double *buf) override { rods.unpack_positions(n, first, buf); }

 private:
  LocalRods rods;
  double **sums = nullptr, **totals = nullptr;    // this rank's and all ranks' per-chunk sums

  void allocate() override;
};

}    // namespace LAMMPS_NS

#endif
#endif
