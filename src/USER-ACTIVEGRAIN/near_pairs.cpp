#include "near_pairs.h"

#include "atom.h"
#include "contact_ranks.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;

void NearPairs::refresh(NeighList *list, const ContactRanks &ranks, double margin, double fastest)
{
  const int nall = atom->nlocal + atom->nghost;
  const bool stale = neighbor->lastcall != list_built_ || nall != nall_ || margin != margin_ ||
      2.0 * (largest_change() + fastest * update->dt) >= margin;
  if (!stale) return;
  margin_ = margin;
  build(list, ranks);
}

// Largest displacement of an atom since the build, plus its growth in radius.
double NearPairs::largest_change() const
{
  double **x = atom->x;
  const double *radius = atom->radius;
  double largest2 = 0.0, growth = 0.0;
  for (int i = 0; i < nall_; i++) {
    const double *x0 = &x_built_[3 * i];
    const double dx = x[i][0] - x0[0], dy = x[i][1] - x0[1], dz = x[i][2] - x0[2];
    largest2 = std::max(largest2, dx * dx + dy * dy + dz * dz);
    growth = std::max(growth, radius[i] - radius_built_[i]);
  }
  return std::sqrt(largest2) + growth;
}

void NearPairs::build(NeighList *list, const ContactRanks &ranks)
{
  double **x = atom->x;
  const double *radius = atom->radius;
  nall_ = atom->nlocal + atom->nghost;
  list_built_ = neighbor->lastcall;
  x_built_.resize(3 * static_cast<std::size_t>(nall_));
  radius_built_.assign(radius, radius + nall_);
  for (int i = 0; i < nall_; i++) std::copy(x[i], x[i] + 3, &x_built_[3 * i]);

  pairs_.clear();
  const int nlist = list->inum + (list->ghost ? list->gnum : 0);
  for (int ii = 0; ii < nlist; ii++) {
    const int i = list->ilist[ii];
    const int *jlist = list->firstneigh[i];
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (!ranks.may_solve_pair(i, j)) continue;
      const double dx = x[j][0] - x[i][0], dy = x[j][1] - x[i][1], dz = x[j][2] - x[i][2];
      const double reach = radius[i] + radius[j] + margin_;
      if (dx * dx + dy * dy + dz * dz < reach * reach) pairs_.emplace_back(i, j);
    }
  }
}

double NearPairs::memory_usage() const
{
  return (double) pairs_.capacity() * sizeof(std::pair<int, int>) +
      (double) (x_built_.capacity() + radius_built_.capacity()) * sizeof(double);
}
