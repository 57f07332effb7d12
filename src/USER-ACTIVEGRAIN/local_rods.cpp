#include "local_rods.h"

#include "atom.h"
#include "comm.h"
#include "compute.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "lowest_tag_rule.h"
#include "modify.h"
#include "rigid_body_provider.h"

#include <unordered_map>

using namespace LAMMPS_NS;
using ActiveGrain::Vec3;

LocalRods::LocalRods(LAMMPS *lmp, const char *error_prefix, bool required) :
    Pointers(lmp), style(error_prefix), rods_required(required)
{
}

RigidBodyProvider *LocalRods::find_provider()
{
  for (auto *fix : modify->get_fix_list())
    if (auto *found = dynamic_cast<RigidBodyProvider *>(fix)) return found;
  if (rods_required) error->all(FLERR, "{}: no rod fix (fix rigid/rod) is defined", style);
  return nullptr;
}

// As LAMMPS's atom styles pack positions for ghosts, across periodic boundaries too.
int LocalRods::pack_positions(int n, int *list, double *buf, int pbc_flag, int *pbc) const
{
  double shift[3] = {0.0, 0.0, 0.0};
  if (pbc_flag) {
    shift[0] = pbc[0] * domain->xprd + (domain->triclinic ? pbc[5] * domain->xy + pbc[4] * domain->xz : 0.0);
    shift[1] = pbc[1] * domain->yprd + (domain->triclinic ? pbc[3] * domain->yz : 0.0);
    shift[2] = pbc[2] * domain->zprd;
  }
  int m = 0;
  for (int k = 0; k < n; ++k)
    for (int d = 0; d < POSITION_COLUMNS; ++d) buf[m++] = atom->x[list[k]][d] + shift[d];
  return m;
}

void LocalRods::unpack_positions(int n, int first, const double *buf) const
{
  int m = 0;
  for (int i = first; i < first + n; ++i)
    for (int d = 0; d < POSITION_COLUMNS; ++d) atom->x[i][d] = buf[m++];
}

void LocalRods::update(Compute *caller, int groupbit)
{
  comm->forward_comm(caller);
  provider = find_provider();    // fixes may have been replaced since the last call
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  double **x = atom->x;
  double *radius = atom->radius;
  tagint *tag = atom->tag;
  int *mask = atom->mask;

  rod_list.clear();
  rod_index.assign(nlocal, -1);
  area_shares.assign(nlocal, 0.0);

  // Rods with an owned atom in the group, each with a reference atom to pick periodic images by.
  std::unordered_map<tagint, int> index_of_body;
  std::vector<int> reference;
  ActiveGrain::RigidBodyState body;
  tagint body_id;
  if (!provider) return;
  for (int i = 0; i < nlocal; ++i) {
    if (!(mask[i] & groupbit) || !provider->body_of_atom(i, body, body_id)) continue;
    auto found = index_of_body.find(body_id);
    if (found == index_of_body.end()) {
      index_of_body[body_id] = (int) rod_list.size();
      rod_index[i] = (int) rod_list.size();
      rod_list.push_back({body_id, false, body, Vec3(), Vec3(), 0.0});
      reference.push_back(i);
    } else {
      rod_index[i] = found->second;
    }
  }

  // All atoms of those rods, owned or ghost, in the image nearest the reference atom.
  std::vector<std::vector<int>> members(rod_list.size());
  for (int j = 0; j < nall; ++j) {
    if (!provider->body_of_atom(j, body, body_id)) continue;
    auto found = index_of_body.find(body_id);
    if (found == index_of_body.end()) continue;
    if (nearest_copy(atom, domain, reference[found->second], j) != j) continue;
    members[found->second].push_back(j);
  }

  LowestTagRule counting;
  for (std::size_t r = 0; r < rod_list.size(); ++r)
    for (int j : members[r]) counting.add(rod_list[r].id, tag[j]);
  // The image used above may be a ghost of an atom this rank owns: atom->map() gives the owned copy.
  auto owned = [&](tagint id) {
    const int i = atom->map(id);
    return (i >= 0 && i < nlocal) ? i : -1;
  };
  for (std::size_t r = 0; r < rod_list.size(); ++r) {
    auto &atoms = members[r];
    std::vector<Vec3> centres;
    std::vector<double> radii;
    for (int j : atoms) {
      centres.emplace_back(x[j]);
      radii.push_back(radius[j]);
    }
    const auto chain = ActiveGrain::project_rod_chain(centres, radii);
    rod_list[r].axis = chain.axis;
    rod_list[r].polar = chain.polar;
    rod_list[r].counted_here = counting.deciding_atom(atom, rod_list[r].id) >= 0;
    rod_list[r].area = 0.0;
    for (std::size_t k = 0; k < atoms.size(); ++k) {
      rod_list[r].area += chain.shares[k];
      const int i = owned(tag[atoms[k]]);
      if (i >= 0) area_shares[i] = chain.shares[k];
    }
  }
}
