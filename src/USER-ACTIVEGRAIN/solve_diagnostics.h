// The health of pair gran/impulse's solves, over ranks (pair gran/impulse's outputs), with the
// errors and warnings a run needs: an atom larger than its neighbor cutoff allows, particles or
// walls that close more than half the neighbor skin in a step, impacts that keep hitting the
// sub-step cap. And the energy ledger of each step's contacts, summed and told to the walls.
#pragma once

#include "ag_contact_solver.h"
#include "contact_assembly.h"
#include "pointers.h"

namespace LAMMPS_NS {

class SolveDiagnostics : protected Pointers {
 public:
  // Maxima over all ranks: of the last step (substeps, shortfall), since the run's setup
  // (largest overlap, steps in which an impact hit the sub-step cap).
  struct Health {
    double substeps = 0.0, shortfall = 0.0, largest_overlap = 0.0, capped_steps = 0.0, resting_sweeps = 0.0;
  };
  // This rank's contacts of the last step (energy units).
  struct Energies {
    double dissipated_pair = 0.0, dissipated_wall = 0.0, overlap_work = 0.0, wall_work = 0.0;
  };

  SolveDiagnostics(LAMMPS *lmp, const char *style) : Pointers(lmp), style(style) {}

  // A run's setup: its maxima and warnings start afresh.
  void setup();
  // After a solve: largest_radius is the largest neighbor-cutoff radius of any type.
  const Health &record(const ActiveGrain::ContactSolver::Result &result,
                       const ContactAssembly::StepExtremes &extremes, double largest_radius, int max_substeps);
  // The energy ledger of the solved contacts (each on the rank that solved it).
  Energies tally_energy(const ActiveGrain::ContactSolver &solver, const ContactAssembly &assembly) const;

 private:
  void check_radius(double radius_excess, double largest_radius) const;
  void check_skin(double fastest, double wall_speed);
  void warn_capped(int max_substeps);

  const char *style;
  Health health;
  double largest_overlap = 0.0;    // this rank's, since the run's setup
  bigint capped_steps = 0;
  bigint next_cap_warning = 0;     // capped_steps at which to warn next (10, 100, 1000, ...)
  bool skin_warned = false;        // once per run
};

}    // namespace LAMMPS_NS
