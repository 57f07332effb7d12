#include "local_rods.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "modify.h"
#include "rigid_body_provider.h"

#include <algorithm>
#include <unordered_map>

using namespace LAMMPS_NS;
using ActiveGrain::Vec3;

LocalRods::LocalRods(LAMMPS *lmp, const char *style, bool rods_required) :
    Pointers(lmp), style_(style), rods_required_(rods_required)
{
}

RigidBodyProvider *LocalRods::find_provider()
{
  for (auto *fix : modify->get_fix_list())
    if (auto *provider = dynamic_cast<RigidBodyProvider *>(fix)) return provider;
  if (rods_required_) error->all(FLERR, "Compute {}: no rod fix (fix rigid/rod) is defined", style_);
  return nullptr;
}

void LocalRods::update(int groupbit)
{
  provider_ = find_provider();    // fixes may have been replaced since the last call
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  double **x = atom->x;
  double *radius = atom->radius;
  tagint *tag = atom->tag;
  int *mask = atom->mask;

  rods_.clear();
  rod_of_atom_.assign(nlocal, -1);
  area_share_.assign(nlocal, 0.0);

  // Rods with an owned atom in the group, each with a reference atom to pick periodic images by.
  std::unordered_map<tagint, int> index_of_body;
  std::vector<int> reference;
  ActiveGrain::RigidBodyState body;
  tagint body_id;
  if (!provider_) return;
  for (int i = 0; i < nlocal; ++i) {
    if (!(mask[i] & groupbit) || !provider_->body_of_atom(i, body, body_id)) continue;
    auto found = index_of_body.find(body_id);
    if (found == index_of_body.end()) {
      index_of_body[body_id] = (int) rods_.size();
      rod_of_atom_[i] = (int) rods_.size();
      rods_.push_back({body_id, false, body, Vec3(), Vec3(), 0.0});
      reference.push_back(i);
    } else {
      rod_of_atom_[i] = found->second;
    }
  }

  // All atoms of those rods, owned or ghost, in the image nearest the reference atom.
  std::vector<std::vector<int>> members(rods_.size());
  for (int j = 0; j < nall; ++j) {
    if (!provider_->body_of_atom(j, body, body_id)) continue;
    auto found = index_of_body.find(body_id);
    if (found == index_of_body.end()) continue;
    if (nearest_copy(atom, domain, reference[found->second], j) != j) continue;
    members[found->second].push_back(j);
  }

  for (std::size_t r = 0; r < rods_.size(); ++r) {
    auto &atoms = members[r];
    std::vector<Vec3> centres;
    std::vector<double> radii;
    tagint lowest = tag[atoms.front()];
    for (int j : atoms) {
      centres.emplace_back(x[j]);
      radii.push_back(radius[j]);
      lowest = std::min(lowest, tag[j]);
    }
    const auto chain = ActiveGrain::project_rod_chain(centres, radii);
    // The image used above may be a ghost of an atom this rank owns: atom->map() gives the owned copy.
    auto owned = [&](tagint id) {
      const int i = atom->map(id);
      return (i >= 0 && i < nlocal) ? i : -1;
    };
    rods_[r].axis = chain.axis;
    rods_[r].polar = chain.polar;
    rods_[r].counted_here = owned(lowest) >= 0;
    rods_[r].area = 0.0;
    for (std::size_t k = 0; k < atoms.size(); ++k) {
      rods_[r].area += chain.shares[k];
      const int i = owned(tag[atoms[k]]);
      if (i >= 0) area_share_[i] = chain.shares[k];
    }
  }
}
