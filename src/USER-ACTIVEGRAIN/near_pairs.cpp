#include "near_pairs.h"

#include "atom.h"
#include "contact_ranks.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;

// x, y, z of an atom in x_built.
static constexpr int COORDS = 3;
// A pair closes at most by the sum of both atoms' moves: twice the largest.
static constexpr double ATOMS_PER_PAIR = 2.0;

void NearPairs::refresh(NeighList *list, const ContactRanks &ranks, double margin, double fastest)
{
  const int nall = atom->nlocal + atom->nghost;
  const bool stale = neighbor->lastcall != list_built || nall != nall_built || margin != built_margin ||
      ATOMS_PER_PAIR * (largest_change() + fastest * update->dt) >= margin;
  if (!stale) return;
  built_margin = margin;
  build(list, ranks);
}

// Largest displacement of an atom since the build, plus its growth in radius.
double NearPairs::largest_change() const
{
  double **x = atom->x;
  const double *radius = atom->radius;
  double largest2 = 0.0, growth = 0.0;
  for (int i = 0; i < nall_built; i++) {
    const double *x0 = &x_built[COORDS * i];
    const double dx = x[i][0] - x0[0], dy = x[i][1] - x0[1], dz = x[i][2] - x0[2];
    largest2 = std::max(largest2, dx * dx + dy * dy + dz * dz);
    growth = std::max(growth, radius[i] - radius_built[i]);
  }
  return std::sqrt(largest2) + growth;
}

void NearPairs::build(NeighList *list, const ContactRanks &ranks)
{
  double **x = atom->x;
  const double *radius = atom->radius;
  nall_built = atom->nlocal + atom->nghost;
  list_built = neighbor->lastcall;
  x_built.resize(COORDS * static_cast<std::size_t>(nall_built));
  radius_built.assign(radius, radius + nall_built);
  for (int i = 0; i < nall_built; i++) std::copy(x[i], x[i] + COORDS, &x_built[COORDS * i]);

  screened.clear();
  const int nlist = list->inum + (list->ghost ? list->gnum : 0);
  for (int ii = 0; ii < nlist; ii++) {
    const int i = list->ilist[ii];
    const int *jlist = list->firstneigh[i];
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (!ranks.may_solve_pair(i, j)) continue;
      const double dx = x[j][0] - x[i][0], dy = x[j][1] - x[i][1], dz = x[j][2] - x[i][2];
      const double reach = radius[i] + radius[j] + built_margin;
      if (dx * dx + dy * dy + dz * dz < reach * reach) screened.emplace_back(i, j);
    }
  }
}

double NearPairs::memory_usage() const
{
  return (double) screened.capacity() * sizeof(std::pair<int, int>) +
      (double) (x_built.capacity() + radius_built.capacity()) * sizeof(double);
}
