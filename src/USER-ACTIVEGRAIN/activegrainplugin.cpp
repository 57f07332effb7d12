// Plugin entry point: registers every ActiveGrain style with the host LAMMPS.
#include "lammpsplugin.h"
#include "version.h"

#include "compute.h"
#include "fix.h"
#include "pair.h"

#include "compute_areafrac_chunk.h"
#include "compute_polar_rod.h"

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
}    // namespace

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto register_plugin = (lammpsplugin_regfunc) regfunc;
  lammpsplugin_t plugin;
  plugin.version = LAMMPS_VERSION;
  plugin.author = "ActiveGrain developers";
  plugin.handle = handle;

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
