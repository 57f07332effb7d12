#include "compute_polar_rod.h"

#include "domain.h"
#include "error.h"
#include "memory.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;

static const char *const STYLE = "Compute polar/rod";

enum { POLAR, PX, PY, AXIS_Z_MEAN, NEMATIC, NRODS, NVECTOR };
enum { ID, X, Y, Z, POLAR_X, POLAR_Y, AXIS_Z, VX, VY, VZ, NCOLS };

ComputePolarRod::ComputePolarRod(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), rods(lmp, STYLE, true)
{
  if (narg != 3) error->all(FLERR, "{}: expected no arguments after the group, got {}", STYLE, narg - 3);
  scalar_flag = vector_flag = local_flag = 1;
  size_vector = NVECTOR;
  size_local_cols = NCOLS;
  size_local_rows = 0;
  extscalar = extvector = 0;
  timeflag = 1;
  comm_forward = LocalRods::POSITION_COLUMNS;
  vector = new double[NVECTOR];
}

ComputePolarRod::~ComputePolarRod()
{
  memory->destroy(rod_table);
  delete[] vector;
}

void ComputePolarRod::init()
{
  rods.check_provider();    // fails early, naming this style
}

double ComputePolarRod::compute_scalar()
{
  invoked_scalar = update->ntimestep;
  if (invoked_vector != update->ntimestep) compute_vector();
  scalar = vector[POLAR];
  return scalar;
}

// Over the rods, with p each rod's in-plane polar axis (docs/compute_polar_rod.rst): |<p>|,
// <p>, the mean z component of the 3-D axes (tilt), the nematic order |<exp(2 i theta)>| of p's
// angles, and the number of rods.
void ComputePolarRod::compute_vector()
{
  invoked_vector = update->ntimestep;
  rods.update(this, groupbit);
  enum { SUM_PX, SUM_PY, SUM_AXIS_Z, SUM_COS2, SUM_SIN2, SUM_COUNT, NSUM };
  double sum[NSUM] = {};
  for (const auto &rod : rods.rods()) {
    if (!rod.counted_here) continue;
    const double theta = std::atan2(rod.polar.y, rod.polar.x);
    sum[SUM_PX] += rod.polar.x;
    sum[SUM_PY] += rod.polar.y;
    sum[SUM_AXIS_Z] += rod.axis.z;
    sum[SUM_COS2] += std::cos(2 * theta);
    sum[SUM_SIN2] += std::sin(2 * theta);
    sum[SUM_COUNT] += 1;
  }
  double all[NSUM];
  MPI_Allreduce(sum, all, NSUM, MPI_DOUBLE, MPI_SUM, world);
  const double n = all[SUM_COUNT];
  for (int k = 0; k < NVECTOR; ++k) vector[k] = 0.0;
  vector[NRODS] = n;
  if (n == 0) return;
  vector[PX] = all[SUM_PX] / n;
  vector[PY] = all[SUM_PY] / n;
  vector[AXIS_Z_MEAN] = all[SUM_AXIS_Z] / n;
  vector[POLAR] = std::hypot(vector[PX], vector[PY]);
  vector[NEMATIC] = std::hypot(all[SUM_COS2], all[SUM_SIN2]) / n;
}

// One row per rod counted on this rank: id, centre of mass, polar axis, axis z, velocity.
void ComputePolarRod::compute_local()
{
  invoked_local = update->ntimestep;
  rods.update(this, groupbit);
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
    r[POLAR_X] = rod.polar.x;
    r[POLAR_Y] = rod.polar.y;
    r[AXIS_Z] = rod.axis.z;
    rod.body.v.store(&r[VX]);
  }
  size_local_rows = rows;
  array_local = rod_table;
}

double ComputePolarRod::memory_usage()
{
  return (double) max_rows * NCOLS * sizeof(double);
}
