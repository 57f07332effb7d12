#include "ag_contact_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>

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
                               const ContactMaterial &material, double min_separation,
                               const Vec3 &gain, double time)
{
  return add_contact_arms(body1, body2, point - bodies_[body1].com, point - bodies_[body2].com, n,
                          material, min_separation, gain, time);
}

int ContactSolver::add_contact_arms(int body1, int body2, const Vec3 &r1, const Vec3 &r2,
                                    const Vec3 &n, const ContactMaterial &material,
                                    double min_separation, const Vec3 &gain, double time)
{
  Contact c;
  c.body1 = body1;
  c.body2 = body2;
  c.r1 = r1;
  c.r2 = r2;
  c.n = n;
  c.material = material;
  c.min_separation = min_separation;
  c.gain = gain;
  c.time = time;
  contacts_.push_back(c);
  return num_contacts() - 1;
}

Vec3 ContactSolver::relative_velocity(const Contact &c) const
{
  return bodies_[c.body2].velocity_at_arm(c.r2) - bodies_[c.body1].velocity_at_arm(c.r1) + c.gain;
}

void ContactSolver::apply(const Contact &c, const Vec3 &J)
{
  bodies_[c.body1].apply_impulse_at_arm(-J, c.r1);
  bodies_[c.body2].apply_impulse_at_arm(J, c.r2);
}

namespace {

// The spring of one contact in a compliant impact: unit stiffness while loading; unloading
// along the line of stiffness 1/e^2 that ends (zero force) at compression peak (1 - e^2); a
// plastic contact (e = 0) unloads at once.
double spring_offset(const ContactSolver::Contact &c)
{
  const double e = c.material.e;
  return c.peak * (1.0 - e * e);
}

double spring_force(const ContactSolver::Contact &c)
{
  if (!c.unloading) return std::max(0.0, c.compression);
  if (c.material.e == 0.0) return 0.0;
  return std::max(0.0, (c.compression - spring_offset(c)) / (c.material.e * c.material.e));
}

// (A plastic contact that approaches again at its peak reloads with unit stiffness.)
double spring_stiffness(const ContactSolver::Contact &c)
{
  return c.unloading && c.material.e > 0.0 ? 1.0 / (c.material.e * c.material.e) : 1.0;
}

// The spring follows its compression: unloading once it shrinks, loading again beyond its peak.
void compress(ContactSolver::Contact &c, double change)
{
  c.compression += change;
  if (change < 0.0 && !c.unloading) c.unloading = true;
  if (c.compression > c.peak) {
    c.peak = c.compression;
    c.unloading = false;
  }
}

// The overlap correction's Jacobi pushes stop when every overlap opens within this fraction of
// its minimum separation velocity, or after this many sweeps: the correction removes a fraction
// of an overlap per step, and overlaps squeezed from opposite sides (a rod tilted between base
// and lid) cannot all open at once, so it need not converge.
constexpr double kOverlapTolerance = 1.0e-2;
constexpr int kOverlapSweeps = 100;
// In a compliant impact, a contact approaches if faster than this fraction of the island's
// largest pre-impact speed.
constexpr double kRestingSpeed = 1.0e-12;
// A compliant impact ends once no spring is loaded and no contact approaches faster than this
// fraction of the island's fastest approach before it: the slow re-collisions of a dense
// cluster's tail are left to the next time step, which finds them as contacts again.
constexpr double kSettledApproach = 1.0e-2;
// A loading spring is close to its turn when this many sub-steps of its present force would stop
// its approach.
constexpr double kTurnLookahead = 2.0;
// ... with at most the unloading stiffness of this restitution: below it the unloading returns
// too little (e^2 of the work) to be worth 2 / e sub-steps.
constexpr double kTurnStiffestE = 0.05;

// What a loading spring close to its turn adds to its stiffness: up to its unloading's.
double turning_extra(const ContactSolver::Contact &c)
{
  const double e = c.material.e;
  return 1.0 / std::max(e * e, kTurnStiffestE * kTurnStiffestE) - 1.0;
}

// An island takes at most this many impacts in order within a step; contacts that would close
// after them wait for the next step (rods bouncing between base and lid with little play).
constexpr int kMaxImpactsInOrder = 64;
// A contact is resting, not an impact, if it approaches at most this many times as fast as the
// forces of the step (its gain) make it: a rod lying on a plate under gravity. When such a
// contact closes within the step is set by nanometres of gap, so its place in the order means
// nothing: it counts as touching from the start.
constexpr double kRestingGain = 2.0;

}    // namespace

// Matrices and targets from the pre-solve velocities; which contacts share a movable body.
void ContactSolver::prepare()
{
  contacts_of_body_.assign(bodies_.size(), 0);
  for (Contact &c : contacts_) {
    c.K = contact_matrix(bodies_[c.body1], c.r1, bodies_[c.body2], c.r2);
    c.impulse = Vec3();
    ++contacts_of_body_[c.body1];
    ++contacts_of_body_[c.body2];
  }
  auto alone = [&](int body) { return bodies_[body].is_static() || contacts_of_body_[body] == 1; };
  for (Contact &c : contacts_) {
    c.isolated = alone(c.body1) && alone(c.body2);
    if (c.isolated) continue;
    c.knn = dot(c.n, c.K * c.n);
    c.tangential = TangentialStep(c.K, c.n);
  }
  find_islands();
}

// Coupled contacts that share a movable body, directly or through others, form one island;
// islands do not interact within a solve.
void ContactSolver::find_islands()
{
  island_root_.resize(bodies_.size());
  for (int b = 0; b < num_bodies(); ++b) island_root_[b] = b;
  auto root = [&](int b) {
    while (island_root_[b] != b) b = island_root_[b] = island_root_[island_root_[b]];
    return b;
  };
  for (const Contact &c : contacts_) {
    if (c.isolated || bodies_[c.body1].is_static() || bodies_[c.body2].is_static()) continue;
    const int r1 = root(c.body1), r2 = root(c.body2);
    if (r1 != r2) island_root_[std::max(r1, r2)] = std::min(r1, r2);
  }
  // The islands' lists keep their storage from solve to solve.
  island_of_root_.assign(bodies_.size(), -1);
  num_islands_ = 0;
  for (int i = 0; i < num_contacts(); ++i) {
    const Contact &c = contacts_[i];
    if (c.isolated) continue;
    const int r = root(bodies_[c.body1].is_static() ? c.body2 : c.body1);
    if (island_of_root_[r] < 0) {
      island_of_root_[r] = num_islands_++;
      if (islands_.size() < static_cast<std::size_t>(num_islands_)) islands_.emplace_back();
      islands_[island_of_root_[r]].clear();
    }
    islands_[island_of_root_[r]].push_back(i);
  }
}

// Stronge's impact of a contact alone, leaving at least at min_separation.
Vec3 ContactSolver::impact_alone(const Contact &c, double min_separation) const
{
  const Vec3 u = relative_velocity(c);
  const double target = std::max(c.material.e * std::max(0.0, -dot(u, c.n)), min_separation);
  return contact_law_impulse(c.K, u, c.n, c.material, target);
}

void ContactSolver::solve_isolated()
{
  for (Contact &c : contacts_)
    if (c.isolated) {
      c.impulse = impact_alone(c, c.min_separation);
      c.late = c.impulse * c.time;
      apply(c, c.impulse);
    }
}

// The island's bodies, each once (island_bodies_).
void ContactSolver::collect_bodies(const std::vector<int> &island)
{
  island_bodies_.clear();
  for (int i : island)
    for (int b : {contacts_[i].body1, contacts_[i].body2})
      if (!in_island_[b]) {
        in_island_[b] = 1;
        island_bodies_.push_back(b);
      }
  for (int b : island_bodies_) in_island_[b] = 0;
}

// One Jacobi step's impulses (step_impulse_) of the listed island contacts, in increasing order:
// added to the contacts and summed per movable body, so that each body's inverse inertia is
// applied once (move_bodies). The sums are zero between steps.
void ContactSolver::push(const std::vector<int> &island, const std::vector<int> &pushed)
{
  auto add = [&](int b, const Vec3 &J, const Vec3 &r) {
    if (bodies_[b].is_static()) return;
    body_momentum_[b] += J;
    body_angular_[b] += cross(r, J);
    if (!moved_[b]) {
      moved_[b] = 1;
      moved_bodies_.push_back(b);
    }
  };
  for (int k : pushed) {
    Contact &c = contacts_[island[k]];
    const Vec3 &J = step_impulse_[k];
    c.impulse += J;
    add(c.body1, -J, c.r1);
    add(c.body2, J, c.r2);
  }
}

// The pushed bodies take their summed impulses; they stay marked as moved until forget_moved().
void ContactSolver::move_bodies()
{
  for (int b : moved_bodies_) {
    RigidBodyState &body = bodies_[b];
    body.v += body_momentum_[b] * body.inv_mass;
    body.omega += body.inv_inertia * body_angular_[b];
    body_momentum_[b] = body_angular_[b] = Vec3();
  }
}

void ContactSolver::forget_moved()
{
  for (int b : moved_bodies_) moved_[b] = 0;
  moved_bodies_.clear();
}

bool ContactSolver::moved(const Contact &c) const { return moved_[c.body1] || moved_[c.body2]; }

int ContactSolver::share(const Contact &c) const
{
  return std::max(bodies_[c.body1].is_static() ? 1 : body_contacts_[c.body1],
                  bodies_[c.body2].is_static() ? 1 : body_contacts_[c.body2]);
}

// The island's springs all start to compress at once. Each sub-step: which contacts are
// engaged (loaded, or approaching at or past the compression where their force starts), a
// sub-step of pi / resolution of the fastest oscillation they make (a contact's inverse
// effective mass times the stiffness its bodies feel), the impulses of all loaded contacts from
// the same state, then the compressions move with the new velocities. A sticking contact's
// tangential impulse is shared among the loaded contacts of its bodies, so that together they
// do not overshoot. When no spring is engaged but one still approaches, the bodies fly freely
// up to its contact.
int ContactSolver::compliant_impact(const std::vector<int> &island, const Settings &settings)
{
  const double phase_per_substep = M_PI / settings.resolution;
  const std::size_t size = island.size();
  step_impulse_.resize(size);
  velocity_.resize(size);
  auto measure_velocities = [&] {
    for (std::size_t k = 0; k < size; ++k) velocity_[k] = relative_velocity(contacts_[island[k]]);
  };
  // A contact's spring stiffens its movable bodies (a static body's stays 0: it does not move).
  auto stiffen = [&](const Contact &c, double stiffness) {
    for (int b : {c.body1, c.body2})
      if (!bodies_[b].is_static()) body_stiffness_[b] += stiffness;
  };
  bool plastic = false;
  for (int i : island) {
    Contact &c = contacts_[i];
    plastic = plastic || c.material.e == 0.0;
    c.compression = c.peak = 0.0;
    c.unloading = false;
  }
  measure_velocities();
  // Approach slower than this is round-off (a plastic contact left at rest at its peak).
  double speed = 0.0;
  for (const Vec3 &u : velocity_) speed = std::max(speed, norm(u));
  const double approaching = -kRestingSpeed * speed;
  double settled = 0.0;
  for (std::size_t k = 0; k < size; ++k)
    settled = std::max(settled, -kSettledApproach * dot(velocity_[k], contacts_[island[k]].n));
  int substeps = 0;
  double previous_dtau = 0.0;    // the last drift: a kick spans half of it and half the next
  // The sub-step follows from which springs are engaged, loaded and turning; it is computed again
  // only when one of them changes (most sub-steps keep all three).
  engaged_stiffness_.assign(size, -1.0);
  force_.resize(size);
  loaded_.assign(size, 0);
  turning_.assign(size, 0);
  double engaged_dtau = 0.0, turning_dtau = 0.0;
  auto sum_body_stiffness = [&](bool with_turning) {
    for (int b : island_bodies_) body_stiffness_[b] = 0.0;
    for (std::size_t k = 0; k < size; ++k)
      if (engaged_stiffness_[k] > 0.0) stiffen(contacts_[island[k]], engaged_stiffness_[k]);
    for (std::size_t k = 0; with_turning && k < size; ++k)
      if (turning_[k]) stiffen(contacts_[island[k]], turning_extra(contacts_[island[k]]));
    double omega2 = 0.0;
    for (int i : island) {
      const Contact &c = contacts_[i];
      omega2 = std::max(omega2, c.knn * std::max(body_stiffness_[c.body1], body_stiffness_[c.body2]));
    }
    return phase_per_substep / std::sqrt(omega2);
  };
  while (true) {
    bool engaged = false, any_loaded = false, changed = false;
    double to_contact = std::numeric_limits<double>::infinity(), fastest_approach = 0.0;
    for (std::size_t k = 0; k < size; ++k) {
      const Contact &c = contacts_[island[k]];
      const double un = dot(velocity_[k], c.n);
      force_[k] = spring_force(c);
      const bool loaded = force_[k] > 0.0;
      any_loaded = any_loaded || loaded;
      fastest_approach = std::max(fastest_approach, -un);
      double stiffness = 0.0;
      if (loaded || (un < approaching && c.compression >= spring_offset(c))) {
        engaged = true;
        stiffness = spring_stiffness(c);
      } else if (un < approaching) {
        to_contact = std::min(to_contact, (spring_offset(c) - c.compression) / -un);
      }
      changed = changed || stiffness != engaged_stiffness_[k] || loaded != loaded_[k];
      engaged_stiffness_[k] = stiffness;
      loaded_[k] = loaded;
    }
    if (!any_loaded && fastest_approach <= settled) return substeps;
    if (!engaged) {
      if (!std::isfinite(to_contact)) return substeps;    // all unloaded, none approaching
      for (std::size_t k = 0; k < size; ++k) {
        Contact &c = contacts_[island[k]];
        compress(c, -dot(velocity_[k], c.n) * to_contact);
      }
      previous_dtau = 0.0;
      continue;
    }
    if (substeps == settings.max_substeps) return -1;
    ++substeps;

    if (changed) {
      for (int b : island_bodies_) body_contacts_[b] = 0;
      for (std::size_t k = 0; k < size; ++k) {
        body_contacts_[contacts_[island[k]].body1] += loaded_[k];
        body_contacts_[contacts_[island[k]].body2] += loaded_[k];
      }
      engaged_dtau = sum_body_stiffness(false);
    }
    // A loading spring close to its turn already counts with its unloading stiffness, so that
    // the sub-steps have shrunk to the unloading's when it turns (else the drift across the turn
    // skips most of a stiff unloading: an error of order pi / resolution in the rebound).
    bool turning = false, turning_changed = false;
    for (std::size_t k = 0; k < size; ++k) {
      const Contact &c = contacts_[island[k]];
      const double e = c.material.e, force = force_[k];
      const bool turns = !(c.unloading || e == 0.0 || e == 1.0 || force <= 0.0) &&
          dot(velocity_[k], c.n) + kTurnLookahead * c.knn * force * engaged_dtau >= 0.0;
      turning_changed = turning_changed || turns != static_cast<bool>(turning_[k]);
      turning_[k] = turns;
      turning = turning || turns;
    }
    if (turning && (changed || turning_changed)) turning_dtau = sum_body_stiffness(true);
    const double dtau = turning ? turning_dtau : engaged_dtau;
    const double kick = 0.5 * (previous_dtau + dtau);
    previous_dtau = dtau;

    pushed_.clear();
    for (std::size_t k = 0; k < size; ++k) {
      const Contact &c = contacts_[island[k]];
      const double dp = force_[k] * kick;
      if (dp <= 0.0) continue;
      bool stuck = false;
      Vec3 friction = c.tangential.friction(velocity_[k], c.material.mu, dp, stuck);
      if (stuck) friction *= 1.0 / share(c);
      step_impulse_[k] = c.n * dp + friction;
      pushed_.push_back(static_cast<int>(k));
    }
    push(island, pushed_);
    move_bodies();
    // A plastic contact (e = 0) passes its peak within the kick that turns its normal velocity:
    // the kick's part after the peak would return energy it must not, so it is taken back (all
    // from the same state, as the kick).
    taken_back_.clear();
    for (std::size_t i = 0; plastic && i < pushed_.size(); ++i) {
      const int k = pushed_[i];
      const Contact &c = contacts_[island[k]];
      const double before = dot(velocity_[k], c.n);
      if (c.material.e != 0.0 || before >= 0.0) continue;
      const double after = dot(relative_velocity(c), c.n);
      if (after <= 0.0) continue;
      step_impulse_[k] *= -after / (after - before);
      taken_back_.push_back(k);
    }
    if (!taken_back_.empty()) {
      push(island, taken_back_);
      move_bodies();
      for (int k : taken_back_) contacts_[island[k]].unloading = true;
    }
    // Only the pushed bodies' contacts change velocity (most of a large island's do not).
    for (std::size_t k = 0; k < size; ++k) {
      Contact &c = contacts_[island[k]];
      if (moved(c)) velocity_[k] = relative_velocity(c);
      compress(c, -dot(velocity_[k], c.n) * dtau);
    }
    forget_moved();
  }
}

// The island's contacts in the order they close within the step (see the class comment), resting
// ones from the start (kRestingGain). An impact takes the contacts that close within the window
// of the first; it leaves them touching, and settled if they approach slower than its settled
// approach (they wait for the next step, as do contacts that close after the step). Each
// contact's late impulse is the sum of its impulses times when they acted.
int ContactSolver::solve_island(const std::vector<int> &island, const Settings &settings)
{
  const std::size_t size = island.size();
  approach_.resize(size);
  auto measure_approaches = [&] {
    for (std::size_t k = 0; k < size; ++k) {
      const Contact &c = contacts_[island[k]];
      approach_[k] = -dot(relative_velocity(c), c.n);
    }
  };
  auto closing_time = [&](std::size_t k) {
    const Contact &c = contacts_[island[k]];
    return approach_[k] <= kRestingGain * std::fabs(dot(c.gain, c.n)) ? 0.0 : c.time;
  };
  double first = 0.0, last = 0.0;
  if (std::isfinite(settings.window)) {
    measure_approaches();
    first = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < size; ++k) {
      first = std::min(first, closing_time(k));
      last = std::max(last, closing_time(k));
    }
  }
  if (last - first <= settings.window) {
    collect_bodies(island);
    const int substeps = compliant_impact(island, settings);
    for (int i : island) contacts_[i].late = contacts_[i].impulse * contacts_[i].time;
    return substeps;
  }
  gap_.resize(size);
  impulse_before_.resize(size);
  floor_.assign(size, 0.0);
  for (std::size_t k = 0; k < size; ++k) {
    gap_[k] = std::max(0.0, approach_[k]) * closing_time(k);
    contacts_[island[k]].late = Vec3();
  }
  // Whether contact k closes within the window from now (gap_ at now).
  auto in_impact = [&](std::size_t k) {
    return approach_[k] > floor_[k] && gap_[k] <= approach_[k] * settings.window;
  };
  int substeps = 0;
  double now = 0.0;
  for (int impacts = 0; impacts < kMaxImpactsInOrder; ++impacts) {
    double next = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < size; ++k)
      if (approach_[k] > floor_[k]) next = std::min(next, std::max(0.0, gap_[k]) / approach_[k]);
    if (!(now + next <= settings.step)) break;
    now += next;
    wave_.clear();
    double fastest = 0.0;
    for (std::size_t k = 0; k < size; ++k) {
      gap_[k] -= approach_[k] * next;
      if (!in_impact(k)) continue;
      wave_.push_back(island[k]);
      impulse_before_[k] = contacts_[island[k]].impulse;
      fastest = std::max(fastest, approach_[k]);
    }
    if (wave_.size() == 1) {
      Contact &c = contacts_[wave_[0]];
      const Vec3 J = impact_alone(c, 0.0);    // overlaps are opened after all impacts
      c.impulse += J;
      apply(c, J);
    } else {
      collect_bodies(wave_);
      const int s = compliant_impact(wave_, settings);
      if (s < 0) return -1;
      substeps = std::max(substeps, s);
    }
    for (std::size_t k = 0; k < size; ++k) {
      if (!in_impact(k)) continue;
      Contact &c = contacts_[island[k]];
      c.late += (c.impulse - impulse_before_[k]) * (now + std::max(0.0, gap_[k]) / approach_[k]);
      gap_[k] = 0.0;
      floor_[k] = kSettledApproach * fastest;
    }
    measure_approaches();
  }
  return substeps;
}

// Overlapping contacts must open at least at their minimum separation velocity: pushes where one
// opens slower, with Stronge's friction for their normal impulse (a body resting on a plate
// under gravity sits on these pushes), each shared among the pushed contacts of its bodies (a
// Jacobi step).
double ContactSolver::separate_overlaps(const std::vector<int> &island)
{
  double largest = 0.0;
  step_impulse_.resize(island.size());
  velocity_.resize(island.size());
  for (int sweep = 0; sweep < kOverlapSweeps; ++sweep) {
    for (int b : island_bodies_) body_contacts_[b] = 0;
    largest = 0.0;
    pushed_.clear();
    for (std::size_t k = 0; k < island.size(); ++k) {
      const Contact &c = contacts_[island[k]];
      velocity_[k] = relative_velocity(c);
      const double shortfall = c.min_separation - dot(velocity_[k], c.n);
      if (c.min_separation <= 0.0 || shortfall <= kOverlapTolerance * c.min_separation) continue;
      largest = std::max(largest, shortfall / c.min_separation);
      const double dp = shortfall / c.knn;
      bool stuck = false;
      step_impulse_[k] = c.n * dp + c.tangential.friction(velocity_[k], c.material.mu, dp, stuck);
      pushed_.push_back(static_cast<int>(k));
      ++body_contacts_[c.body1];
      ++body_contacts_[c.body2];
    }
    if (largest == 0.0) break;
    for (int k : pushed_) step_impulse_[k] *= 1.0 / share(contacts_[island[k]]);
    push(island, pushed_);
    move_bodies();
    forget_moved();
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
  solve_isolated();
  Result result;
  body_stiffness_.assign(bodies_.size(), 0.0);
  body_contacts_.assign(bodies_.size(), 0);
  body_momentum_.assign(bodies_.size(), Vec3());
  body_angular_.assign(bodies_.size(), Vec3());
  moved_.assign(bodies_.size(), 0);
  in_island_.assign(bodies_.size(), 0);
  for (int k = 0; k < num_islands_; ++k) {
    const std::vector<int> &island = islands_[k];
    const int substeps = solve_island(island, settings);
    collect_bodies(island);
    const double shortfall = separate_overlaps(island);
    result.substeps = std::max(result.substeps, substeps < 0 ? settings.max_substeps : substeps);
    result.shortfall = std::max(result.shortfall, shortfall);
    result.converged = result.converged && substeps >= 0;
  }
  return result;
}

}    // namespace ActiveGrain
