#include "solve_diagnostics.h"

#include "ag_contact_energy.h"
#include "comm.h"
#include "error.h"
#include "impulse_wall.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>

using namespace LAMMPS_NS;

static constexpr bigint FIRST_CAP_WARNING = 10;    // then every tenfold
static constexpr bigint CAP_WARNING_FACTOR = 10;
// Relative to the largest radius: an atom larger than its type's cutoff radius by more is refused.
static constexpr double RADIUS_TOLERANCE = 1e-12;
// LAMMPS rebuilds neighbor lists after an atom moved half the skin.
static constexpr double SKIN_FRACTION = 0.5;

void SolveDiagnostics::setup()
{
  health = Health();
  largest_overlap = 0.0;
  capped_steps = 0;
  next_cap_warning = FIRST_CAP_WARNING;
  skin_warned = false;
}

const SolveDiagnostics::Health &SolveDiagnostics::record(const ActiveGrain::ContactSolver::Result &result,
                                                         const ContactAssembly::StepExtremes &extremes,
                                                         double largest_radius, int max_substeps)
{
  largest_overlap = std::max(largest_overlap, extremes.overlap);
  enum Reduced { SUBSTEPS, SHORTFALL, OVERLAP, CAPPED, FASTEST, WALL_SPEED, RADIUS, RESTING_SWEEPS, NUM_REDUCED };
  double mine[NUM_REDUCED] = {(double) result.substeps, result.shortfall, largest_overlap,
                              result.converged ? 0.0 : 1.0, extremes.fastest, extremes.wall_speed,
                              extremes.radius_excess, (double) result.resting_sweeps};
  double all[NUM_REDUCED];
  if (comm->nprocs > 1) MPI_Allreduce(mine, all, NUM_REDUCED, MPI_DOUBLE, MPI_MAX, world);
  else std::copy(mine, mine + NUM_REDUCED, all);
  if (all[CAPPED] > 0.0) capped_steps++;
  check_radius(all[RADIUS], largest_radius);
  check_skin(all[FASTEST], all[WALL_SPEED]);
  health = {all[SUBSTEPS], all[SHORTFALL], all[OVERLAP], (double) capped_steps, all[RESTING_SWEEPS]};
  warn_capped(max_substeps);
  return health;
}

void SolveDiagnostics::check_radius(double radius_excess, double largest_radius) const
{
  if (radius_excess > RADIUS_TOLERANCE * largest_radius)
    error->all(FLERR, "{}: an atom is larger by {:.3g} than the largest radius of its type known at "
               "the run's setup (atoms then present, fix pour and fix deposit), from which the "
               "neighbor cutoff is made: its contacts would be missed. Insert atoms with fix pour or "
               "fix deposit, or between runs", style, radius_excess);
}

// A pair that closes more than the other half of the skin in one step can be missing from the
// neighbor list when it is about to touch. Walls are searched up to the skin from each atom: a
// vibrating plate closes a gap at its own speed plus the particle's, held to the same margin.
void SolveDiagnostics::check_skin(double fastest, double wall_speed)
{
  const double pair_closing = 2.0 * fastest * update->dt;
  const double wall_closing = (fastest + wall_speed) * update->dt;
  if (skin_warned || !(std::max(pair_closing, wall_closing) > SKIN_FRACTION * neighbor->skin)) return;
  if (comm->me == 0) {
    if (pair_closing >= wall_closing)
      error->warning(FLERR, "{}: two particles can close {:.3g} in one step (2 x largest |v| + "
                     "|omega| r, times dt), more than half the neighbor skin {:.3g}: contacts can be "
                     "missed; use a larger skin or a smaller time step", style, pair_closing, neighbor->skin);
    else
      error->warning(FLERR, "{}: a particle and a wall can close {:.3g} in one step (largest |v| + "
                     "|omega| r plus the wall speed {:.3g}, times dt), more than half the neighbor "
                     "skin {:.3g}: contacts can be missed; use a larger skin or a smaller time step",
                     style, wall_closing, wall_speed, neighbor->skin);
  }
  skin_warned = true;
}

void SolveDiagnostics::warn_capped(int max_substeps)
{
  if (capped_steps != next_cap_warning) return;
  if (comm->me == 0)
    error->warning(FLERR, "{}: in {} steps of this run a compliant impact did not end within {} sub-steps",
                   style, capped_steps, max_substeps);
  next_cap_warning *= CAP_WARNING_FACTOR;
}

SolveDiagnostics::Energies SolveDiagnostics::tally_energy(const ActiveGrain::ContactSolver &solver,
                                                          const ContactAssembly &assembly) const
{
  Energies sums;
  for (int c = 0; c < solver.num_contacts(); c++) {
    const ContactAssembly::AtomContact &ac = assembly.atoms_of(c);
    const ActiveGrain::ContactEnergy energy =
        ActiveGrain::contact_energy(solver, c, ac.velocity_before, ac.approach, ac.wall_velocity);
    sums.overlap_work += energy.overlap_work;
    if (!ac.wall) {
      sums.dissipated_pair += energy.dissipated;
      continue;
    }
    sums.wall_work += energy.wall_work;
    sums.dissipated_wall += energy.dissipated;
    ac.wall->add_energy(ac.surface, energy.wall_work, energy.dissipated, energy.overlap_work);
  }
  return sums;
}
