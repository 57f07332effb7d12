// Plugin entry point: registers every ActiveGrain style with the host LAMMPS.
#include "lammpsplugin.h"
#include "version.h"

#include "compute_areafrac_chunk.h"
#include "compute_polar_rod.h"
#include "fix_rigid_rod.h"
#include "fix_store_impulse.h"
#include "fix_wall_impulse.h"
#include "fix_wall_impulse_region.h"
#include "pair_gran_impulse.h"
#include "rod_template.h"

using namespace LAMMPS_NS;

namespace {
template <class Style> Pair *create_pair(LAMMPS *lmp) { return new Style(lmp); }
template <class Style> Fix *create_fix(LAMMPS *lmp, int narg, char **arg)
{
  return new Style(lmp, narg, arg);
}
template <class Style> Compute *create_compute(LAMMPS *lmp, int narg, char **arg)
{
  return new Style(lmp, narg, arg);
}
template <class Style> Command *create_command(LAMMPS *lmp) { return new Style(lmp); }
}    // namespace

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto register_plugin = (lammpsplugin_regfunc) regfunc;
  lammpsplugin_t plugin;
  plugin.version = LAMMPS_VERSION;
  plugin.author = "ActiveGrain developers";
  plugin.handle = handle;

  plugin.style = "pair";
  plugin.name = "gran/impulse";
  plugin.info = "Frictional restitutive impulse contacts";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &create_pair<PairGranImpulse>;
  register_plugin(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "wall/impulse";
  plugin.info = "Vibrating base plate and lid with impulse contacts";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &create_fix<FixWallImpulse>;
  register_plugin(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "wall/impulse/region";
  plugin.info = "Region side walls with impulse contacts";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &create_fix<FixWallImpulseRegion>;
  register_plugin(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "rigid/rod";
  plugin.info = "Tapered polar rods as rigid bodies with true inertia and polar axis";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &create_fix<FixRigidRod>;
  register_plugin(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "STORE/IMPULSE";
  plugin.info = "Internal: pair gran/impulse's per-atom store of the impulses still due";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &create_fix<FixStoreImpulse>;
  register_plugin(&plugin, lmp);

  plugin.style = "command";
  plugin.name = "rod_template";
  plugin.info = "Molecule template of a tapered rod from its physical parameters";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &create_command<RodTemplate>;
  register_plugin(&plugin, lmp);

  plugin.style = "compute";
  plugin.name = "polar/rod";
  plugin.info = "Polar and nematic order of rigid rods, and a per-rod table";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &create_compute<ComputePolarRod>;
  register_plugin(&plugin, lmp);

  plugin.style = "compute";
  plugin.name = "areafrac/chunk";
  plugin.info = "Bead and rod area fractions and rod polarization per chunk";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &create_compute<ComputeAreafracChunk>;
  register_plugin(&plugin, lmp);
}
