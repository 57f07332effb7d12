#include "ag_contact_prediction.h"

#include <algorithm>
#include <cmath>

namespace ActiveGrain {

namespace {

// stays_open() leaves to predict_contact() the contacts that close or stay open by less than this
// fraction of their gap and travel: the atoms' and the bodies' velocities differ by round-off.
constexpr double ROUNDOFF_MARGIN = 1e-6;

}    // namespace

bool gap_may_close(double gap, const Vec3 &relative_velocity, double spin_speeds, double dt)
{
  if (gap <= 0.0) return true;
  const double slack = gap / dt - spin_speeds;
  return slack < 0.0 || slack * slack < norm2(relative_velocity);
}

bool stays_open(double gap, const Vec3 &u, const Vec3 &n, double dt)
{
  return gap + dot(u, n) * dt > ROUNDOFF_MARGIN * (std::fabs(gap) + norm(u) * dt);
}

ContactPrediction predict_contact(double gap, const Vec3 &u, const Vec3 &n, double dt, double beta,
                                  const Vec3 &atom_acceleration, const Vec3 &wall_acceleration)
{
  ContactPrediction p;
  if (gap + dot(u, n) * dt >= 0.0) return p;
  p.closes = true;
  const double approach_now = -dot(u + atom_acceleration * (0.5 * dt), n);
  p.time_to_contact = gap <= 0.0 ? 0.0 : approach_now * dt > gap ? gap / approach_now : dt;
  p.gain = atom_acceleration * (0.5 * dt + p.time_to_contact) - wall_acceleration * p.time_to_contact;
  p.min_separation = gap < 0.0 ? beta * -gap / dt : 0.0;
  p.approach = std::max(0.0, -dot(u + p.gain, n));
  return p;
}

}    // namespace ActiveGrain
