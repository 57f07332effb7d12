#include "ag_jacobi_step.h"

#include <algorithm>

namespace ActiveGrain {

void JacobiStep::resize(std::size_t num_bodies)
{
  in_island.assign(num_bodies, 0);
  body_contacts.assign(num_bodies, 0);
  body_momentum.assign(num_bodies, Vec3());
  body_angular.assign(num_bodies, Vec3());
  body_moved.assign(num_bodies, 0);
}

void JacobiStep::start_island(std::vector<RigidBodyState> &bodies, std::vector<SolverContact> &contacts,
                              const std::vector<int> &island)
{
  solver_bodies = &bodies;
  solver_contacts = &contacts;
  island_contacts = &island;
  step_impulse.resize(island.size());
  bodies_of_island.clear();
  for (int i : island)
    for (int b : {contacts[i].body1, contacts[i].body2})
      if (!in_island[b]) {
        in_island[b] = 1;
        bodies_of_island.push_back(b);
      }
  for (int b : bodies_of_island) in_island[b] = 0;
}

void JacobiStep::clear_counts()
{
  for (int b : bodies_of_island) body_contacts[b] = 0;
}

void JacobiStep::count(std::size_t k)
{
  const SolverContact &c = contact(k);
  ++body_contacts[c.body1];
  ++body_contacts[c.body2];
}

int JacobiStep::share(std::size_t k) const
{
  const SolverContact &c = contact(k);
  return std::max(is_static(c.body1) ? 1 : body_contacts[c.body1],
                  is_static(c.body2) ? 1 : body_contacts[c.body2]);
}

void JacobiStep::start_step() { step_contacts.clear(); }

void JacobiStep::add(std::size_t k, const Vec3 &J)
{
  step_impulse[k] = J;
  step_contacts.push_back(static_cast<int>(k));
}

// In increasing order of the contacts: each one's impulse, and each movable body's sums (zero
// between steps).
void JacobiStep::push(const std::vector<int> &which)
{
  auto sum = [&](int b, const Vec3 &J, const Vec3 &r) {
    if (is_static(b)) return;
    body_momentum[b] += J;
    body_angular[b] += cross(r, J);
    if (!body_moved[b]) {
      body_moved[b] = 1;
      moved_bodies.push_back(b);
    }
  };
  for (int k : which) {
    SolverContact &c = contact(k);
    const Vec3 &J = step_impulse[k];
    c.impulse += J;
    sum(c.body1, -J, c.r1);
    sum(c.body2, J, c.r2);
  }
}

void JacobiStep::move_bodies()
{
  for (int b : moved_bodies) {
    RigidBodyState &body = (*solver_bodies)[b];
    body.v += body_momentum[b] * body.inv_mass;
    body.omega += body.inv_inertia * body_angular[b];
    body_momentum[b] = body_angular[b] = Vec3();
  }
}

void JacobiStep::forget_moved()
{
  for (int b : moved_bodies) body_moved[b] = 0;
  moved_bodies.clear();
}

bool JacobiStep::moved(std::size_t k) const
{
  const SolverContact &c = contact(k);
  return body_moved[c.body1] || body_moved[c.body2];
}

}    // namespace ActiveGrain
