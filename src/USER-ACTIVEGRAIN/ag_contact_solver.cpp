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
  return bodies_[c.body2].velocity_at_arm(c.r2) - bodies_[c.body1].velocity_at_arm(c.r1);
}

void ContactSolver::apply(const Contact &c, const Vec3 &J)
{
  bodies_[c.body1].apply_impulse_at_arm(-J, c.r1);
  bodies_[c.body2].apply_impulse_at_arm(J, c.r2);
}

// Matrices and targets from the pre-solve velocities; which contacts share a movable body.
void ContactSolver::prepare()
{
  std::vector<int> contacts_of_body(bodies_.size(), 0);
  for (Contact &c : contacts_) {
    c.K = contact_matrix(bodies_[c.body1], c.r1, bodies_[c.body2], c.r2);
    c.K_inverse = c.K.inverse();
    const Vec3 u = relative_velocity(c);
    const double approach = std::max(0.0, -dot(u, c.n));
    c.target_separation = std::max(c.material.e * approach, c.min_separation);
    c.impulse = Vec3();
    c.speed = std::max(norm(u), c.target_separation);
    ++contacts_of_body[c.body1];
    ++contacts_of_body[c.body2];
  }
  auto alone = [&](int body) { return bodies_[body].is_static() || contacts_of_body[body] == 1; };
  coupled_.clear();
  for (int i = 0; i < num_contacts(); ++i) {
    Contact &c = contacts_[i];
    c.isolated = alone(c.body1) && alone(c.body2);
    if (!c.isolated) coupled_.push_back(i);
  }
  find_islands();
}

// Coupled contacts that share a movable body, directly or through others, form one island;
// islands do not interact within a solve, and each is swept until it converges.
void ContactSolver::find_islands()
{
  island_root_.resize(bodies_.size());
  for (int b = 0; b < num_bodies(); ++b) island_root_[b] = b;
  auto root = [&](int b) {
    while (island_root_[b] != b) b = island_root_[b] = island_root_[island_root_[b]];
    return b;
  };
  for (int i : coupled_) {
    const Contact &c = contacts_[i];
    if (bodies_[c.body1].is_static() || bodies_[c.body2].is_static()) continue;
    const int r1 = root(c.body1), r2 = root(c.body2);
    if (r1 != r2) island_root_[std::max(r1, r2)] = std::min(r1, r2);
  }
  islands_.clear();
  std::vector<int> island_of_root(bodies_.size(), -1);
  for (int i : coupled_) {
    const Contact &c = contacts_[i];
    const int r = root(bodies_[c.body1].is_static() ? c.body2 : c.body1);
    if (island_of_root[r] < 0) {
      island_of_root[r] = static_cast<int>(islands_.size());
      islands_.emplace_back();
    }
    islands_[island_of_root[r]].push_back(i);
  }
}

void ContactSolver::solve_isolated()
{
  for (Contact &c : contacts_)
    if (c.isolated) {
      c.impulse = contact_law_impulse(c.K, relative_velocity(c), c.n, c.material, c.target_separation);
      apply(c, c.impulse);
    }
}

// One projected Gauss-Seidel sweep over an island's contacts, in the order they were added.
// Returns the largest velocity correction of one contact update, |K dJ|, relative to the
// island's velocity scale speed: zero exactly when every contact meets its conditions. (The change of the
// bodies' velocities over a sweep is no measure: while the active contacts ask for more than
// a rigid motion can give, their impulses drift and the bodies hardly move.)
double ContactSolver::sweep(const std::vector<int> &island, double speed, CoupledLaw law)
{
  double largest_correction = 0.0;
  for (int i : island) {
    Contact &c = contacts_[i];
    apply(c, -c.impulse);
    const Vec3 u = relative_velocity(c);
    const Vec3 J = law == CoupledLaw::PROJECTION
        ? coupled_contact_impulse(c.K, c.K_inverse, u, c.n, c.material, c.target_separation)
        : contact_law_impulse(c.K, u, c.n, c.material, c.target_separation);
    largest_correction = std::max(largest_correction, norm(c.K * (J - c.impulse)));
    c.impulse = J;
    apply(c, c.impulse);
  }
  return speed > 0.0 ? largest_correction / speed : 0.0;
}

ContactSolver::Result ContactSolver::solve(int max_sweeps, double tolerance, CoupledLaw law)
{
  prepare();
  solve_isolated();
  Result result;
  for (const std::vector<int> &island : islands_) {
    double speed = 0.0;    // the island's velocity scale
    for (int i : island) speed = std::max(speed, contacts_[i].speed);
    int sweeps = 0;
    double residual = 0.0;
    do {
      ++sweeps;
      residual = sweep(island, speed, law);
    } while (residual > tolerance && sweeps < max_sweeps);
    result.sweeps = std::max(result.sweeps, sweeps);
    result.residual = std::max(result.residual, residual);
    result.converged = result.converged && residual <= tolerance;
  }
  return result;
}

}    // namespace ActiveGrain
