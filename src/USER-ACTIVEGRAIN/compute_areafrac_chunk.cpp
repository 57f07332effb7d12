#include "compute_areafrac_chunk.h"

#include "ag_math.h"

#include "atom.h"
#include "compute_chunk_atom.h"
#include "domain.h"
#include "error.h"
#include "memory.h"

#include <cmath>

using namespace LAMMPS_NS;

static const char *const STYLE = "Compute areafrac/chunk";

// Output columns, and the per-chunk sums they come from.
enum { PHI_BEADS, PHI_RODS, NRODS, POLAR_X, POLAR_Y, POLAR, NCOLS };
enum { BEAD_AREA, ROD_AREA, ROD_COUNT, ROD_PX, ROD_PY, NSUMS };

ComputeAreafracChunk::ComputeAreafracChunk(LAMMPS *lmp, int narg, char **arg) :
    ComputeChunk(lmp, narg, arg), rods(lmp, STYLE, false)
{
  if (narg != 4) error->all(FLERR, "{}: expected one argument, a compute chunk/atom ID", STYLE);
  if (!atom->radius_flag) error->all(FLERR, "{}: atom style must define radius (atom_style sphere)", STYLE);
  array_flag = 1;
  size_array_cols = NCOLS;
  size_array_rows = 0;
  size_array_rows_variable = 1;
  extarray = 0;
  comm_forward = LocalRods::POSITION_COLUMNS;
  ComputeAreafracChunk::init();
  ComputeAreafracChunk::allocate();
}

ComputeAreafracChunk::~ComputeAreafracChunk()
{
  memory->destroy(sums);
  memory->destroy(totals);
  memory->destroy(array);
}

void ComputeAreafracChunk::init()
{
  ComputeChunk::init();
  if (domain->dimension == 3 && domain->zperiodic == 0 && domain->zprd <= 0)
    error->all(FLERR, "{}: the box has no extent in z", STYLE);
}

void ComputeAreafracChunk::allocate()
{
  ComputeChunk::allocate();
  memory->destroy(sums);
  memory->destroy(totals);
  memory->destroy(array);
  maxchunk = nchunk;
  memory->create(sums, maxchunk, NSUMS, "areafrac/chunk:sums");
  memory->create(totals, maxchunk, NSUMS, "areafrac/chunk:totals");
  memory->create(array, maxchunk, NCOLS, "areafrac/chunk:array");
}

// Beads count pi r^2 in their chunk; a rod's projected area is split exactly among its atoms
// (so it counts once in all, across the chunks its atoms fall in), and so are its count and
// polarization.
void ComputeAreafracChunk::compute_array()
{
  ComputeChunk::compute_array();
  const int *ichunk = cchunk->ichunk;
  rods.update(this, groupbit);

  for (int c = 0; c < nchunk; ++c)
    for (int k = 0; k < NSUMS; ++k) sums[c][k] = 0.0;

  const double *radius = atom->radius;
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; ++i) {
    if (!(mask[i] & groupbit)) continue;
    const int c = ichunk[i] - 1;
    if (c < 0) continue;
    const int r = rods.rod_of_atom(i);
    if (r < 0) {
      sums[c][BEAD_AREA] += ActiveGrain::PI * radius[i] * radius[i];
      continue;
    }
    const auto &rod = rods.rods()[r];
    const double share = rods.area_share(i);
    sums[c][ROD_AREA] += share;
    sums[c][ROD_COUNT] += share / rod.area;
    sums[c][ROD_PX] += share * rod.polar.x;
    sums[c][ROD_PY] += share * rod.polar.y;
  }
  MPI_Allreduce(&sums[0][0], &totals[0][0], nchunk * NSUMS, MPI_DOUBLE, MPI_SUM, world);

  // A chunk's area is its volume over the box height: the bins must span the cell in z.
  const double height = domain->dimension == 3 ? domain->zprd : 1.0;
  for (int c = 0; c < nchunk; ++c) {
    const double volume = cchunk->chunk_volume_vec ? cchunk->chunk_volume_vec[c] : cchunk->chunk_volume_scalar;
    const double area = volume / height;
    const double *t = totals[c];
    array[c][PHI_BEADS] = t[BEAD_AREA] / area;
    array[c][PHI_RODS] = t[ROD_AREA] / area;
    array[c][NRODS] = t[ROD_COUNT];
    array[c][POLAR_X] = t[ROD_AREA] > 0 ? t[ROD_PX] / t[ROD_AREA] : 0.0;
    array[c][POLAR_Y] = t[ROD_AREA] > 0 ? t[ROD_PY] / t[ROD_AREA] : 0.0;
    array[c][POLAR] = std::hypot(array[c][POLAR_X], array[c][POLAR_Y]);
  }
}

double ComputeAreafracChunk::memory_usage()
{
  return ComputeChunk::memory_usage() + (double) maxchunk * (2 * NSUMS + NCOLS) * sizeof(double);
}
