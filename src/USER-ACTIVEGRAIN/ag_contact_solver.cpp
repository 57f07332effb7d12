#include "ag_contact_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ActiveGrain {

namespace {

// K n within this fraction of n.K.n of n: the normal and tangential motions do not couple.
constexpr double DECOUPLED = 1.0e-9;

}    // namespace

void ContactSolver::clear()
{
  bodies.clear();
  contacts.clear();
}

int ContactSolver::add_body(const RigidBodyState &body)
{
  bodies.push_back(body);
  return num_bodies() - 1;
}

int ContactSolver::add_contact(int body1, int body2, const Vec3 &point, const Vec3 &n,
                               const ContactModel &model, double min_separation,
                               const Vec3 &gain, double time)
{
  return add_contact_arms(body1, body2, point - bodies[body1].com, point - bodies[body2].com, n,
                          model, min_separation, gain, time);
}

int ContactSolver::add_contact_arms(int body1, int body2, const Vec3 &r1, const Vec3 &r2,
                                    const Vec3 &n, const ContactModel &model,
                                    double min_separation, const Vec3 &gain, double time)
{
  Contact c;
  c.body1 = body1;
  c.body2 = body2;
  c.r1 = r1;
  c.r2 = r2;
  c.n = n;
  c.model = model;
  c.min_separation = min_separation;
  c.gain = gain;
  c.time = time;
  contacts.push_back(c);
  return num_contacts() - 1;
}

// Matrices and targets from the pre-solve velocities; which contacts share a movable body.
void ContactSolver::prepare()
{
  contacts_of_body.assign(bodies.size(), 0);
  for (Contact &c : contacts) {
    c.K = contact_matrix(bodies[c.body1], c.r1, bodies[c.body2], c.r2);    // the energy ledger's too
    if (c.solved_elsewhere) continue;
    c.impulse = c.late = Vec3();
    ++contacts_of_body[c.body1];
    ++contacts_of_body[c.body2];
  }
  auto alone = [&](int body) { return bodies[body].is_static() || contacts_of_body[body] == 1; };
  for (Contact &c : contacts) {
    if (c.solved_elsewhere) continue;
    c.isolated = alone(c.body1) && alone(c.body2);
    if (c.isolated && !c.model.tangential.compliant()) continue;
    c.knn = dot(c.n, c.K * c.n);
    c.tangential = TangentialStep(c.K, c.n);
  }
  find_islands();
}

// Coupled contacts that share a movable body, directly or through others, form one island;
// islands do not interact within a solve.
void ContactSolver::find_islands()
{
  coupled.clear();
  for (int i = 0; i < num_contacts(); ++i)
    if (!contacts[i].isolated && !contacts[i].solved_elsewhere) coupled.push_back(i);
  num_islands = group_by_bodies(coupled, islands);
}

// The contacts of subset (in its order) that share movable bodies, directly or through others,
// as groups in the order of their first contact. The groups' lists keep their storage from call
// to call; returns how many there are.
int ContactSolver::group_by_bodies(const std::vector<int> &subset, std::vector<std::vector<int>> &groups)
{
  island_root.resize(bodies.size());
  island_of_root.resize(bodies.size());
  for (int i : subset)
    for (int b : {contacts[i].body1, contacts[i].body2}) island_root[b] = b, island_of_root[b] = -1;
  auto root = [&](int b) {
    while (island_root[b] != b) b = island_root[b] = island_root[island_root[b]];
    return b;
  };
  for (int i : subset) {
    const Contact &c = contacts[i];
    if (bodies[c.body1].is_static() || bodies[c.body2].is_static()) continue;
    const int r1 = root(c.body1), r2 = root(c.body2);
    if (r1 != r2) island_root[std::max(r1, r2)] = std::min(r1, r2);
  }
  int count = 0;
  for (int i : subset) {
    const Contact &c = contacts[i];
    const int r = root(bodies[c.body1].is_static() ? c.body2 : c.body1);
    if (island_of_root[r] < 0) {
      island_of_root[r] = count++;
      if (groups.size() < static_cast<std::size_t>(count)) groups.emplace_back();
      groups[island_of_root[r]].clear();
    }
    groups[island_of_root[r]].push_back(i);
  }
  return count;
}

// Stronge's impact of a contact alone, leaving at least at min_separation.
Vec3 ContactSolver::impact_alone(const Contact &c, double min_separation) const
{
  const Vec3 u = relative_velocity(bodies, c);
  return contact_law_impulse(c.K, u, c.n, c.model, c.model.normal.target_separation(-dot(u, c.n), min_separation));
}

// A contact's whole impulse by Stronge's law: on the bodies, acting when it closes. With the
// compliant tangential law the impact is integrated (a compliant impact of one contact, then
// compliant_alone()).
void ContactSolver::solve_alone(int k, double min_separation, const Settings &settings)
{
  Contact &c = contacts[k];
  if (!c.model.tangential.compliant()) {
    c.impulse = impact_alone(c, min_separation);
    apply_impulse(bodies, c, c.impulse);
  } else {
    const Vec3 before = relative_velocity(bodies, c);
    c.impulse = Vec3();
    alone.assign(1, k);
    compliant_impact.solve(bodies, contacts, alone, settings);
    const Vec3 integrated = c.impulse;
    apply_impulse(bodies, c, compliant_alone(c, before, min_separation) - integrated);
  }
  c.late = c.impulse * c.time;
}

// The integrated impact's impulse of a compliant contact alone (relative velocity `before` it),
// made exact where the normal does not couple to the tangent plane (K n along n: a sphere): the
// normal impulse that leaves at Stronge's e times the approach (or the overlap's minimum
// separation velocity), which the tangential springs do not change, and the tangential impulse
// scaled back if the sub-steps made it gain energy. Elsewhere an overlap left opening slower
// than min_separation is pushed open (with the sticking law's friction, as the overlap
// correction's). Returns the contact's impulse and keeps it in c.impulse.
Vec3 ContactSolver::compliant_alone(Contact &c, const Vec3 &before, double min_separation) const
{
  const Vec3 Kn = c.K * c.n;
  const bool decoupled = norm(Kn - c.n * c.knn) <= DECOUPLED * c.knn;
  if (decoupled) {
    const double un = dot(before, c.n);
    const double target = c.model.normal.target_separation(-un, min_separation);
    Vec3 tangential = c.impulse - c.n * dot(c.impulse, c.n);
    cap_energy(c.K, before, tangential);
    c.impulse = c.n * (std::max(0.0, target - un) / c.knn) + tangential;
    return c.impulse;
  }
  const Vec3 u = relative_velocity(bodies, c);
  const double shortfall = min_separation - dot(u, c.n);
  if (shortfall > 0.0) {
    const double dp = shortfall / c.knn;
    bool stuck = false;
    c.impulse += c.n * dp + c.model.tangential.friction(c.tangential, u, dp, stuck);
  }
  return c.impulse;
}

void ContactSolver::solve_isolated(const Settings &settings)
{
  for (int k = 0; k < num_contacts(); ++k)
    if (contacts[k].isolated) solve_alone(k, contacts[k].min_separation, settings);
}

// What the energy ledger (ag_contact_energy.h) reads of the solved bodies, kept with each contact
// so that a contact solved elsewhere can carry it back.
void ContactSolver::record_velocities_after()
{
  for (Contact &c : contacts)
    if (!c.solved_elsewhere)
      c.velocity_after = bodies[c.body2].velocity_at_arm(c.r2) - bodies[c.body1].velocity_at_arm(c.r1);
}

void ContactSolver::set_solution(int c, const Vec3 &impulse, const Vec3 &late, const Vec3 &velocity_after)
{
  contacts[c].impulse = impulse;
  contacts[c].late = late;
  contacts[c].velocity_after = velocity_after;
}

void ContactSolver::measure_approaches(const std::vector<int> &island)
{
  approach.resize(island.size());
  for (std::size_t k = 0; k < island.size(); ++k) {
    const Contact &c = contacts[island[k]];
    approach[k] = -dot(relative_velocity(bodies, c), c.n);
  }
}

// When within the step a contact closes; a resting one (Settings::resting_gain) at the start.
double ContactSolver::closing_time(const Contact &c, double approach_speed, const Settings &settings) const
{
  return approach_speed <= settings.resting_gain * std::fabs(dot(c.gain, c.n)) ? 0.0 : c.time;
}

// The island's contacts in the order they close within the step (see the class comment): one
// compliant impact if they all close within the window, else impacts in order.
int ContactSolver::solve_island(const std::vector<int> &island, const Settings &settings)
{
  double first = 0.0, last = 0.0;
  if (std::isfinite(settings.window)) {
    measure_approaches(island);
    first = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < island.size(); ++k) {
      const double time = closing_time(contacts[island[k]], approach[k], settings);
      first = std::min(first, time);
      last = std::max(last, time);
    }
  }
  if (last - first <= settings.window) {
    const int substeps = compliant_impact.solve(bodies, contacts, island, settings);
    for (int i : island) contacts[i].late = contacts[i].impulse * contacts[i].time;
    return substeps;
  }
  return impacts_in_order(island, settings);
}

// After solve_island() measured the approaches. An impact takes the contacts that close within
// the window of the first; it leaves them touching, and settled if they approach slower than its
// settled approach (they wait for the next step, as do contacts that close after the step). Each
// contact's late impulse is the sum of its impulses times when they acted.
int ContactSolver::impacts_in_order(const std::vector<int> &island, const Settings &settings)
{
  const std::size_t size = island.size();
  gap.resize(size);
  impulse_before.resize(size);
  settled_below.assign(size, 0.0);
  for (std::size_t k = 0; k < size; ++k) {
    gap[k] = std::max(0.0, approach[k]) * closing_time(contacts[island[k]], approach[k], settings);
    contacts[island[k]].late = Vec3();
  }
  // Whether contact k closes within the window from now (gap at now).
  auto in_impact = [&](std::size_t k) {
    return approach[k] > settled_below[k] && gap[k] <= approach[k] * settings.window;
  };
  int substeps = 0;
  double now = 0.0;
  for (int impacts = 0; impacts < settings.max_impacts_in_order; ++impacts) {
    double next = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < size; ++k)
      if (approach[k] > settled_below[k]) next = std::min(next, std::max(0.0, gap[k]) / approach[k]);
    if (!(now + next <= settings.step)) break;
    now += next;
    wave.clear();
    double fastest = 0.0;
    for (std::size_t k = 0; k < size; ++k) {
      gap[k] -= approach[k] * next;
      if (!in_impact(k)) continue;
      wave.push_back(island[k]);
      impulse_before[k] = contacts[island[k]].impulse;
      fastest = std::max(fastest, approach[k]);
    }
    if (wave.size() == 1 && !contacts[wave[0]].model.tangential.compliant()) {
      Contact &c = contacts[wave[0]];
      const Vec3 J = impact_alone(c, 0.0);    // overlaps are opened after all impacts
      c.impulse += J;
      apply_impulse(bodies, c, J);
    } else {
      const int s = compliant_impact.solve(bodies, contacts, wave, settings);
      if (s < 0) return -1;
      substeps = std::max(substeps, s);
    }
    for (std::size_t k = 0; k < size; ++k) {
      if (!in_impact(k)) continue;
      Contact &c = contacts[island[k]];
      c.late += (c.impulse - impulse_before[k]) * (now + std::max(0.0, gap[k]) / approach[k]);
      gap[k] = 0.0;
      settled_below[k] = settings.settled_approach * fastest;
    }
    measure_approaches(island);
  }
  return substeps;
}

// With a resting speed: the contacts approaching faster are impacts, solved first (as islands of
// their own: through resting contacts they do not couple), then all of the island's contacts
// together as resting contacts (ag_resting_solve.h).
int ContactSolver::solve_impacts_then_resting(const std::vector<int> &island, const Settings &settings,
                                              Result &result)
{
  measure_approaches(island);
  impacts.clear();
  for (std::size_t k = 0; k < island.size(); ++k)
    if (approach[k] > settings.resting_speed) impacts.push_back(island[k]);
  int substeps = 0;
  const int groups = group_by_bodies(impacts, impact_islands);
  for (int g = 0; g < groups && substeps >= 0; ++g) {
    const std::vector<int> &group = impact_islands[g];
    if (group.size() == 1) {    // Stronge's law, exactly (its overlap is opened below)
      solve_alone(group[0], 0.0, settings);
      continue;
    }
    const int s = solve_island(group, settings);
    substeps = s < 0 ? -1 : std::max(substeps, s);
  }
  const int sweeps = resting_solve.solve(bodies, contacts, island, settings);
  result.resting_sweeps = std::max(result.resting_sweeps, sweeps < 0 ? settings.max_resting_sweeps : sweeps);
  result.resting_converged = result.resting_converged && sweeps >= 0;
  return substeps;
}

// Overlapping contacts must open at least at their minimum separation velocity: pushes where one
// opens slower, with Stronge's friction for their normal impulse (a body resting on a plate
// under gravity sits on these pushes), each shared among the pushed contacts of its bodies.
double ContactSolver::separate_overlaps(const std::vector<int> &island, const Settings &settings)
{
  overlap_step.start_island(bodies, contacts, island);
  double largest = 0.0;
  for (int sweep = 0; sweep < settings.max_overlap_sweeps; ++sweep) {
    overlap_step.clear_counts();
    overlap_step.start_step();
    largest = 0.0;
    for (std::size_t k = 0; k < island.size(); ++k) {
      const Contact &c = contacts[island[k]];
      const Vec3 u = relative_velocity(bodies, c);
      const double shortfall = c.min_separation - dot(u, c.n);
      if (c.min_separation <= 0.0 || shortfall <= settings.overlap_tolerance * c.min_separation) continue;
      largest = std::max(largest, shortfall / c.min_separation);
      const double dp = shortfall / c.knn;
      bool stuck = false;
      overlap_step.add(k, c.n * dp + c.model.tangential.friction(c.tangential, u, dp, stuck));
      overlap_step.count(k);
    }
    if (largest == 0.0) break;
    for (int k : overlap_step.pushed()) overlap_step.impulse(k) *= 1.0 / overlap_step.share(k);
    overlap_step.push();
    overlap_step.move_bodies();
    overlap_step.forget_moved();
  }
  return largest;
}

// The resting solve has opened the island's overlaps already, to its own tolerance, which is
// absolute: what they lack beyond it, as separate_overlaps() reports it.
double ContactSolver::overlap_shortfall(const std::vector<int> &island, const Settings &settings) const
{
  const double allowed = settings.resting_tolerance * settings.resting_speed;
  double largest = 0.0;
  for (int k : island) {
    const Contact &c = contacts[k];
    const double shortfall = c.min_separation - dot(relative_velocity(bodies, c), c.n);
    if (c.min_separation > 0.0 && shortfall > std::max(allowed, settings.overlap_tolerance * c.min_separation))
      largest = std::max(largest, shortfall / c.min_separation);
  }
  return largest;
}

ContactSolver::Result ContactSolver::solve()
{
  return solve(Settings());
}

ContactSolver::Result ContactSolver::solve(const Settings &settings)
{
  prepare();
  compliant_impact.resize(bodies.size());
  overlap_step.resize(bodies.size());
  resting_solve.resize(bodies.size());
  solve_isolated(settings);
  Result result;
  for (int k = 0; k < num_islands; ++k) {
    const std::vector<int> &island = islands[k];
    const int substeps = settings.resting_speed > 0.0 ? solve_impacts_then_resting(island, settings, result)
                                                      : solve_island(island, settings);
    const double shortfall = settings.resting_speed > 0.0 ? overlap_shortfall(island, settings)
                                                          : separate_overlaps(island, settings);
    result.substeps = std::max(result.substeps, substeps < 0 ? settings.max_substeps : substeps);
    result.shortfall = std::max(result.shortfall, shortfall);
    result.converged = result.converged && substeps >= 0;
  }
  record_velocities_after();
  return result;
}

}    // namespace ActiveGrain
