// The projected (xy) area of a rod built from overlapping spheres is the area of the union of
// their discs, not the sum. Splitting that union exactly among the discs lets any per-atom
// binning (chunks) count each rod's true shape once.
#pragma once

#include "ag_math.h"

#include <vector>

namespace ActiveGrain {

// Area of the union of discs whose centres lie on one line, at positions `centres` along it
// (any order) with `radii`, split into one share per disc: disc k's share is the part of disc k
// inside its power-diagram cell. The shares add up to the union's area exactly.
std::vector<double> disc_chain_area_shares(const std::vector<double> &centres,
                                           const std::vector<double> &radii);

// A rod seen through its constituent spheres (centres on the rod's axis, tapered radii).
struct RodChain {
  Vec3 axis;                    // unit 3-D axis, from the widest sphere (tail) to the narrowest (nose)
  Vec3 polar;                   // the polar axis p as seen from above: axis projected on xy, unit length
  std::vector<double> shares;   // each sphere's share of the rod's projected area in the xy plane
};

// The axes and xy projected-area shares of a rod from its spheres' centres and radii.
// The centres must be unwrapped (one periodic image); at least two spheres of different radius
// are needed for the axis to be defined (otherwise axis and polar are zero).
RodChain project_rod_chain(const std::vector<Vec3> &centres, const std::vector<double> &radii);

}    // namespace ActiveGrain
