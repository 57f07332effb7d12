#include "ag_contact_prediction.h"

#include <algorithm>

namespace ActiveGrain {

ContactPrediction predict_contact(double gap, const Vec3 &u, const Vec3 &n, double dt, double beta, double slop,
                                  const Vec3 &atom_acceleration, const Vec3 &wall_acceleration)
{
  ContactPrediction p;
  if (gap + dot(u, n) * dt >= 0.0) return p;
  p.closes = true;
  const double approach_now = -dot(u + atom_acceleration * (0.5 * dt), n);
  p.time_to_contact = gap <= 0.0 ? 0.0 : approach_now * dt > gap ? gap / approach_now : dt;
  p.gain = atom_acceleration * (0.5 * dt + p.time_to_contact) - wall_acceleration * p.time_to_contact;
  p.min_separation = gap < -slop ? beta * (-gap - slop) / dt : 0.0;
  p.approach = std::max(0.0, -dot(u + p.gain, n));
  return p;
}

}    // namespace ActiveGrain
