// Shared input for the rod tests: one paper rod (SI units) in a periodic box.
#pragma once

#include <cmath>
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

// Radii along the template are linear, r = a + k x: tilted by asin(-k) (nose down), the rod lies
// flat on a plane, its spheres touching it at once.
inline double flat_tilt_degrees(double tail = TAIL, double nose = NOSE)
{
  return std::asin(-0.5 * (nose - tail) / LENGTH) * 180.0 / M_PI;
}

// Commands that create one rod of template `rod` (tail and nose diameters as given to
// rod_template) centred at (0, 0), along `heading` degrees in the plane, lying flat with its lowest
// points `lift` above z = 0 (a box that holds z = 5e-4).
inline std::string flat_rod(double lift, double heading = 30.0, double tail = TAIL, double nose = NOSE)
{
  return "create_atoms 0 single 0 0 5e-4 mol rod 1 units box rotate 0 0 0 1\n"
         "displace_atoms all rotate 0 0 5e-4 0 1 0 " + std::to_string(flat_tilt_degrees(tail, nose)) +
         " units box\n"
         "displace_atoms all rotate 0 0 5e-4 0 0 1 " + std::to_string(heading) + " units box\n"
         "variable bottom atom z-radius\ncompute lowest all reduce min v_bottom\n"
         "thermo_style custom step c_lowest\nrun 0 post no\n"
         "variable lift equal " + std::to_string(lift) + "-c_lowest\n"
         "displace_atoms all move 0 0 ${lift} units box\n";
}

inline std::string rod_template(const std::string &file, double tail = TAIL, double nose = NOSE)
{
  return "rod_template rod length " + std::to_string(LENGTH) + " tail " + std::to_string(tail) +
      " nose " + std::to_string(nose) + " spheres " + std::to_string(SPHERES) + " density " +
      std::to_string(DENSITY) + " types 1 2 3 file " + file + "\n";
}

}    // namespace rod_deck
