#include "style_inputs.h"

#include "atom.h"
#include "error.h"
#include "fix.h"
#include "modify.h"

#include <algorithm>

using namespace LAMMPS_NS;

// Group all's bit: every atom, inserted ones included, is in it.
static constexpr int GROUP_ALL_BIT = 1;

void LAMMPS_NS::check_material(Error *error, const std::string &style, double e, double mu)
{
  if (e < 0.0 || e > 1.0)
    error->all(FLERR, "{}: restitution coefficient e = {} must be in [0, 1]", style, e);
  if (mu < 0.0) error->all(FLERR, "{}: friction coefficient mu = {} must be >= 0", style, mu);
}

double LAMMPS_NS::inserted_radius(LAMMPS *lmp, int type, int groupbit)
{
  double largest = 0.0;
  for (const char *style : {"^pour", "^deposit"})
    for (Fix *fix : lmp->modify->get_fix_by_style(style)) {
      // Inserted atoms join group all and the inserting fix's group.
      if (groupbit && groupbit != GROUP_ALL_BIT && groupbit != fix->groupbit) continue;
      int dim = type;    // extract() overwrites it
      auto *radius = static_cast<double *>(fix->extract("radius", dim));
      if (radius) largest = std::max(largest, *radius);
    }
  return largest;
}

double LAMMPS_NS::largest_radius(LAMMPS *lmp, int groupbit)
{
  Atom *atom = lmp->atom;
  double mine = 0.0, all = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) mine = std::max(mine, atom->radius[i]);
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_MAX, lmp->world);
  for (int t = 1; t <= atom->ntypes; t++) all = std::max(all, inserted_radius(lmp, t, groupbit));
  return all;
}
