#include "ag_resting_solve.h"

#include <algorithm>
#include <cmath>

namespace ActiveGrain {

namespace {

// Over-relaxation of the normal impulses: faster convergence up to oscillation near 2.
constexpr double RELAXATION = 1.7;

// A tangential impulse within the Coulomb disc of radius limit.
Vec3 within_cone(const Vec3 &pt, double limit)
{
  const double length = norm(pt);
  return length > limit ? pt * (limit / length) : pt;
}

}    // namespace

void RestingSolve::resize(std::size_t num_bodies) { body_colours.resize(num_bodies); }

int RestingSolve::solve(std::vector<RigidBodyState> &bodies, std::vector<SolverContact> &contacts,
                        const std::vector<int> &island, const SolverSettings &settings)
{
  prepare(bodies, contacts, island);
  const double converged = settings.resting_tolerance * settings.resting_speed;
  int sweeps = 0;
  bool done = false;
  while (!done && sweeps < settings.max_resting_sweeps) {
    ++sweeps;
    done = sweep() <= converged * converged;
  }
  store();
  return done ? sweeps : -1;
}

// The contacts in the order of their keys, coloured greedily so that no two of one colour share
// a movable body: the contacts of a colour are then independent, and a sweep over the colours is
// the same in any order the contacts came in.
void RestingSolve::prepare(std::vector<RigidBodyState> &bodies, std::vector<SolverContact> &contacts,
                           const std::vector<int> &island)
{
  solver_bodies = &bodies;
  solver_contacts = &contacts;
  island_contacts = &island;
  const std::size_t n = island.size();
  normal.assign(n, 0.0);
  tangential.assign(n, Vec3());
  normal_mass.resize(n);
  normal_response.resize(n);
  by_key.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    normal_mass[k] = 1.0 / contact(k).knn;
    normal_response[k] = contact(k).K * contact(k).n;
    by_key[k] = static_cast<int>(k);
  }
  std::sort(by_key.begin(), by_key.end(), [&](int a, int b) {
    return contact(a).key != contact(b).key ? contact(a).key < contact(b).key : a < b;
  });
  for (int k : by_key)
    for (int b : {contact(k).body1, contact(k).body2}) body_colours[b].clear();
  colour_of.resize(n);
  for (int k : by_key) {
    const SolverContact &c = contact(k);
    auto used = [&](int b, int colour) {
      const auto &list = body_colours[b];
      return !bodies[b].is_static() && std::find(list.begin(), list.end(), colour) != list.end();
    };
    int colour = 0;
    while (used(c.body1, colour) || used(c.body2, colour)) ++colour;
    colour_of[k] = colour;
    for (int b : {c.body1, c.body2})
      if (!bodies[b].is_static()) body_colours[b].push_back(colour);
  }
  sweep_order = by_key;
  std::stable_sort(sweep_order.begin(), sweep_order.end(), [&](int a, int b) { return colour_of[a] < colour_of[b]; });
}

// Each contact in turn, colour by colour: the normal impulse that makes it leave at its target
// (never pulling, over-relaxed), then the friction that stops its slip within mu times it. A
// contact that stays open and carried nothing has nothing to do. Returns the square of the
// largest velocity change a contact asked for.
double RestingSolve::sweep()
{
  double largest = 0.0;
  for (int k : sweep_order) {
    const SolverContact &c = contact(k);
    const Vec3 u = relative_velocity(*solver_bodies, c);
    const double target = std::max(0.0, c.min_separation);
    const double asked = (target - dot(u, c.n)) * normal_mass[k];
    const double pn = std::max(0.0, normal[k] + RELAXATION * asked);
    if (pn == 0.0 && normal[k] == 0.0) continue;
    const double dpn = pn - normal[k];
    const Vec3 pt = within_cone(tangential[k] + c.tangential.stopping(u + normal_response[k] * dpn),
                                c.material.mu * pn);
    const Vec3 dt = pt - tangential[k];
    largest = std::max(largest, norm2(normal_response[k] * std::max(-normal[k], asked) + c.K * dt));
    normal[k] = pn;
    tangential[k] = pt;
    apply_impulse(*solver_bodies, c, c.n * dpn + dt);
  }
  return largest;
}

void RestingSolve::store()
{
  for (std::size_t k = 0; k < size(); ++k) {
    SolverContact &c = contact(k);
    const Vec3 resting = c.n * normal[k] + tangential[k];
    c.impulse += resting;
    c.late += resting * c.time;
  }
}

}    // namespace ActiveGrain
