#include "ag_compliant_impact.h"

#include <algorithm>
#include <cmath>

namespace ActiveGrain {

namespace {

// A contact approaches if faster than this fraction of the island's largest speed before the
// impact: slower is round-off (a plastic contact left at rest at its peak).
constexpr double ROUNDOFF_SPEED = 1.0e-12;
// A loading spring is close to its turn when this many sub-steps of its present force would stop
// its approach...
constexpr double TURN_LOOKAHEAD = 2.0;
// ... and counts with at most the unloading stiffness of this restitution: below it the
// unloading returns too little (e^2 of the work) to be worth 2 / e sub-steps.
constexpr double TURN_STIFFEST_E = 0.05;
// A spring's engaged stiffness before its first classification: any stiffness is a change.
constexpr double UNCLASSIFIED = -1.0;

}    // namespace

double CompliantImpact::Spring::force() const
{
  if (!unloading) return std::max(0.0, compression);
  if (e == 0.0) return 0.0;
  return std::max(0.0, (compression - offset()) / (e * e));
}

void CompliantImpact::Spring::compress(double change)
{
  compression += change;
  if (change < 0.0 && !unloading) unloading = true;
  if (compression > peak) {
    peak = compression;
    unloading = false;
  }
}

double CompliantImpact::Spring::turning_extra() const
{
  return 1.0 / std::max(e * e, TURN_STIFFEST_E * TURN_STIFFEST_E) - 1.0;
}

void CompliantImpact::resize(std::size_t num_bodies)
{
  body_stiffness.assign(num_bodies, 0.0);
  body_tangential.assign(num_bodies, 0.0);
  jacobi.resize(num_bodies);
}

// Each sub-step: which springs are engaged, a sub-step of pi / resolution of the fastest
// oscillation they make, the impulses of all loaded springs from the same state (a plastic one's
// part past its peak taken back), then the compressions move with the new velocities. When no
// spring is engaged but one still approaches, the bodies fly freely up to its contact.
int CompliantImpact::solve(std::vector<RigidBodyState> &bodies, std::vector<SolverContact> &contacts,
                           const std::vector<int> &island, const SolverSettings &settings)
{
  start(bodies, contacts, island, settings);
  int substeps = 0;
  while (true) {
    const Engagement found = classify();
    if (ended(found)) {
      if (compliant) keep_within_start_energy();
      return substeps;
    }
    if (!found.engaged) {
      fly(found.to_contact);
      continue;
    }
    if (substeps == settings.max_substeps) {
      if (compliant) keep_within_start_energy();
      return -1;
    }
    ++substeps;
    const double dtau = substep_size(found.changed);
    kick(dtau);
    take_back();
    drift(dtau);
  }
}

// The island's springs all start to compress at once, from zero.
void CompliantImpact::start(std::vector<RigidBodyState> &bodies, std::vector<SolverContact> &contacts,
                            const std::vector<int> &island, const SolverSettings &settings)
{
  solver_bodies = &bodies;
  solver_contacts = &contacts;
  island_contacts = &island;
  jacobi.start_island(bodies, contacts, island);
  phase_per_substep = PI / settings.resolution;
  const std::size_t n = island.size();
  springs.assign(n, Spring());
  velocities.resize(n);
  plastic = compliant = false;
  for (std::size_t k = 0; k < n; ++k) {
    springs[k].e = contact(k).model.normal.e;
    plastic = plastic || springs[k].e == 0.0;
    compliant = compliant || contact(k).model.tangential.compliant();
    velocities[k] = contact_velocity(k);
  }
  if (compliant) {
    stretch.assign(n, Vec3());
    start_velocity = velocities;
    start_impulse.resize(n);
    for (std::size_t k = 0; k < n; ++k) start_impulse[k] = contact(k).impulse;
    const std::vector<int> &island_bodies = jacobi.island_bodies();
    start_v.resize(island_bodies.size());
    start_omega.resize(island_bodies.size());
    for (std::size_t i = 0; i < island_bodies.size(); ++i) {
      start_v[i] = bodies[island_bodies[i]].v;
      start_omega[i] = bodies[island_bodies[i]].omega;
    }
  }
  double speed = 0.0;
  for (const Vec3 &u : velocities) speed = std::max(speed, norm(u));
  approaching_below = -ROUNDOFF_SPEED * speed;
  settled_speed = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    settled_speed = std::max(settled_speed, -settings.settled_approach * dot(velocities[k], contact(k).n));
  previous_dtau = engaged_dtau = turning_dtau = 0.0;
  engaged_stiffness.assign(n, UNCLASSIFIED);
  forces.resize(n);
  loaded.assign(n, 0);
  turning.assign(n, 0);
}

// A spring is engaged if loaded, or approaching at or past the compression where its force
// starts; else, if it approaches, the free flight ends when it gets there.
CompliantImpact::Engagement CompliantImpact::classify()
{
  Engagement found;
  for (std::size_t k = 0; k < size(); ++k) {
    const Spring &s = springs[k];
    const double un = dot(velocities[k], contact(k).n);
    forces[k] = s.force();
    const bool is_loaded = forces[k] > 0.0;
    found.loaded = found.loaded || is_loaded;
    found.fastest_approach = std::max(found.fastest_approach, -un);
    double stiffness = 0.0;
    if (is_loaded || (un < approaching_below && s.compression >= s.offset())) {
      found.engaged = true;
      stiffness = s.stiffness();
    } else if (un < approaching_below) {
      found.to_contact = std::min(found.to_contact, (s.offset() - s.compression) / -un);
    }
    found.changed = found.changed || stiffness != engaged_stiffness[k] || is_loaded != loaded[k];
    engaged_stiffness[k] = stiffness;
    loaded[k] = is_loaded;
  }
  return found;
}

// Every spring unloaded and no contact approaching faster than settled, or none engaged and none
// approaching.
bool CompliantImpact::ended(const Engagement &found) const
{
  return (!found.loaded && found.fastest_approach <= settled_speed) ||
      (!found.engaged && !std::isfinite(found.to_contact));
}

// A flight of time zero is an underflow: the nearest spring's gap to its offset is denormal (an
// elastic one back at zero compression), and no flight can close it. It starts at its offset, or
// the impact would fly forever.
void CompliantImpact::fly(double time)
{
  for (std::size_t k = 0; k < size(); ++k) springs[k].compress(-dot(velocities[k], contact(k).n) * time);
  previous_dtau = 0.0;
  if (time > 0.0) return;
  for (std::size_t k = 0; k < size(); ++k) {
    Spring &s = springs[k];
    const double un = dot(velocities[k], contact(k).n);
    if (un < approaching_below && s.compression < s.offset() && (s.offset() - s.compression) / -un == 0.0)
      s.compression = s.offset();
  }
}

double CompliantImpact::substep_size(bool changed)
{
  if (changed) {
    count_loaded();
    engaged_dtau = stiffest_substep(false);
  }
  bool turning_changed = false;
  const bool any_turning = find_turning(turning_changed);
  if (any_turning && (changed || turning_changed)) turning_dtau = stiffest_substep(true);
  return any_turning ? turning_dtau : engaged_dtau;
}

// The loaded springs on each body: a sticking contact's share of its bodies' impulses (kick).
void CompliantImpact::count_loaded()
{
  jacobi.clear_counts();
  for (std::size_t k = 0; k < size(); ++k)
    if (loaded[k]) jacobi.count(k);
}

// pi / resolution of the fastest oscillation of the engaged springs: a contact's n.K.n times the
// stiffness of the springs on its bodies (a static body's stays 0: it does not move); with
// with_turning, a turning spring already with its unloading's stiffness.
double CompliantImpact::stiffest_substep(bool with_turning)
{
  auto stiffen = [&](const SolverContact &c, double stiffness) {
    for (int b : {c.body1, c.body2})
      if (!(*solver_bodies)[b].is_static()) body_stiffness[b] += stiffness;
  };
  for (int b : jacobi.island_bodies()) body_stiffness[b] = 0.0;
  for (std::size_t k = 0; k < size(); ++k)
    if (engaged_stiffness[k] > 0.0) stiffen(contact(k), engaged_stiffness[k]);
  for (std::size_t k = 0; with_turning && k < size(); ++k)
    if (turning[k]) stiffen(contact(k), springs[k].turning_extra());
  double omega2 = 0.0;
  for (std::size_t k = 0; k < size(); ++k) {
    const SolverContact &c = contact(k);
    omega2 = std::max(omega2, c.knn * std::max(body_stiffness[c.body1], body_stiffness[c.body2]));
  }
  if (!compliant) return phase_per_substep / std::sqrt(omega2);
  // The tangential springs' oscillations, with K's trace across the plane (at least its largest
  // eigenvalue there).
  for (int b : jacobi.island_bodies()) body_tangential[b] = 0.0;
  for (std::size_t k = 0; k < size(); ++k) {
    const SolverContact &c = contact(k);
    if (engaged_stiffness[k] <= 0.0 || !c.model.tangential.compliant()) continue;
    for (int b : {c.body1, c.body2})
      if (!(*solver_bodies)[b].is_static()) body_tangential[b] += c.model.tangential.stiffness_ratio;
  }
  for (std::size_t k = 0; k < size(); ++k) {
    const SolverContact &c = contact(k);
    const double across = c.K.m[0][0] + c.K.m[1][1] + c.K.m[2][2] - c.knn;
    omega2 = std::max(omega2, across * std::max(body_tangential[c.body1], body_tangential[c.body2]));
  }
  return phase_per_substep / std::sqrt(omega2);
}

// A loading spring close to its turn already counts with its unloading stiffness, so that the
// sub-steps have shrunk to the unloading's when it turns (else the drift across the turn skips
// most of a stiff unloading: an error of order pi / resolution in the rebound).
bool CompliantImpact::find_turning(bool &changed)
{
  bool any = false;
  for (std::size_t k = 0; k < size(); ++k) {
    const SolverContact &c = contact(k);
    const Spring &s = springs[k];
    const double force = forces[k];
    const bool turns = !(s.unloading || s.e == 0.0 || s.e == 1.0 || force <= 0.0) &&
        dot(velocities[k], c.n) + TURN_LOOKAHEAD * c.knn * force * engaged_dtau >= 0.0;
    changed = changed || turns != static_cast<bool>(turning[k]);
    turning[k] = turns;
    any = any || turns;
  }
  return any;
}

// The kick spans half the last drift and half this one. A sticking contact's tangential impulse
// is shared among the loaded contacts of its bodies, so that together they do not overshoot.
void CompliantImpact::kick(double dtau)
{
  const double span = 0.5 * (previous_dtau + dtau);
  previous_dtau = dtau;
  jacobi.start_step();
  for (std::size_t k = 0; k < size(); ++k) {
    const SolverContact &c = contact(k);
    const double dp = forces[k] * span;
    if (dp <= 0.0) continue;
    jacobi.add(k, c.n * dp + tangential_impulse(k, dp, span));
  }
  jacobi.push();
  jacobi.move_bodies();
}

// Sticking law: the friction that stops the slip, shared among the loaded contacts of its bodies
// (so that together they do not overshoot), else mu dp against it. Compliant law: the tangential
// spring's push, its stretch first cut back to what mu times the normal force holds (the slider
// slips).
Vec3 CompliantImpact::tangential_impulse(std::size_t k, double dp, double span)
{
  const SolverContact &c = contact(k);
  const TangentialModel &law = c.model.tangential;
  if (!law.compliant()) {
    bool stuck = false;
    Vec3 friction = law.friction(c.tangential, velocities[k], dp, stuck);
    if (stuck) friction *= 1.0 / jacobi.share(k);
    return friction;
  }
  Vec3 &s = stretch[k];
  const double held = law.limit(forces[k]), force = law.stiffness_ratio * norm(s);
  if (force > held) s *= held / force;
  return s * (-law.stiffness_ratio * span);
}

// A plastic contact (e = 0) passes its peak within the kick that turns its normal velocity: the
// kick's part after the peak would return energy it must not, so it is taken back (all from the
// same state, as the kick) and the spring unloads.
void CompliantImpact::take_back()
{
  taken_back.clear();
  const std::vector<int> &pushed = jacobi.pushed();
  for (std::size_t i = 0; plastic && i < pushed.size(); ++i) {
    const int k = pushed[i];
    const SolverContact &c = contact(k);
    const double before = dot(velocities[k], c.n);
    if (!c.model.normal.plastic() || before >= 0.0) continue;
    const double after = dot(contact_velocity(k), c.n);
    if (after <= 0.0) continue;
    jacobi.impulse(k) *= -after / (after - before);
    taken_back.push_back(k);
  }
  if (taken_back.empty()) return;
  jacobi.push(taken_back);
  jacobi.move_bodies();
  for (int k : taken_back) springs[k].unloading = true;
}

// Only the pushed bodies' contacts change velocity (most of a large island's do not). A
// tangential spring stretches with the slip while its contact is loaded and is slack otherwise.
void CompliantImpact::drift(double dtau)
{
  for (std::size_t k = 0; k < size(); ++k) {
    if (jacobi.moved(k)) velocities[k] = contact_velocity(k);
    const Vec3 &n = contact(k).n;
    const double un = dot(velocities[k], n);
    springs[k].compress(-un * dtau);
    if (compliant) stretch[k] = engaged_stiffness[k] > 0.0 ? stretch[k] + (velocities[k] - n * un) * dtau : Vec3();
  }
  jacobi.forget_moved();
}

// The kinetic energy the impulses J add, sum J . (u_start + u_end) / 2 over the contacts, is
// s a + s^2 b for the impulses scaled by s: where it is positive at s = 1, the largest s that adds
// none (velocities and impulses are linear in s).
void CompliantImpact::keep_within_start_energy()
{
  double a = 0.0, b = 0.0;
  for (std::size_t k = 0; k < size(); ++k) {
    const Vec3 J = contact(k).impulse - start_impulse[k];
    a += dot(J, start_velocity[k]);
    b += 0.5 * dot(J, contact_velocity(k) - start_velocity[k]);
  }
  if (a + b <= 0.0) return;
  const double s = a < 0.0 && b > 0.0 ? -a / b : 0.0;
  std::vector<RigidBodyState> &bodies = *solver_bodies;
  const std::vector<int> &island_bodies = jacobi.island_bodies();
  for (std::size_t i = 0; i < island_bodies.size(); ++i) {
    RigidBodyState &body = bodies[island_bodies[i]];
    body.v = start_v[i] + (body.v - start_v[i]) * s;
    body.omega = start_omega[i] + (body.omega - start_omega[i]) * s;
  }
  for (std::size_t k = 0; k < size(); ++k) {
    Vec3 &impulse = contact(k).impulse;
    impulse = start_impulse[k] + (impulse - start_impulse[k]) * s;
  }
}

}    // namespace ActiveGrain
