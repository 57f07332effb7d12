// Predictive contact (docs/model.rst, contacts): which gaps close within a time step, when, and with what
// relative velocity the contact law must act. No LAMMPS in here.
//
// Velocities are those of the last drift, half a step before the step's start; a contact closes
// a time t_c after the start (0 for an overlap, at most dt). By then the atoms have gained their
// relative acceleration (gravity) times dt/2 + t_c, and a wall its own acceleration times t_c.
// An overlap deeper than slop must open at least at beta * (overlap - slop) / dt.
#pragma once

#include "ag_math.h"

#include <cmath>

namespace ActiveGrain {

// Whether a gap between surfaces (< 0: an overlap) can close within dt: faster than the centres'
// relative speed plus the surface speeds of the spins it cannot. A cheap test on atoms alone,
// before any body is built (inline: it runs once per near pair).
inline bool gap_may_close(double gap, const Vec3 &relative_velocity, double spin_speeds, double dt)
{
  if (gap <= 0.0) return true;
  const double slack = gap / dt - spin_speeds;
  return slack < 0.0 || slack * slack < norm2(relative_velocity);
}

// stays_open() leaves to predict_contact() the contacts that close or stay open by less than this
// fraction of their gap and travel: the atoms' and the bodies' velocities differ by round-off.
constexpr double ROUNDOFF_MARGIN = 1e-6;

// Whether a gap surely stays open through the step at relative velocity u along normal n (from
// surface 1 to surface 2, u = v2 - v1): the closing test of predict_contact with a margin for the
// round-off between the atoms' velocities and their bodies'.
inline bool stays_open(double gap, const Vec3 &u, const Vec3 &n, double dt)
{
  return gap + dot(u, n) * dt > ROUNDOFF_MARGIN * (std::fabs(gap) + norm(u) * dt);
}

struct ContactPrediction {
  bool closes = false;             // the gap closes within the step, or overlaps
  double time_to_contact = 0.0;    // after the step's start (0: an overlap)
  Vec3 gain;                       // relative velocity gained until then
  double min_separation = 0.0;     // normal velocity an overlap must at least leave with
  double approach = 0.0;           // normal approach speed when it closes (>= 0)
};

// The contact of a gap at relative velocity u (body 2 minus body 1 at the contact, normal n from
// 1 to 2), with the relative acceleration of the atoms (2 minus 1) and of a wall (body 1).
ContactPrediction predict_contact(double gap, const Vec3 &u, const Vec3 &n, double dt, double beta, double slop,
                                  const Vec3 &atom_acceleration, const Vec3 &wall_acceleration = Vec3());

}    // namespace ActiveGrain
