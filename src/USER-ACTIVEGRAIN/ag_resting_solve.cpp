#include "ag_resting_solve.h"

#include <algorithm>
#include <cmath>

namespace ActiveGrain {

namespace {

// Over-relaxation of the normal impulses: faster convergence up to oscillation near 2.
constexpr double RELAXATION = 1.7;

// The largest velocity change a converged sweep asks of a contact.
double converged_speed(const SolverSettings &settings) { return settings.resting_tolerance * settings.resting_speed; }

}    // namespace

void RestingSolve::resize(std::size_t num_bodies) { body_colours.resize(num_bodies); }

int RestingSolve::solve(std::vector<RigidBodyState> &bodies, std::vector<SolverContact> &contacts,
                        const std::vector<int> &island, const SolverSettings &settings)
{
  prepare(bodies, contacts, island, settings);
  int sweeps = sweeps_to_tolerance(settings);
  if (collisions) {
    keep_compression();
    expand();
    const int more = sweeps_to_tolerance(settings);
    sweeps = sweeps < 0 || more < 0 ? -1 : sweeps + more;
    blend_within_overlap_credit();
  }
  store();
  return sweeps;
}

int RestingSolve::sweeps_to_tolerance(const SolverSettings &settings)
{
  const double converged = converged_speed(settings);
  for (int sweeps = 1; sweeps <= settings.max_resting_sweeps; ++sweeps)
    if (sweep() <= converged * converged) return sweeps;
  return -1;
}

// The contacts in the order of their keys, coloured greedily so that no two of one colour share
// a movable body: the contacts of a colour are then independent, and a sweep over the colours is
// the same in any order the contacts came in.
void RestingSolve::prepare(std::vector<RigidBodyState> &bodies, std::vector<SolverContact> &contacts,
                           const std::vector<int> &island, const SolverSettings &settings)
{
  solver_bodies = &bodies;
  solver_contacts = &contacts;
  island_contacts = &island;
  const std::size_t n = island.size();
  by_key.resize(n);
  for (std::size_t k = 0; k < n; ++k) by_key[k] = static_cast<int>(k);
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
  rows.resize(n);
  collisions = false;
  for (std::size_t i = 0; i < n; ++i) {
    const int k = sweep_order[i];
    const SolverContact &c = contact(k);
    Row &row = rows[i];
    row.contact = k;
    row.body1 = c.body1;
    row.body2 = c.body2;
    row.r1 = c.r1;
    row.r2 = c.r2;
    row.gain = c.gain;
    row.n = c.n;
    row.plane = c.tangential.plane();
    row.target = row.overlap_target = std::max(0.0, c.min_separation);
    row.restitution = row.floor = 0.0;
    if (settings.resting_restitution) {
      row.before = relative_velocity(bodies, c);
      // Faster than its gain makes it, beyond what the last solve's tolerance leaves: a collision.
      const double settling = settings.resting_gain * std::fabs(dot(c.gain, c.n)) + converged_speed(settings);
      if (-dot(row.before, c.n) > settling) row.restitution = c.model.normal.e;
      collisions = collisions || row.restitution > 0.0;
    }
    row.normal_mass = 1.0 / c.knn;
    row.mu = c.model.tangential.mu;
    row.kn = c.K * c.n;
    row.kt1 = c.K * row.plane.tangent1;
    row.kt2 = c.K * row.plane.tangent2;
    row.normal = row.tangent1 = row.tangent2 = 0.0;
    row.with_next = i + 1 < n && colour_of[sweep_order[i + 1]] == colour_of[k];
  }
  if (!collisions) return;
  // An overlap's push is no part of the compression that the expansion gives back: the
  // compression stops the approaches, the sweeps after the expansion open the overlaps.
  for (Row &row : rows) row.target = 0.0;
  island_bodies.clear();
  for (const Row &row : rows)
    for (int b : {row.body1, row.body2})
      if (!bodies[b].is_static()) island_bodies.push_back(b);
  std::sort(island_bodies.begin(), island_bodies.end());
  island_bodies.erase(std::unique(island_bodies.begin(), island_bodies.end()), island_bodies.end());
}

// The normal impulse that makes the contact leave at its target (never pulling, nor below its
// floor; over-relaxed), then the friction that stops its slip within mu times it. A contact that
// stays open and carried nothing has nothing to do (zero).
Vec3 RestingSolve::row_impulse(Row &row, const Vec3 &u, double &asked2)
{
  const double asked = (row.target - dot(u, row.n)) * row.normal_mass;
  const double pn = std::max(row.floor, row.normal + RELAXATION * asked);
  if (pn == 0.0 && row.normal == 0.0) {
    asked2 = 0.0;
    return Vec3();
  }
  const double dpn = pn - row.normal;
  // The friction that stops the slip after dpn, within the Coulomb disc of radius mu pn.
  const TangentPlane &p = row.plane;
  const double b1 = -dot(p.tangent1, u) - dpn * p.kn1, b2 = -dot(p.tangent2, u) - dpn * p.kn2;
  double pt1 = row.tangent1 + p.inv11 * b1 + p.inv12 * b2;
  double pt2 = row.tangent2 + p.inv12 * b1 + p.inv22 * b2;
  const double limit = row.mu * pn, length2 = pt1 * pt1 + pt2 * pt2;
  if (length2 > limit * limit) {
    const double scale = limit / std::sqrt(length2);
    pt1 *= scale;
    pt2 *= scale;
  }
  const double dt1 = pt1 - row.tangent1, dt2 = pt2 - row.tangent2;
  asked2 = norm2(row.kn * std::max(row.floor - row.normal, asked) + row.kt1 * dt1 + row.kt2 * dt2);
  row.normal = pn;
  row.tangent1 = pt1;
  row.tangent2 = pt2;
  return row.n * dpn + p.tangent1 * dt1 + p.tangent2 * dt2;
}

// Each contact in turn, colour by colour; two of one colour at a time where they follow each
// other (they share no movable body, so the second's velocities need not wait for the first's
// impulse). Returns the square of the largest velocity change a contact asked for.
double RestingSolve::sweep()
{
  std::vector<RigidBodyState> &bodies = *solver_bodies;
  double largest = 0.0;
  for (std::size_t i = 0; i < rows.size();) {
    Row &a = rows[i];
    if (a.with_next) {
      Row &b = rows[i + 1];
      const Vec3 ua = relative_velocity(bodies, a), ub = relative_velocity(bodies, b);
      double asked_a, asked_b;
      const Vec3 Ja = row_impulse(a, ua, asked_a), Jb = row_impulse(b, ub, asked_b);
      apply_impulse(bodies, a, Ja);
      apply_impulse(bodies, b, Jb);
      largest = std::max(largest, std::max(asked_a, asked_b));
      i += 2;
    } else {
      double asked;
      apply_impulse(bodies, a, row_impulse(a, relative_velocity(bodies, a), asked));
      largest = std::max(largest, asked);
      ++i;
    }
  }
  return largest;
}

void RestingSolve::keep_compression()
{
  const std::vector<RigidBodyState> &bodies = *solver_bodies;
  compression_v.resize(island_bodies.size());
  compression_omega.resize(island_bodies.size());
  for (std::size_t i = 0; i < island_bodies.size(); ++i) {
    compression_v[i] = bodies[island_bodies[i]].v;
    compression_omega[i] = bodies[island_bodies[i]].omega;
  }
  compression_impulse.resize(rows.size());
  compression_after.resize(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    compression_impulse[i] = {rows[i].normal, rows[i].tangent1, rows[i].tangent2};
    compression_after[i] = relative_velocity(bodies, rows[i]);
  }
}

// Poisson's expansion: each colliding contact gets e times its compression's normal impulse
// again, which its normal impulse then keeps as a floor while the sweeps that follow stop the
// contacts this makes approach and the slips it starts (friction within mu times the whole).
void RestingSolve::expand()
{
  std::vector<RigidBodyState> &bodies = *solver_bodies;
  for (Row &row : rows) {
    const double expansion = row.restitution * row.normal;
    row.normal += expansion;
    row.floor = row.normal;
    row.target = row.overlap_target;
    if (expansion > 0.0) apply_impulse(bodies, row, row.n * expansion);
  }
}

// What the overlaps' pushes may add: for each, 1/2 m (s^2 - (e a)^2) where its minimum separation
// velocity s exceeds what its restitution gives (the energy ledger's credit, ag_contact_energy.h).
double RestingSolve::overlap_credit() const
{
  double credit = 0.0;
  for (const Row &row : rows) {
    const double kept = row.restitution * std::max(0.0, -dot(row.before, row.n));
    if (row.overlap_target > kept) credit += 0.5 * row.normal_mass * (row.overlap_target * row.overlap_target - kept * kept);
  }
  return credit;
}

// Impulses and velocities are linear in a blend s of the compression (0) and the solution with
// restitution (1): every contact of a blend leaves at least at the compression's target, every
// impulse lies in its cone. The energy change is quadratic in s, compression + s a + s^2 b: the
// largest s <= 1 at which it gains no more than the overlaps' credit. (Where that stops short,
// the overlaps open short by as much; the solver reports it.)
void RestingSolve::blend_within_overlap_credit()
{
  std::vector<RigidBodyState> &bodies = *solver_bodies;
  double compression_change = 0.0, a = 0.0, b = 0.0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row &row = rows[i];
    const RowImpulse &p = compression_impulse[i];
    const Vec3 compressed = row.n * p.normal + row.plane.tangent1 * p.tangent1 + row.plane.tangent2 * p.tangent2;
    const Vec3 dJ = row_impulse_sum(row) - compressed, du = relative_velocity(bodies, row) - compression_after[i];
    compression_change += 0.5 * dot(compressed, row.before + compression_after[i]);
    a += 0.5 * (dot(dJ, row.before + compression_after[i]) + dot(compressed, du));
    b += 0.5 * dot(dJ, du);
  }
  const double room = std::max(0.0, overlap_credit() - compression_change);    // s a + s^2 b <= room
  if (a + b <= room) return;
  const double root = std::sqrt(std::max(0.0, a * a + 4.0 * b * room));
  double s = b > 0.0 ? (root - a) / (2.0 * b) : b < 0.0 ? 2.0 * room / (a + root) : room / a;
  s = std::min(1.0, std::max(0.0, s));
  for (std::size_t i = 0; i < island_bodies.size(); ++i) {
    RigidBodyState &body = bodies[island_bodies[i]];
    body.v = compression_v[i] + (body.v - compression_v[i]) * s;
    body.omega = compression_omega[i] + (body.omega - compression_omega[i]) * s;
  }
  for (std::size_t i = 0; i < rows.size(); ++i) {
    Row &row = rows[i];
    const RowImpulse &p = compression_impulse[i];
    row.normal = p.normal + (row.normal - p.normal) * s;
    row.tangent1 = p.tangent1 + (row.tangent1 - p.tangent1) * s;
    row.tangent2 = p.tangent2 + (row.tangent2 - p.tangent2) * s;
  }
}

void RestingSolve::store()
{
  for (const Row &row : rows) {
    SolverContact &c = contact(row.contact);
    const Vec3 resting = row_impulse_sum(row);
    c.impulse += resting;
    c.late += resting * c.time;
  }
}

}    // namespace ActiveGrain
