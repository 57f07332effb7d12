// The settings of pair gran/impulse in one place: its keywords, their checks and defaults, and
// their layout in restart files. The contact solver's part is the core's SolverSettings; the
// rest is how contacts are assembled (overlap correction, order).
#pragma once

#include "ag_contact_model.h"
#include "ag_solver_settings.h"
#include "contact_assembly.h"
#include "pointers.h"

#include <cstdio>

namespace LAMMPS_NS {

struct GranImpulseSettings {
  ActiveGrain::SolverSettings solver;
  double beta = 0.2;    // overlaps leave at >= beta * (overlap - slop) / dt
  double slop = 0.0;
  ContactOrder order = ContactOrder::SHUFFLE;

  // pair_style gran/impulse [resolution N] [beta B] [slop S] [order shuffle|tag|reverse]
  // [window W|step] [resting yes|newton|no|V] [tolerance T] [max_sweeps N]; every setting not given
  // takes its default. An ERROR naming the style and keyword for a value out of its range.
  void parse(LAMMPS *lmp, const char *style, int narg, char **arg);
  void write_restart(FILE *fp) const;
  void read_restart(LAMMPS *lmp, const char *style, FILE *fp);    // rank 0 reads, all get it
  // The contact models' coefficients per type pair in the restart file read_restart() read (files
  // before the tangential law: e and mu only); rank 0's.
  int restart_model_coeffs = ActiveGrain::ContactModel::NUM_COEFFS;
};

}    // namespace LAMMPS_NS
