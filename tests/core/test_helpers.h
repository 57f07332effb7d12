// Shared helpers for the core tests: random rigid bodies and their energy and momenta, and a
// solved contact's separation velocity.
#pragma once

#include "ag_contact_solver.h"
#include "ag_rigid_body.h"

#include <cmath>
#include <random>

namespace ActiveGrain::testing {

inline Mat3 rotation(const Vec3 &axis_unnormalised, double angle)
{
  const Vec3 a = axis_unnormalised / norm(axis_unnormalised);
  const Mat3 k = Mat3::skew(a);
  return Mat3::identity() + k * std::sin(angle) + k * k * (1.0 - std::cos(angle));
}

inline Mat3 inertia_of(const RigidBodyState &b) { return b.inv_inertia.inverse(); }

inline double kinetic_energy(const RigidBodyState &b)
{
  if (b.inv_mass == 0.0) return 0.0;
  return 0.5 * norm2(b.v) / b.inv_mass + 0.5 * dot(b.omega, inertia_of(b) * b.omega);
}

inline Vec3 linear_momentum(const RigidBodyState &b) { return b.v / b.inv_mass; }

// Angular momentum about point p.
inline Vec3 angular_momentum(const RigidBodyState &b, const Vec3 &p)
{
  return cross(b.com - p, b.v / b.inv_mass) + inertia_of(b) * b.omega;
}

// A rigid body of random mass, anisotropic inertia in a random orientation, position and motion.
inline RigidBodyState random_body(std::mt19937 &rng)
{
  std::uniform_real_distribution<double> U(-1.0, 1.0), P(0.2, 5.0);
  RigidBodyState b;
  b.inv_mass = 1.0 / P(rng);
  const Mat3 R = rotation(Vec3(U(rng), U(rng), U(rng)), 3.0 * U(rng));
  const Vec3 principal(P(rng), P(rng), P(rng));
  b.inv_inertia = R * Mat3::diagonal(Vec3(1 / principal.x, 1 / principal.y, 1 / principal.z)) * R.transpose();
  b.com = Vec3(U(rng), U(rng), U(rng));
  b.v = Vec3(U(rng), U(rng), U(rng)) * 2.0;
  b.omega = Vec3(U(rng), U(rng), U(rng)) * 3.0;
  return b;
}

inline Vec3 random_unit(std::mt19937 &rng)
{
  std::normal_distribution<double> N;
  Vec3 v(N(rng), N(rng), N(rng));
  return v / norm(v);
}

// The normal velocity at contact c of a solved solver (body 2 minus body 1; < 0: approaching).
inline double separation(const ContactSolver &solver, int c)
{
  const ContactSolver::Contact &k = solver.contact(c);
  return dot(solver.body(k.body2).velocity_at_arm(k.r2) - solver.body(k.body1).velocity_at_arm(k.r1), k.n);
}

}    // namespace ActiveGrain::testing
