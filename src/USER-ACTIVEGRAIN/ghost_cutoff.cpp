#include "ghost_cutoff.h"

#include "lammps.h"
#include "neighbor.h"

#include <cmath>

using namespace LAMMPS_NS;

// Relative margin for spans measured from atom positions (round-off of a rotated body).
static constexpr double SPAN_MARGIN = 1e-6;
static constexpr int QUOTED_DIGITS = 3;

double LAMMPS_NS::ghost_cutoff_needed(LAMMPS *lmp, double span)
{
  return span + lmp->neighbor->cutneighmax;
}

double LAMMPS_NS::ghost_cutoff_quoted(LAMMPS *lmp, double span)
{
  const double needed = ghost_cutoff_needed(lmp, span * (1.0 + SPAN_MARGIN));
  if (!(needed > 0.0)) return needed;
  const double unit = std::pow(10.0, std::floor(std::log10(needed)) - (QUOTED_DIGITS - 1));
  return std::ceil(needed / unit) * unit;
}
