// The state of one rigid body as the contact core sees it. A bead, a rod, or a wall.
#pragma once

#include "ag_math.h"

namespace ActiveGrain {

// A solid sphere's moment of inertia about a diameter, over m r^2.
constexpr double SOLID_SPHERE_INERTIA = 0.4;

struct RigidBodyState {
  double inv_mass = 0.0;    // 0: infinite mass (a plate or wall moving as prescribed)
  Mat3 inv_inertia;         // world-frame inverse inertia tensor; 0 for a wall
  Vec3 com;                 // centre of mass
  Vec3 v;                   // centre-of-mass velocity
  Vec3 omega;               // angular velocity

  static RigidBodyState wall(const Vec3 &velocity)
  {
    RigidBodyState w;
    w.v = velocity;
    return w;
  }
  // A solid sphere of mass m and radius r centred at x.
  static RigidBodyState sphere(double m, double r, const Vec3 &x, const Vec3 &v, const Vec3 &omega)
  {
    RigidBodyState s;
    s.inv_mass = 1.0 / m;
    s.inv_inertia = Mat3::identity(1.0 / (SOLID_SPHERE_INERTIA * m * r * r));
    s.com = x;
    s.v = v;
    s.omega = omega;
    return s;
  }

  bool is_static() const { return inv_mass == 0.0; }

  Vec3 velocity_at(const Vec3 &p) const { return velocity_at_arm(p - com); }
  // Velocity of the body point at lever arm r from the centre of mass.
  Vec3 velocity_at_arm(const Vec3 &r) const { return v + cross(omega, r); }
  // Apply impulse J at point p, or at lever arm r from the centre of mass.
  void apply_impulse(const Vec3 &J, const Vec3 &p) { apply_impulse_at_arm(J, p - com); }
  void apply_impulse_at_arm(const Vec3 &J, const Vec3 &r)
  {
    v += J * inv_mass;
    omega += inv_inertia * cross(r, J);
  }
};

}    // namespace ActiveGrain
