#include "contact_ranks.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "ghost_cutoff.h"
#include "lowest_tag_rule.h"
#include "neighbor.h"
#include "rigid_body_provider.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

using namespace LAMMPS_NS;

// Rigid body IDs of all atoms, and which atoms' contacts this rank solves: owned beads, and the
// atoms of bodies this rank decides (LowestTagRule), one copy each: the owned one, else the
// ghost image nearest the body's lowest-tag atom.
void ContactRanks::assign(const std::vector<RigidBodyProvider *> &providers)
{
  rigid_bodies = !providers.empty();
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  tagint *tag = atom->tag;
  assigned_nlocal = nlocal;
  assigned_tag = tag;
  newton_pair = force->newton_pair != 0;
  body_ids.assign(nall, 0);
  solved_here.assign(nall, 0);
  std::fill(solved_here.begin(), solved_here.begin() + nlocal, 1);
  // A bead is decided here if owned here; a ghost image of an owned bead too (without an atom map
  // it counts as decided elsewhere: its island is then exchanged, which is only slower). On one
  // rank every body is.
  const bool mapped = atom->map_style != Atom::MAP_NONE;
  decided_here.assign(nall, 1);
  if (comm->nprocs > 1)
    for (int i = nlocal; i < nall; i++) decided_here[i] = mapped && atom->map(tag[i]) < nlocal;
  if (!rigid_bodies) return;

  LowestTagRule solving;
  ActiveGrain::RigidBodyState state;
  for (int i = 0; i < nall; i++)
    for (RigidBodyProvider *provider : providers)
      if (provider->body_of_atom(i, state, body_ids[i])) {
        solving.add(body_ids[i], tag[i]);
        break;
      }
  for (int i = 0; i < nall; i++) {
    if (!body_ids[i]) continue;
    const int solver_atom = solving.deciding_atom(atom, body_ids[i]);
    decided_here[i] = solver_atom >= 0;
    solved_here[i] = 0;
    if (solver_atom < 0) continue;
    const int owned = atom->map(tag[i]);    // map() prefers the owned copy
    solved_here[i] = (owned < nlocal ? owned : nearest_copy(atom, domain, solver_atom, i)) == i;
  }
}

// span + neighbor cutoff <= ghost cutoff (ghost_cutoff.h: the rule fix rigid/rod quotes too). The span (largest distance between two atoms of a body) is measured where a
// whole body is visible (fix rigid/small's ghost cutoff check ensures one rank sees it).
void ContactRanks::check_ghost_cutoff(const char *style)
{
  if (comm->nprocs == 1) return;
  const int nlocal = atom->nlocal;
  double **x = atom->x;
  std::unordered_map<tagint, std::vector<int>> visible;    // bodies with an owned atom
  for (int i = 0; i < nlocal; i++)
    if (body_ids[i]) visible[body_ids[i]];
  for (int j = 0; j < (int) body_ids.size(); j++) {
    auto found = visible.find(body_ids[j]);
    if (found != visible.end()) found->second.push_back(j);
  }
  double span = 0.0;
  for (auto &body : visible) {
    const std::vector<int> &atoms = body.second;
    for (std::size_t a = 0; a < atoms.size(); a++)
      for (std::size_t b = a + 1; b < atoms.size(); b++) {
        double image[3];
        domain->closest_image(x[atoms[a]], x[atoms[b]], image);
        const double d[3] = {image[0] - x[atoms[a]][0], image[1] - x[atoms[a]][1], image[2] - x[atoms[a]][2]};
        span = std::max(span, std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
      }
  }
  double largest = 0.0;
  MPI_Allreduce(&span, &largest, 1, MPI_DOUBLE, MPI_MAX, world);
  if (ghost_cutoff_needed(lmp, largest) > comm->get_comm_cutoff())
    error->all(FLERR, "{}: rigid body span {:.6g} + neighbor cutoff {:.6g} exceeds the ghost cutoff "
               "{:.6g}: use comm_modify cutoff {:.6g} (valid on any number of ranks)", style, largest,
               neighbor->cutneighmax, comm->get_comm_cutoff(), ghost_cutoff_quoted(lmp, largest));
}

double ContactRanks::memory_usage() const
{
  return (double) body_ids.capacity() * sizeof(tagint) + (double) solved_here.capacity() +
      (double) decided_here.capacity();
}
