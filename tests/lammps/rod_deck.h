// Shared input for the rod tests: one paper rod (SI units) in a periodic box.
#pragma once

#include <string>

namespace rod_deck {

// Paper rod: 4.5 mm, tail 1.1 mm, nose 0.7 mm, brass.
constexpr double LENGTH = 4.5e-3, TAIL = 1.1e-3, NOSE = 0.7e-3, DENSITY = 8500.0;
constexpr int SPHERES = 9;

inline std::string box(double half = 6e-3)
{
  const std::string h = std::to_string(half);
  return "units si\n"
         "atom_style sphere\n"
         "atom_modify map array\n"
         "fix molecule_ids all property/atom mol ghost yes\n"
         "boundary p p p\n"
         "region box block -" + h + " " + h + " -" + h + " " + h + " -" + h + " " + h + "\n"
         "create_box 3 box\n";
}

inline std::string rod_template(const std::string &file, double tail = TAIL, double nose = NOSE)
{
  return "rod_template rod length " + std::to_string(LENGTH) + " tail " + std::to_string(tail) +
      " nose " + std::to_string(nose) + " spheres " + std::to_string(SPHERES) + " density " +
      std::to_string(DENSITY) + " types 1 2 3 file " + file + "\n";
}

}    // namespace rod_deck
