// A rough plate: a frozen random height field z = h(x, y) about the flat plate, with a given rms
// slope and lateral correlation length. It is a function of position and seed only (value noise:
// heights hashed from the cells of a square lattice of spacing about the correlation length,
// blended with C2 quintic weights), so a grain that sits still meets the same bump at every impact,
// on any number of ranks, and nothing has to be stored in restarts. Along a periodic direction the
// lattice is made commensurate with the period, so every image of an atom sees the same surface.
// No LAMMPS in here.
#pragma once

#include "ag_math.h"

#include <cstdint>

namespace ActiveGrain {

struct SurfacePoint {
  double height = 0.0;                  // h
  double slope_x = 0.0, slope_y = 0.0;  // dh/dx, dh/dy

  // Unit normal of the surface on its +z side (into the cell, for a base plate).
  Vec3 normal_up() const;
};

class RoughSurface {
 public:
  RoughSurface() = default;    // flat: h = 0 everywhere
  // rms_slope: rms of |grad h| (the rms tilt of the normal, in radians, for small slopes).
  // period_x, period_y: the box length along a periodic direction, 0 along a bounded one.
  RoughSurface(double rms_slope, double correlation_length, std::uint64_t seed, double period_x = 0.0,
               double period_y = 0.0);

  bool flat() const { return amplitude == 0.0; }
  SurfacePoint at(double x, double y) const;
  double rms_height() const;    // of h over the plane
  // Bounds over the whole plane: |h| <= max_height(), and the normal's z component is at least
  // min_normal_z() (its tilt at the steepest slope the lattice allows).
  double max_height() const { return amplitude; }
  double min_normal_z() const { return normal_z_bound; }
  double spacing_x() const { return lattice_x; }
  double spacing_y() const { return lattice_y; }

 private:
  double node_height(std::int64_t i, std::int64_t j) const;

  double amplitude = 0.0;    // heights at lattice nodes are uniform in [-amplitude, amplitude)
  double normal_z_bound = 1.0;
  double lattice_x = 1.0, lattice_y = 1.0;    // lattice spacings
  std::int64_t cells_x = 0, cells_y = 0;      // > 0: periodic with this many cells
  std::uint64_t hash_seed = 0;
};

}    // namespace ActiveGrain
