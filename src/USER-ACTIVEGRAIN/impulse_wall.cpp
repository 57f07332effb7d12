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
  for (int q = 0; q < NUM_SURFACE_QUANTITIES; ++q) n += COMPONENTS[q] * static_cast<int>(delivered.size());
  return n;
}

void ImpulseWall::clear_delivered(double phase, double threshold)
{
  std::fill(delivered.begin(), delivered.end(), ActiveGrain::Vec3());
  std::fill(impacts.begin(), impacts.end(), ActiveGrain::Vec3());
  std::fill(energy.begin(), energy.end(), ActiveGrain::Vec3());
  std::fill(wall_fix->virial, wall_fix->virial + ActiveGrain::NSYMMETRIC, 0.0);
  drive_phase = phase;
  impact_speed = threshold;
  max_wall_speed = 0.0;
}

void ImpulseWall::add_delivered_impulse(int surface, const ActiveGrain::Vec3 &J, double approach)
{
  delivered[surface] += J;
  if (impact_speed >= 0.0 && approach > impact_speed)
    impacts[surface] += ActiveGrain::Vec3(1.0, std::cos(drive_phase), std::sin(drive_phase));
}

void ImpulseWall::add_energy(int surface, double work, double dissipated, double overlap)
{
  energy[surface] += ActiveGrain::Vec3(work, dissipated, overlap);
}

void ImpulseWall::add_virial(const ActiveGrain::Vec3 &arm, const ActiveGrain::Vec3 &force)
{
  if (wall_fix->thermo_virial) ActiveGrain::add_outer_product(wall_fix->virial, arm, force);
}

double ImpulseWall::surface_output(MPI_Comm world, int k) const
{
  const int nsurfaces = static_cast<int>(delivered.size());
  int quantity = 0;
  while (k >= COMPONENTS[quantity] * nsurfaces) k -= COMPONENTS[quantity++] * nsurfaces;
  const int surface = k / COMPONENTS[quantity], component = k % COMPONENTS[quantity];
  double mine = 0.0, all = 0.0;
  switch (static_cast<SurfaceQuantity>(quantity)) {
    case IMPULSE: mine = (&delivered[surface].x)[component]; break;
    case IMPACTS: mine = (&impacts[surface].x)[component]; break;
    case ENERGY: mine = (&energy[surface].x)[component]; break;
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

ActiveGrain::ContactMaterial WallMaterials::checked(const char *e, const char *mu) const
{
  ActiveGrain::ContactMaterial m;
  m.e = utils::numeric(FLERR, e, false, lmp);
  m.mu = utils::numeric(FLERR, mu, false, lmp);
  check_material(error, style, m.e, m.mu);
  return m;
}

int WallMaterials::parse(int narg, char **arg, int iarg)
{
  const int ntypes = atom->ntypes;
  if (per_type.empty()) {
    per_type.resize(ntypes + 1);
    type_set.assign(ntypes + 1, false);
  }
  const std::string key = arg[iarg];
  if (key == "e" || key == "mu") {
    if (iarg + 2 > narg) error->all(FLERR, "{}: missing value after keyword {}", style, key);
    const double value = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    if (key == "e") check_material(error, style, value, 0.0);
    else check_material(error, style, 0.0, value);
    (key == "e" ? e_all : mu_all) = value;
    for (int t = 1; t <= ntypes; ++t)
      if (!type_set[t]) (key == "e" ? per_type[t].e : per_type[t].mu) = value;
    return iarg + 2;
  }
  if (key == "type") {
    if (iarg + 4 > narg) error->all(FLERR, "{}: keyword type needs a type and values e mu", style);
    int lo, hi;
    utils::bounds(FLERR, arg[iarg + 1], 1, ntypes, lo, hi, error);
    const ActiveGrain::ContactMaterial m = checked(arg[iarg + 2], arg[iarg + 3]);
    for (int t = lo; t <= hi; ++t) {
      per_type[t] = m;
      type_set[t] = true;
    }
    return iarg + 4;
  }
  return iarg;
}

void WallMaterials::check_complete() const
{
  for (int t = 1; t < (int) per_type.size(); ++t)
    if (!type_set[t] && (e_all < 0.0 || mu_all < 0.0))
      error->all(FLERR, "{}: no restitution e and friction mu for atom type {} (use keywords e and mu, or type)",
                 style, t);
  if (per_type.empty())
    error->all(FLERR, "{}: keywords e and mu are required", style);
}
