#include "impulse_wall.h"

#include "atom.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "lammps.h"
#include "modify.h"
#include "utils.h"

#include <cmath>

using namespace LAMMPS_NS;

int ImpulseWall::num_surface_outputs() const
{
  int n = 0;
  for (int q = 0; q < NUM_SURFACE_QUANTITIES; ++q) n += COMPONENTS[q] * static_cast<int>(delivered_.size());
  return n;
}

void ImpulseWall::clear_delivered(double drive_phase, double impact_speed)
{
  std::fill(delivered_.begin(), delivered_.end(), ActiveGrain::Vec3());
  std::fill(impacts_.begin(), impacts_.end(), ActiveGrain::Vec3());
  std::fill(energy_.begin(), energy_.end(), ActiveGrain::Vec3());
  std::fill(fix_->virial, fix_->virial + 6, 0.0);
  drive_phase_ = drive_phase;
  impact_speed_ = impact_speed;
  wall_speed_ = 0.0;
}

void ImpulseWall::add_delivered_impulse(int surface, const ActiveGrain::Vec3 &J, double approach)
{
  delivered_[surface] += J;
  if (impact_speed_ >= 0.0 && approach > impact_speed_)
    impacts_[surface] += ActiveGrain::Vec3(1.0, std::cos(drive_phase_), std::sin(drive_phase_));
}

void ImpulseWall::add_energy(int surface, double work, double dissipated, double overlap)
{
  energy_[surface] += ActiveGrain::Vec3(work, dissipated, overlap);
}

void ImpulseWall::add_virial(const ActiveGrain::Vec3 &arm, const ActiveGrain::Vec3 &force)
{
  if (fix_->thermo_virial) ActiveGrain::add_outer_product(fix_->virial, arm, force);
}

double ImpulseWall::surface_output(MPI_Comm world, int k) const
{
  const int nsurfaces = static_cast<int>(delivered_.size());
  int quantity = 0;
  while (k >= COMPONENTS[quantity] * nsurfaces) k -= COMPONENTS[quantity++] * nsurfaces;
  const int surface = k / COMPONENTS[quantity], component = k % COMPONENTS[quantity];
  double mine = 0.0, all = 0.0;
  switch (static_cast<SurfaceQuantity>(quantity)) {
    case IMPULSE: mine = (&delivered_[surface].x)[component]; break;
    case IMPACTS: mine = (&impacts_[surface].x)[component]; break;
    case ENERGY: mine = (&energy_[surface].x)[component]; break;
    case NUM_SURFACE_QUANTITIES: break;
  }
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_SUM, world);
  return all;
}

void LAMMPS_NS::check_wall_host(LAMMPS *lmp, const std::string &style)
{
  if (!lmp->force->pair_match("^gran/impulse", 0))
    lmp->error->all(FLERR, "{} requires pair_style gran/impulse", style);
  if (!lmp->atom->radius_flag) lmp->error->all(FLERR, "{} requires atom attribute radius", style);
}

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
      if (groupbit && groupbit != 1 && groupbit != fix->groupbit) continue;
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

ActiveGrain::ContactMaterial WallMaterials::checked(const char *e, const char *mu) const
{
  ActiveGrain::ContactMaterial m;
  m.e = utils::numeric(FLERR, e, false, lmp);
  m.mu = utils::numeric(FLERR, mu, false, lmp);
  check_material(error, style_, m.e, m.mu);
  return m;
}

int WallMaterials::parse(int narg, char **arg, int iarg)
{
  const int ntypes = atom->ntypes;
  if (per_type_.empty()) {
    per_type_.resize(ntypes + 1);
    set_.assign(ntypes + 1, false);
  }
  const std::string key = arg[iarg];
  if (key == "e" || key == "mu") {
    if (iarg + 2 > narg) error->all(FLERR, "{}: missing value after keyword {}", style_, key);
    const double value = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    if (key == "e") check_material(error, style_, value, 0.0);
    else check_material(error, style_, 0.0, value);
    (key == "e" ? e_all_ : mu_all_) = value;
    for (int t = 1; t <= ntypes; ++t)
      if (!set_[t]) (key == "e" ? per_type_[t].e : per_type_[t].mu) = value;
    return iarg + 2;
  }
  if (key == "type") {
    if (iarg + 4 > narg) error->all(FLERR, "{}: keyword type needs a type and values e mu", style_);
    int lo, hi;
    utils::bounds(FLERR, arg[iarg + 1], 1, ntypes, lo, hi, error);
    const ActiveGrain::ContactMaterial m = checked(arg[iarg + 2], arg[iarg + 3]);
    for (int t = lo; t <= hi; ++t) {
      per_type_[t] = m;
      set_[t] = true;
    }
    return iarg + 4;
  }
  return iarg;
}

void WallMaterials::check_complete() const
{
  for (int t = 1; t < (int) per_type_.size(); ++t)
    if (!set_[t] && (e_all_ < 0.0 || mu_all_ < 0.0))
      error->all(FLERR, "{}: no restitution e and friction mu for atom type {} (use keywords e and mu, or type)",
                 style_, t);
  if (per_type_.empty())
    error->all(FLERR, "{}: keywords e and mu are required", style_);
}
