// Shared by the walking tests: runs examples/single-rod/in.single-rod (rods between vibrating
// plates, paper parameters unless overridden) and measures each rod's mean velocity along its
// own polar axis in the plate plane, <v_cm . p_xy / |p_xy|>, inside LAMMPS.
#pragma once

#include "lammps.h"
#include "library.h"

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace rod_walking {

constexpr double SETTLE = 0.1;     // s: let the rods find the plates before measuring
constexpr double MEASURE = 2.0;    // s

// Commands that measure, from now on, the speed of rods 1..nrods along their own axes (rod k is
// molecule k): averaged every 10 steps over `seconds`.
inline std::string measure(int nrods, double seconds = MEASURE)
{
  std::string cmd, values;
  for (int k = 1; k <= nrods; ++k) {
    const std::string K = std::to_string(k);
    cmd += "group rod" + K + " molecule " + K + "\n"
           "compute polar" + K + " rod" + K + " reduce ave f_rods[1] f_rods[2]\n"
           "variable along" + K + " equal (vcm(rod" + K + ",x)*c_polar" + K + "[1]+vcm(rod" + K +
        ",y)*c_polar" + K + "[2])/sqrt(c_polar" + K + "[1]^2+c_polar" + K + "[2]^2)\n";
    values += " v_along" + K;
  }
  cmd += "variable nmeasure equal 10*round(" + std::to_string(seconds) + "/dt/10)\n"
         "fix speed all ave/time 10 1 10" + values + " ave running\n"
         "run ${nmeasure}\n";
  return cmd;
}

// in.single-rod's default plate roughness: rms slope, correlation length, seed.
constexpr const char *DECK_ROUGHNESS = "0.06 5e-6 12345";

// The styles of in.single-rod (paper rods and plates, with the given roughness), for atoms read
// back from a data or restart file; the rod template is written to mol_file.
inline std::string single_rod_styles(const std::string &mol_file, const std::string &roughness,
                                     bool pair_style = true)
{
  return "comm_modify vel yes cutoff 6e-3\n"
         "rod_template rod length 4.5e-3 tail 1.1e-3 nose 0.7e-3 spheres 9 density 8500 types 1 2 3 "
         "file " + mol_file + "\n"
         "neigh_modify exclude molecule/intra all\n" +
         std::string(pair_style ? "pair_style gran/impulse window 5e-6\npair_coeff * * 0.3 0.05\n" : "") +
         "fix rods all rigid/rod molecule mol rod\n"
         "fix plates all wall/impulse zlo 0.0 gap 1.12e-3 lid moving vibrate 4.0e-5 200 0.0 e 0.1 mu 0.03 "
         "rough " + roughness + "\n"
         "fix gravity all gravity 9.81 vector 0 0 -1\n"
         "compute tsphere all temp/sphere\nthermo_modify temp tsphere\n";
}

// The deck's variables for flat plates (the deterministic model; the deck's default is calibrated
// roughness), unless `vars` set the roughness.
inline std::map<std::string, std::string> flat_plates(std::map<std::string, std::string> vars)
{
  vars.emplace("rough", "0");
  return vars;
}

// Commands: every index variable of the deck set by `vars`, then the deck, then per-rod speed
// along the axis averaged every 10 steps over `seconds`.
inline std::string deck(const std::map<std::string, std::string> &vars, int nrods, double seconds = MEASURE)
{
  std::string cmd;
  for (const auto &[name, value] : vars) cmd += "variable " + name + " index " + value + "\n";
  cmd += "variable time index " + std::to_string(SETTLE) + "\n";
  cmd += "include " ACTIVEGRAIN_SOURCE_DIR "/examples/single-rod/in.single-rod\n"
         "undump bodies\nthermo 0\n";
  return cmd + measure(nrods, seconds);
}

// Mean speed along the own axis of each rod (m/s), the same on every rank.
inline std::vector<double> speeds(void *lmp, int nrods)
{
  std::vector<double> v;
  for (int k = 0; k < nrods; ++k)
  {
    // fix ave/time of one value is a scalar, of several a vector.
    auto *value = (double *) lammps_extract_fix(lmp, "speed", LMP_STYLE_GLOBAL,
                                                nrods == 1 ? LMP_TYPE_SCALAR : LMP_TYPE_VECTOR, k, 0);
    v.push_back(value ? *value : 0.0);
    lammps_free(value);
  }
  return v;
}

inline double mean(const std::vector<double> &v)
{
  double s = 0;
  for (double x : v) s += x;
  return s / v.size();
}

// Standard error of the mean of v.
inline double standard_error(const std::vector<double> &v)
{
  const double m = mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / (v.size() - 1) / v.size());
}

// The difference allowed between the mean speeds of the same rods walking on two runs: three
// standard errors of their rod-by-rod differences plus 2 % of the reference's mean.
inline double speed_tolerance(const std::vector<double> &reference, const std::vector<double> &other)
{
  std::vector<double> difference(reference.size());
  for (std::size_t k = 0; k < reference.size(); ++k) difference[k] = other[k] - reference[k];
  return 3.0 * standard_error(difference) + 0.02 * mean(reference);
}

}    // namespace rod_walking
