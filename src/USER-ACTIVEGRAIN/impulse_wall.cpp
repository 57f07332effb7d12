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

