#include "ag_contact_solver.h"

#include <algorithm>

namespace ActiveGrain {

void ContactSolver::clear()
{
  bodies_.clear();
  contacts_.clear();
}

int ContactSolver::add_body(const RigidBodyState &body)
{
  bodies_.push_back(body);
  return num_bodies() - 1;
}

int ContactSolver::add_contact(int body1, int body2, const Vec3 &point, const Vec3 &n,
                               const ContactMaterial &material, double min_separation)
{
  return add_contact_arms(body1, body2, point - bodies_[body1].com, point - bodies_[body2].com, n,
                          material, min_separation);
}

int ContactSolver::add_contact_arms(int body1, int body2, const Vec3 &r1, const Vec3 &r2,
                                    const Vec3 &n, const ContactMaterial &material,
                                    double min_separation)
{
  Contact c;
  c.body1 = body1;
  c.body2 = body2;
  c.r1 = r1;
  c.r2 = r2;
  c.n = n;
  c.material = material;
  c.min_separation = min_separation;
  contacts_.push_back(c);
  return num_contacts() - 1;
}

Vec3 ContactSolver::relative_velocity(const Contact &c) const
{
  const RigidBodyState &b1 = bodies_[c.body1], &b2 = bodies_[c.body2];
  return (b2.v + cross(b2.omega, c.r2)) - (b1.v + cross(b1.omega, c.r1));
}

void ContactSolver::apply(const Contact &c, const Vec3 &J)
{
  RigidBodyState &b1 = bodies_[c.body1], &b2 = bodies_[c.body2];
  b1.v -= J * b1.inv_mass;
  b1.omega -= b1.inv_inertia * cross(c.r1, J);
  b2.v += J * b2.inv_mass;
  b2.omega += b2.inv_inertia * cross(c.r2, J);
}

ContactSolver::Result ContactSolver::solve(int max_sweeps, double tolerance)
{
  for (Contact &c : contacts_) {
    c.K = contact_matrix(bodies_[c.body1], c.r1, bodies_[c.body2], c.r2);
    const double approach = std::max(0.0, -dot(relative_velocity(c), c.n));
    c.target_separation = std::max(c.material.e * approach, c.min_separation);
    c.impulse = Vec3();
  }

  Result result;
  while (result.sweeps < max_sweeps) {
    ++result.sweeps;
    double largest_change = 0.0, largest_impulse = 0.0;
    for (Contact &c : contacts_) {
      apply(c, -c.impulse);
      const Vec3 J = contact_law_impulse(c.K, relative_velocity(c), c.n, c.material, c.target_separation);
      apply(c, J);
      largest_change = std::max(largest_change, norm(J - c.impulse));
      largest_impulse = std::max(largest_impulse, norm(J));
      c.impulse = J;
    }
    result.last_change = largest_impulse > 0.0 ? largest_change / largest_impulse : 0.0;
    if (largest_change <= tolerance * largest_impulse) break;
  }
  return result;
}

}    // namespace ActiveGrain
