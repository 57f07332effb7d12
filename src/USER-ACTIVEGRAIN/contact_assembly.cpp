#include "contact_assembly.h"

#include "ag_hash.h"
#include "atom.h"
#include "contact_ranks.h"
#include "domain.h"
#include "near_pairs.h"
#include "neighbor.h"
#include "solver_bodies.h"
#include "update.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;
using ActiveGrain::ContactModel;
using ActiveGrain::Vec3;

// The near pairs are those within this fraction of the neighbor skin.
static constexpr double NEAR_MARGIN = 0.25;

void ContactAssembly::init(double overlap_beta, double overlap_slop, ContactOrder contact_order,
                           const PairContactModels *pair_models, const std::vector<ImpulseWall *> &wall_fixes)
{
  beta = overlap_beta;
  slop = overlap_slop;
  order = contact_order;
  models = pair_models;
  walls = wall_fixes;
}

void ContactAssembly::scan_atoms(const double *maxrad)
{
  const int nall = atom->nlocal + atom->nghost;
  spin_speed.resize(nall);
  step = StepExtremes();
  for (int i = 0; i < nall; i++) {
    spin_speed[i] = norm(Vec3(atom->omega[i])) * atom->radius[i];
    const double speed = norm(Vec3(atom->v[i])) + spin_speed[i];
    step.fastest_near = std::max(step.fastest_near, speed);
    if (i >= atom->nlocal) continue;
    step.fastest = std::max(step.fastest, speed);
    step.radius_excess = std::max(step.radius_excess, atom->radius[i] - maxrad[atom->type[i]]);
  }
}

void ContactAssembly::assemble(NeighList *list)
{
  atom_contacts.clear();
  found.clear();
  gather_pair_contacts(list);
  gather_wall_contacts();
  add_found_contacts();
}

void ContactAssembly::gather_pair_contacts(NeighList *list)
{
  double **x = atom->x, **v = atom->v;
  double *radius = atom->radius;
  int *type = atom->type;
  const double margin = NEAR_MARGIN * neighbor->skin;
  near.refresh(list, ranks, margin, step.fastest_near);
  for (const auto &pair : near.pairs()) {
    const int i = pair.first, j = pair.second;
    if (!ranks.solves_atom(i)) continue;    // a body's copy solved on another rank or image
    Vec3 d = Vec3(x[j]) - Vec3(x[i]);
    const double radsum = radius[i] + radius[j];
    const double rsq = norm2(d);
    if (rsq >= (radsum + margin) * (radsum + margin) || rsq == 0.0) continue;
    const double r = std::sqrt(rsq);
    const double gap = r - radsum;
    if (!ActiveGrain::gap_may_close(gap, Vec3(v[i]) - Vec3(v[j]), spin_speed[i] + spin_speed[j], update->dt))
      continue;
    const Vec3 n = d / r;    // from i to j
    const Vec3 point = Vec3(x[i]) + n * (radius[i] + 0.5 * gap);
    if (ActiveGrain::stays_open(gap, bodies.atom_velocity_at(j, point) - bodies.atom_velocity_at(i, point), n,
                                update->dt))
      continue;
    const int bi = bodies.body_of_atom(i), bj = bodies.body_of_atom(j);
    if (bi == bj) continue;    // constituents of one rigid body, or a bead and its image
    if (solver.body(bi).is_static() && solver.body(bj).is_static()) continue;    // both frozen
    add_contact(bi, bj, {i, j, nullptr, 0, point, Vec3(), 0.0, Vec3()}, n, gap, models->of(type[i], type[j]),
                bodies.lever_arm(i, bi, point), bodies.lever_arm(j, bj, point),
                bodies.gravity_of_atom(j) - bodies.gravity_of_atom(i));
  }
}

void ContactAssembly::gather_wall_contacts()
{
  const double reach = neighbor->skin;
  for (ImpulseWall *wall : walls) {
    wall_contacts.clear();
    wall->find_wall_contacts(reach, ranks.solved_atoms(), spin_speed, wall_contacts);
    step.wall_speed = std::max(step.wall_speed, wall->wall_speed());
    for (const ImpulseWall::Contact &c : wall_contacts) {
      if (ActiveGrain::stays_open(c.gap, bodies.atom_velocity_at(c.atom, c.point) - c.wall_velocity, c.normal,
                                  update->dt))
        continue;
      const int b = bodies.body_of_atom(c.atom);
      if (solver.body(b).is_static()) continue;    // a frozen atom
      const int w = solver.add_body(ActiveGrain::RigidBodyState::wall(c.wall_velocity));
      add_contact(w, b, {-1, c.atom, wall, c.surface, c.point, Vec3(), 0.0, Vec3()}, c.normal, c.gap,
                  c.model, Vec3(), bodies.lever_arm(c.atom, b, c.point), bodies.gravity_of_atom(c.atom),
                  c.wall_acceleration);
    }
  }
}

void ContactAssembly::add_contact(int body1, int body2, const AtomContact &atoms, const Vec3 &n, double gap,
                                  const ContactModel &model, const Vec3 &r1, const Vec3 &r2,
                                  const Vec3 &atom_acceleration, const Vec3 &wall_acceleration)
{
  const Vec3 u = solver.body(body2).velocity_at_arm(r2) - solver.body(body1).velocity_at_arm(r1);
  const ActiveGrain::ContactPrediction prediction =
      ActiveGrain::predict_contact(gap, u, n, update->dt, beta, slop, atom_acceleration, wall_acceleration);
  if (!prediction.closes) return;
  const ContactIdentity identity = identity_of(atoms);
  // The shuffled order: a hash of the step and the contact's identity, the same on any rank.
  const std::uint64_t shuffle = ActiveGrain::hash_words(
      {static_cast<std::uint64_t>(update->ntimestep), static_cast<std::uint64_t>(std::get<0>(identity) + 1),
       static_cast<std::uint64_t>(atoms.surface), static_cast<std::uint64_t>(std::get<2>(identity)),
       static_cast<std::uint64_t>(std::get<3>(identity))});
  AtomContact located = atoms;
  located.approach = prediction.approach;
  located.velocity_before = u;
  if (atoms.wall) located.wall_velocity = solver.body(body1).v + wall_acceleration * prediction.time_to_contact;
  found.push_back({shuffle, identity, body1, body2, r1, r2, n, model, prediction, located});
  step.overlap = std::max(step.overlap, -gap);
}

ContactAssembly::ContactIdentity ContactAssembly::identity_of(const AtomContact &atoms) const
{
  const int wall_index =
      atoms.wall ? static_cast<int>(std::find(walls.begin(), walls.end(), atoms.wall) - walls.begin()) : -1;
  const tagint tag1 = atoms.atom1 >= 0 ? atom->tag[atoms.atom1] : 0, tag2 = atom->tag[atoms.atom2];
  return ContactIdentity(wall_index, atoms.surface, std::min(tag1, tag2), std::max(tag1, tag2));
}

// Ascending shuffle and identity; or descending identity (order reverse).
bool ContactAssembly::precedes(const OrderKey &a, const OrderKey &b, ContactOrder order)
{
  if (order == ContactOrder::REVERSE) return b.identity < a.identity;
  return std::tie(a.shuffle, a.identity) < std::tie(b.shuffle, b.identity);
}

// Sorted as keys (the contacts themselves are large to move).
void ContactAssembly::add_found_contacts()
{
  sort_keys.clear();
  order_keys.clear();
  for (std::size_t k = 0; k < found.size(); k++) {
    const FoundContact &c = found[k];
    sort_keys.push_back({{order == ContactOrder::SHUFFLE ? c.shuffle : 0, c.identity}, static_cast<int>(k)});
  }
  std::sort(sort_keys.begin(), sort_keys.end(),
            [this](const SortKey &a, const SortKey &b) { return precedes(a.key, b.key, order); });
  for (const SortKey &key : sort_keys) {
    const FoundContact &c = found[key.index];
    const int k = solver.add_contact_arms(c.body1, c.body2, c.r1, c.r2, c.n, c.model,
                                          c.prediction.min_separation, c.prediction.gain,
                                          c.prediction.time_to_contact);
    atom_contacts.push_back(c.atoms);
    order_keys.push_back(key.key);
    solver.set_key(k, c.shuffle);    // from the contact's identity and the step, on any rank
  }
}

double ContactAssembly::memory_usage() const
{
  return (double) found.capacity() * sizeof(FoundContact) + (double) sort_keys.capacity() * sizeof(SortKey) +
      (double) atom_contacts.capacity() * sizeof(AtomContact) + (double) order_keys.capacity() * sizeof(OrderKey) +
      (double) spin_speed.capacity() * sizeof(double);
}
