#include "ag_resting_solve.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ActiveGrain {

namespace {

// A tangential impulse within the Coulomb disc of radius limit.
Vec3 within_cone(const Vec3 &pt, double limit)
{
  const double length = norm(pt);
  return length > limit ? pt * (limit / length) : pt;
}

}    // namespace

void RestingSolve::resize(std::size_t num_bodies) { jacobi.resize(num_bodies); }

// Sweeps with Nesterov's momentum (accelerated projected gradient, as Chrono's solver): each
// sweep starts from the last answer pushed on along its last change, by a factor that grows
// towards 1 and falls back to 0 whenever the largest change grows (an adaptive restart).
int RestingSolve::solve(std::vector<RigidBodyState> &bodies, std::vector<SolverContact> &contacts,
                        const std::vector<int> &island, const SolverSettings &settings)
{
  prepare(bodies, contacts, island);
  warm_start();
  const double converged = settings.resting_tolerance * settings.resting_speed;
  int sweeps = 0;
  bool done = false;
  double momentum_time = 1.0, last_change = std::numeric_limits<double>::infinity();
  while (!done && sweeps < settings.max_resting_sweeps) {
    ++sweeps;
    const double next_time = 0.5 * (1.0 + std::sqrt(1.0 + 4.0 * momentum_time * momentum_time));
    const double change = sweep((momentum_time - 1.0) / next_time);    // squared
    momentum_time = change > last_change ? 1.0 : next_time;
    last_change = change;
    done = change <= converged * converged;
  }
  settle();
  store();
  return done ? sweeps : -1;
}

// Every contact shares its bodies' impulses with the others on them (JacobiStep::share).
void RestingSolve::prepare(std::vector<RigidBodyState> &bodies, std::vector<SolverContact> &contacts,
                           const std::vector<int> &island)
{
  solver_bodies = &bodies;
  solver_contacts = &contacts;
  island_contacts = &island;
  jacobi.start_island(bodies, contacts, island);
  jacobi.clear_counts();
  const std::size_t n = island.size();
  normal.assign(n, 0.0);
  tangential.assign(n, Vec3());
  answer_normal.assign(n, 0.0);
  answer_tangential.assign(n, Vec3());
  normal_mass.resize(n);
  share.resize(n);
  for (std::size_t k = 0; k < n; ++k) jacobi.count(k);
  normal_response.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    normal_mass[k] = 1.0 / contact(k).knn;
    normal_response[k] = contact(k).K * contact(k).n;
    share[k] = 1.0 / jacobi.share(k);
  }
}

// The last step's impulse, within this step's cone: its normal part if pressing, its tangential
// part in the new tangent plane and within mu times that.
void RestingSolve::warm_start()
{
  jacobi.start_step();
  for (std::size_t k = 0; k < size(); ++k) {
    const SolverContact &c = contact(k);
    const double pn = dot(c.warm, c.n);
    if (pn <= 0.0) continue;
    const Vec3 pt = within_cone(c.warm - c.n * pn, c.material.mu * pn);
    normal[k] = answer_normal[k] = pn;
    tangential[k] = answer_tangential[k] = pt;
    jacobi.add(k, c.n * pn + pt);
  }
  move();
}

// Every contact from the same state: the normal impulse that makes it leave at its target (never
// pulling), and the friction that then stops its slip within mu times it; of that change, its
// share, kept within the cone; then pushed on by momentum times its change in the sweep. A
// contact that stays open and carried nothing has nothing to do. Returns the square of the
// largest velocity change a contact asked for.
double RestingSolve::sweep(double momentum)
{
  jacobi.start_step();
  double largest = 0.0;
  for (std::size_t k = 0; k < size(); ++k) {
    const SolverContact &c = contact(k);
    const Vec3 u = relative_velocity(*solver_bodies, c);
    const double target = std::max(0.0, c.min_separation);
    const double pn = std::max(0.0, normal[k] + (target - dot(u, c.n)) * normal_mass[k]);
    if (pn == 0.0 && normal[k] == 0.0 && answer_normal[k] == 0.0) continue;    // open, and was
    const double dpn = pn - normal[k];
    const Vec3 pt = within_cone(tangential[k] + c.tangential.stopping(u + normal_response[k] * dpn), c.material.mu * pn);
    const Vec3 dt = pt - tangential[k];
    largest = std::max(largest, norm2(normal_response[k] * dpn + c.K * dt));
    const double part = share[k];
    const double answer_n = std::max(0.0, normal[k] + part * (pn - normal[k]));
    const Vec3 answer_t = within_cone(tangential[k] + (pt - tangential[k]) * part, c.material.mu * answer_n);
    const double next_n = answer_n + momentum * (answer_n - answer_normal[k]);
    const Vec3 next_t = answer_t + (answer_t - answer_tangential[k]) * momentum;
    answer_normal[k] = answer_n;
    answer_tangential[k] = answer_t;
    const Vec3 J = c.n * (next_n - normal[k]) + next_t - tangential[k];
    normal[k] = next_n;
    tangential[k] = next_t;
    if (norm2(J) > 0.0) jacobi.add(k, J);
  }
  move();
  return largest;
}

// The bodies from where momentum pushed them back to the last answers.
void RestingSolve::settle()
{
  jacobi.start_step();
  for (std::size_t k = 0; k < size(); ++k) {
    const Vec3 J = contact(k).n * (answer_normal[k] - normal[k]) + answer_tangential[k] - tangential[k];
    normal[k] = answer_normal[k];
    tangential[k] = answer_tangential[k];
    if (norm2(J) > 0.0) jacobi.add(k, J);
  }
  move();
}

void RestingSolve::move()
{
  jacobi.push();
  jacobi.move_bodies();
  jacobi.forget_moved();
}

// The impulses are in the contacts already (JacobiStep::push).
void RestingSolve::store()
{
  for (std::size_t k = 0; k < size(); ++k) {
    SolverContact &c = contact(k);
    c.resting = c.n * normal[k] + tangential[k];
    c.late += c.resting * c.time;
  }
}

}    // namespace ActiveGrain
