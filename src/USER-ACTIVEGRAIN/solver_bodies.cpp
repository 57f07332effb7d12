#include "solver_bodies.h"

#include "atom.h"
#include "contact_ranks.h"
#include "domain.h"
#include "fix.h"
#include "force.h"
#include "rigid_body_provider.h"

#include <algorithm>

using namespace LAMMPS_NS;
using ActiveGrain::Mat3;
using ActiveGrain::RigidBodyState;
using ActiveGrain::Vec3;

void SolverBodies::init(const std::vector<RigidBodyProvider *> &body_providers, int freeze_bits,
                        const std::vector<Fix *> &gravity_fixes)
{
  providers = body_providers;
  freeze_groupbit = freeze_bits;
  gravities = gravity_fixes;
}

void SolverBodies::begin_step()
{
  body_index.clear();
  keys.clear();
  elsewhere.clear();
  atom_body.assign(atom->nlocal + atom->nghost, -1);
  gravity_now.clear();
  for (Fix *gravity : gravities) {
    int dim;
    const auto *gvec = static_cast<const double *>(gravity->extract("gvec", dim));
    if (gvec) gravity_now.emplace_back(gravity->groupbit, Vec3(gvec) * force->ftm2v);
  }
}

bool SolverBodies::frozen(int i) const { return atom->mask[i] & freeze_groupbit; }

int SolverBodies::body_of_atom(int i)
{
  if (atom_body[i] >= 0) return atom_body[i];
  const tagint body_id = ranks.body_id(i);
  // Rigid bodies and beads in one key space: odd keys for bodies, even for beads.
  const tagint key = body_id ? 2 * body_id + 1 : 2 * atom->tag[i];
  atom_body[i] = body_index.find_or_insert(static_cast<std::uint64_t>(key), [&] {
    RigidBodyState state;
    tagint id = 0;
    if (body_id) {
      for (RigidBodyProvider *provider : providers)
        if (provider->body_of_atom(i, state, id)) break;
    } else if (frozen(i)) {
      // held in place: moves no more than a wall does
      state = RigidBodyState::wall(Vec3(atom->v[i]));
      state.com = Vec3(atom->x[i]);
    } else {
      state = RigidBodyState::sphere(atom->rmass[i], atom->radius[i], Vec3(atom->x[i]),
                                     Vec3(atom->v[i]), Vec3(atom->omega[i]));
      if (atom->radius[i] == 0.0) state.inv_inertia = Mat3();    // a point mass takes no torque
    }
    const int body = solver.add_body(state);
    keys.resize(body + 1, 0);
    elsewhere.resize(body + 1, 0);
    keys[body] = static_cast<std::uint64_t>(key);
    elsewhere[body] = !ranks.decides_body_of(i);
    return body;
  });
  return atom_body[i];
}

// A bead's arm from the atom itself (its images share one body); a rod's from the image of its
// centre of mass nearest the atom.
Vec3 SolverBodies::lever_arm(int i, int body, const Vec3 &point) const
{
  if (!ranks.body_id(i)) return point - Vec3(atom->x[i]);
  double com[3], com_image[3];
  solver.body(body).com.store(com);
  domain->closest_image(atom->x[i], com, com_image);
  return point - Vec3(com_image);
}

// The velocity of its solver body there, to round-off (a rigid body's atoms move with it; an atom
// held by fix freeze does not turn).
Vec3 SolverBodies::atom_velocity_at(int i, const Vec3 &point) const
{
  if (frozen(i)) return Vec3(atom->v[i]);
  return Vec3(atom->v[i]) + cross(Vec3(atom->omega[i]), point - Vec3(atom->x[i]));
}

double SolverBodies::largest_gravity() const
{
  double largest = 0.0;
  for (const auto &g : gravity_now) largest = std::max(largest, ActiveGrain::norm(g.second));
  return largest;
}

// None for an atom held by fix freeze.
Vec3 SolverBodies::gravity_of_atom(int i) const
{
  Vec3 a;
  if (frozen(i)) return a;
  for (const auto &g : gravity_now)
    if (atom->mask[i] & g.first) a += g.second;
  return a;
}

bool SolverBodies::add_late_impulse(int i, const Vec3 &late, const Vec3 &late_angular) const
{
  for (RigidBodyProvider *provider : providers)
    if (provider->add_late_impulse(i, late, late_angular)) return true;
  return false;
}

double SolverBodies::memory_usage() const
{
  return (double) atom_body.capacity() * sizeof(int) + (double) keys.capacity() * sizeof(std::uint64_t) +
      (double) elsewhere.capacity();
}
