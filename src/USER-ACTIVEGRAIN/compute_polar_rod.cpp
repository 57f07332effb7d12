#include "compute_polar_rod.h"

#include "domain.h"
#include "error.h"
#include "memory.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;

enum { POLAR, PX, PY, PZ, NEMATIC, NRODS, NVECTOR };
enum { ID, X, Y, Z, AXIS_X, AXIS_Y, AXIS_Z, VX, VY, VZ, NCOLS };

ComputePolarRod::ComputePolarRod(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), rods(lmp, "polar/rod", true)
{
  if (narg != 3) error->all(FLERR, "Compute polar/rod: expected no arguments after the group, got {}", narg - 3);
  scalar_flag = vector_flag = local_flag = 1;
  size_vector = NVECTOR;
  size_local_cols = NCOLS;
  size_local_rows = 0;
  extscalar = extvector = 0;
  timeflag = 1;
  vector = new double[NVECTOR];
}

ComputePolarRod::~ComputePolarRod()
{
  memory->destroy(rod_table);
  delete[] vector;
}

void ComputePolarRod::init()
{
  rods.update(groupbit);    // fails early, naming this style, without a rod fix
}

double ComputePolarRod::compute_scalar()
{
  invoked_scalar = update->ntimestep;
  if (invoked_vector != update->ntimestep) compute_vector();
  scalar = vector[POLAR];
  return scalar;
}

// |<p>|, <p>, the 2D nematic order of the in-plane axes, and the number of rods.
void ComputePolarRod::compute_vector()
{
  invoked_vector = update->ntimestep;
  rods.update(groupbit);
  double sum[6] = {0, 0, 0, 0, 0, 0};    // px, py, pz, cos 2theta, sin 2theta, count
  for (const auto &rod : rods.rods()) {
    if (!rod.counted_here) continue;
    const double theta = std::atan2(rod.axis.y, rod.axis.x);
    sum[0] += rod.axis.x;
    sum[1] += rod.axis.y;
    sum[2] += rod.axis.z;
    sum[3] += std::cos(2 * theta);
    sum[4] += std::sin(2 * theta);
    sum[5] += 1;
  }
  double all[6];
  MPI_Allreduce(sum, all, 6, MPI_DOUBLE, MPI_SUM, world);
  const double n = all[5];
  for (int k = 0; k < NVECTOR; ++k) vector[k] = 0.0;
  vector[NRODS] = n;
  if (n == 0) return;
  vector[PX] = all[0] / n;
  vector[PY] = all[1] / n;
  vector[PZ] = all[2] / n;
  vector[POLAR] = std::sqrt(vector[PX] * vector[PX] + vector[PY] * vector[PY] + vector[PZ] * vector[PZ]);
  vector[NEMATIC] = std::sqrt(all[3] * all[3] + all[4] * all[4]) / n;
}

// One row per rod counted on this rank: id, centre of mass, axis, velocity.
void ComputePolarRod::compute_local()
{
  invoked_local = update->ntimestep;
  rods.update(groupbit);
  int rows = 0;
  for (const auto &rod : rods.rods()) rows += rod.counted_here;
  if (rows > max_rows) {
    max_rows = rows;
    memory->destroy(rod_table);
    memory->create(rod_table, max_rows, NCOLS, "polar/rod:rod_table");
  }
  int row = 0;
  for (const auto &rod : rods.rods()) {
    if (!rod.counted_here) continue;
    double *r = rod_table[row++];
    r[ID] = rod.id;
    double com[3];
    rod.body.com.store(com);
    domain->remap(com);
    r[X] = com[0]; r[Y] = com[1]; r[Z] = com[2];
    rod.axis.store(&r[AXIS_X]);
    rod.body.v.store(&r[VX]);
  }
  size_local_rows = rows;
  array_local = rod_table;
}

double ComputePolarRod::memory_usage()
{
  return (double) max_rows * NCOLS * sizeof(double);
}
