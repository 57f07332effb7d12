// The projected (xy) area of a rod built from overlapping spheres is the area of the union of
// their discs, not the sum. Splitting that union exactly among the discs lets any per-atom
// binning (chunks) count each rod's true shape once.
#pragma once

#include <vector>

namespace ActiveGrain {

// Area of the union of discs whose centres lie on one line, at positions `centres` along it
// (any order) with `radii`, split into one share per disc: disc k's share is the part of disc k
// inside its power-diagram cell. The shares add up to the union's area exactly.
std::vector<double> disc_chain_area_shares(const std::vector<double> &centres,
                                           const std::vector<double> &radii);

}    // namespace ActiveGrain
