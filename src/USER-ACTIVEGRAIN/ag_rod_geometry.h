// Geometry of a tapered polar rod: a solid frustum (truncated cone) of length L whose diameter
// falls linearly from D_tail at x = 0 to D_nose at x = L, and its representation by N overlapping
// spheres on the axis for contact detection. No LAMMPS here.
//
// Mass properties are those of the solid frustum (exact closed forms), never the sum of the
// spheres: the spheres carry point masses chosen to reproduce the solid's mass and centre of
// mass exactly, and the rigid-body integrator is given the solid's inertia.
#pragma once

#include <string>
#include <vector>

namespace ActiveGrain {

// A tail and a nose: the fewest spheres that give a rod its axis and polarity.
constexpr int MIN_ROD_SPHERES = 2;

struct RodParameters {
  double length = 0.0;          // L, tail face to nose face
  double tail_diameter = 0.0;   // D_tail at x = 0
  double nose_diameter = 0.0;   // D_nose at x = L
  int nspheres = 0;             // constituent spheres, first = tail, last = nose
  double density = 0.0;         // mass per volume of the solid
};

struct RodSphere {
  double x;         // centre on the axis, measured from the tail face
  double radius;    // local radius of the frustum at x
  double mass;      // point mass carried by this sphere (sum = solid mass, first moment = solid's)
};

struct RodGeometry {
  double volume = 0.0;
  double mass = 0.0;
  double com = 0.0;                  // centre of mass on the axis, from the tail face
  double inertia_axial = 0.0;        // about the rod axis through the COM
  double inertia_transverse = 0.0;   // about any axis through the COM perpendicular to the rod
  double max_envelope_dip = 0.0;     // deepest groove of the sphere envelope below the frustum
  std::vector<RodSphere> spheres;
};

// Empty string if the parameters describe a rod, otherwise what is wrong with them.
std::string rod_parameter_error(const RodParameters &p);

// The solid frustum's volume, mass, COM and inertia (no spheres). Precondition: length > 0 and
// diameters >= 0, not both 0.
RodGeometry rod_solid(const RodParameters &p);

// Frustum mass properties and sphere layout. Precondition: rod_parameter_error(p) is empty.
// Sphere i (0 = tail) sits where a sphere of the local frustum radius just reaches the end faces
// for i = 0 and N-1, equally spaced in between; throws std::invalid_argument if N is too small
// for neighbouring spheres to overlap, or if no positive masses reproduce the solid's COM.
RodGeometry make_rod_geometry(const RodParameters &p);

}    // namespace ActiveGrain
