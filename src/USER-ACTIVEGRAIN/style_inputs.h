// Checks and reads of inputs shared by pair gran/impulse and the wall fixes.
#pragma once

#include "pointers.h"

#include <set>
#include <string>

namespace LAMMPS_NS {

// Largest radius of the atoms of type `type` that fix pour or fix deposit will insert during a
// run (0 if none), read as GRANULAR's pair styles read it (the fixes' extract("radius")).
// With groupbit (a fix's group), only inserting fixes whose atoms join that group count.
double inserted_radius(LAMMPS *lmp, int type, int groupbit = 0);

// Largest radius of the atoms of group groupbit present now, on all ranks, or to be inserted into
// it by fix pour/deposit (all types).
double largest_radius(LAMMPS *lmp, int groupbit);

// Inputs that run without a word but do not do what they seem, checked by pair gran/impulse's
// init before a run (all ranks call it): a WARNING from rank 0, each once per key it adds to
// `warned` (the pair style's), when atoms are in the group of no time-integrating
// fix nor of fix freeze (contacts push them, they never move; not before run 0), or when slop is
// more than a tenth of the smallest particle diameter (particles sink that deep into each other).
void warn_silent_inputs(LAMMPS *lmp, const std::string &style, std::set<std::string> &warned, double slop);

}    // namespace LAMMPS_NS
