// The one ghost cutoff rule of rigid bodies, quoted by fix rigid/rod and pair gran/impulse.
#pragma once

namespace LAMMPS_NS {

class LAMMPS;

// On more than one rank, the rank that solves a body's contacts must see, as ghosts, the whole
// body and every neighbor of each of its atoms: span (largest distance between two atom centres
// of a body) + neighbor cutoff (largest contact distance plus skin). One rank needs less (the
// body's extent), but the value quoted is this one, valid on any number of ranks.
double ghost_cutoff_needed(LAMMPS *lmp, double span);

// What `use comm_modify cutoff X` quotes: the rule rounded up to 3 significant digits (with a
// margin for round-off in the measured span), so that X as printed passes the check.
double ghost_cutoff_quoted(LAMMPS *lmp, double span);

}    // namespace LAMMPS_NS
