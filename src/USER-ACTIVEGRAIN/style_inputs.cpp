#include "style_inputs.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix.h"
#include "modify.h"
#include "update.h"
#include "utils.h"

#include <algorithm>
#include <cfloat>
#include <set>
#include <vector>

using namespace LAMMPS_NS;

// Group all's bit: every atom, inserted ones included, is in it.
static constexpr int GROUP_ALL_BIT = 1;
// A slop above this fraction of the smallest particle diameter gets a WARNING.
static constexpr double LARGEST_SLOP_DIAMETERS = 0.1;

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

// Atoms in the group of no time-integrating fix (fix nve/sphere, fix rigid/rod for its rods'
// atoms, ...) nor of fix freeze (bodies of infinite mass for the contacts): the solve gives them
// velocity changes that nothing applies, so they sit still while contacts push them.
static void warn_unintegrated_atoms(LAMMPS *lmp, const std::string &style, std::set<std::string> &warned)
{
  Atom *atom = lmp->atom;
  int integrated = 0;
  for (Fix *fix : lmp->modify->get_fix_list())
    if (fix->time_integrate || utils::strmatch(fix->style, "^freeze")) integrated |= fix->groupbit;
  bigint mine = 0, all = 0;
  std::vector<int> local_types(atom->ntypes + 1, 0), types(atom->ntypes + 1, 0);
  for (int i = 0; i < atom->nlocal; i++)
    if (!(atom->mask[i] & integrated)) {
      mine++;
      local_types[atom->type[i]] = 1;
    }
  MPI_Allreduce(&mine, &all, 1, MPI_LMP_BIGINT, MPI_SUM, lmp->world);
  MPI_Allreduce(local_types.data(), types.data(), atom->ntypes + 1, MPI_INT, MPI_MAX, lmp->world);
  if (all == 0 || lmp->comm->me != 0 || !warned.insert("unintegrated").second) return;
  std::string listed;
  for (int t = 1; t <= atom->ntypes; t++)
    if (types[t]) listed += (listed.empty() ? "" : " ") + std::to_string(t);
  lmp->error->warning(FLERR, "{}: {} of {} atoms (types {}) are in the group of no time-integrating fix (fix "
                      "nve/sphere, fix rigid/rod, ...) nor of fix freeze: contacts push them but they never move; "
                      "integrate them (e.g. fix ID GROUP nve/sphere), freeze them (fix freeze) or delete them",
                      style, all, atom->natoms, listed);
}

// Overlaps up to slop are not pushed apart: with slop a sizeable part of a diameter, particles
// sink that deep into each other and into the plates.
static void warn_large_slop(LAMMPS *lmp, const std::string &style, std::set<std::string> &warned, double slop)
{
  if (slop <= 0.0) return;
  Atom *atom = lmp->atom;
  double mine = DBL_MAX, smallest = DBL_MAX;
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->radius[i] > 0.0) mine = std::min(mine, 2.0 * atom->radius[i]);
  MPI_Allreduce(&mine, &smallest, 1, MPI_DOUBLE, MPI_MIN, lmp->world);
  if (smallest == DBL_MAX || slop <= LARGEST_SLOP_DIAMETERS * smallest) return;
  if (lmp->comm->me != 0 || !warned.insert(fmt::format("slop {}", slop)).second) return;
  lmp->error->warning(FLERR, "{}: slop {} is more than a tenth of the smallest particle diameter {:.6g}: overlaps "
                      "up to slop are never pushed apart, so particles sink that deep into each other and into "
                      "the walls; take slop a small fraction of a diameter (0.01 d)", style, slop, smallest);
}

void LAMMPS_NS::warn_silent_inputs(LAMMPS *lmp, const std::string &style, std::set<std::string> &warned,
                                   double slop)
{
  // Only before a run: other commands (delete_atoms overlap, write_data) init the styles too,
  // perhaps before the deck has defined its integrators.
  if (lmp->update->whichflag != 1) return;
  if (lmp->update->nsteps > 0) warn_unintegrated_atoms(lmp, style, warned);    // (run 0 moves nothing)
  warn_large_slop(lmp, style, warned, slop);
}
