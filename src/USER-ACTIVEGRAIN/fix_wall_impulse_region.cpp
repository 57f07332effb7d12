/* ----------------------------------------------------------------------
   ActiveGrain: fix wall/impulse/region. The surface of a region (planes, cylinders, unions and
   intersections of them; moving regions too) as a wall of infinite mass; particles stay on the
   region's inside. Provides contact geometry to pair gran/impulse.
------------------------------------------------------------------------- */

#include "fix_wall_impulse_region.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "region.h"
#include "update.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;
using ActiveGrain::Vec3;

static const char *const STYLE = "Fix wall/impulse/region";

// The region's surface is the fix's one surface (ImpulseWall's outputs).
enum { REGION_SURFACE = 0, NUM_SURFACES };

/* fix ID group wall/impulse/region REGION-ID e E mu MU [type T E MU] */
FixWallImpulseRegion::FixWallImpulseRegion(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), ImpulseWall(this, NUM_SURFACES), region(nullptr), models(lmp, STYLE), motion_reset(false)
{
  if (narg < 4) error->all(FLERR, "{}: expected a region ID after the style name", STYLE);
  region_id = arg[3];
  region = domain->get_region_by_id(region_id);
  if (!region) error->all(FLERR, "{}: region {} does not exist", STYLE, region_id);
  int iarg = 4;
  while (iarg < narg) {
    const int next = models.parse(narg, arg, iarg);
    if (next == iarg) error->all(FLERR, "{}: unknown keyword {}", STYLE, arg[iarg]);
    iarg = next;
  }
  models.check_complete();

  // A moving region's wall velocity is its displacement since the last step: the restart file
  // keeps the last position (as fix wall/gran/region does).
  restart_global = 1;
  vector_flag = 1;
  size_vector = num_surface_outputs();
  global_freq = 1;
  extvector = 0;
  virial_global_flag = 1;    // fix_modify virial yes: the virial of the wall's contact forces
}

int FixWallImpulseRegion::setmask()
{
  return 0;    // the pair style calls this fix; it has no integration hooks
}

void FixWallImpulseRegion::init()
{
  Region *now = domain->get_region_by_id(region_id);
  if (!now) error->all(FLERR, "{}: region {} does not exist", STYLE, region_id);
  check_wall_host(lmp, STYLE);
  // A region defined anew, or one the restart file's does not fit: its motion starts afresh.
  if (now != region || motion_reset) {
    if (comm->me == 0)
      error->warning(FLERR, "{}: region {} {}, its motion starts afresh (wall velocity 0 in the "
                     "first step)", STYLE, region_id, now != region ? "changed between runs" :
                     "does not match the restart file");
    now->reset_vel();
    motion_reset = false;
  }
  region = now;
  region->init();

  // The largest particle of the group, present or to be inserted, must fit inside the region
  // (its bounding box, where the region has one and keeps its shape and orientation).
  if (region->interior && region->bboxflag && !region->rotateflag && !region->varshape) {
    const double diameter = 2.0 * largest_radius(lmp, groupbit);
    const double extent[3] = {region->extent_xhi - region->extent_xlo, region->extent_yhi - region->extent_ylo,
                              region->extent_zhi - region->extent_zlo};
    const char axis[3] = {'x', 'y', 'z'};
    for (int d = 0; d < domain->dimension; d++)
      if (diameter > extent[d])
        error->all(FLERR, "{}: region {} is narrower ({} extent {}) than the largest particle of "
                   "group {} (diameter {})", STYLE, region_id, axis[d], extent[d],
                   group->names[igroup], diameter);
  }
}

void FixWallImpulseRegion::find_wall_contacts(double reach, const std::vector<char> &atoms,
                                              const std::vector<double> &spin_speed,
                                              std::vector<Contact> &contacts)
{
  clear_delivered();
  const bool moving = region->dynamic_check();
  region->prematch();
  if (moving) region->set_velocity();

  double **x = atom->x, **v = atom->v;
  double *radius = atom->radius;
  int *type = atom->type;
  int *mask = atom->mask;
  const int nall = atom->nlocal + atom->nghost;
  for (int i = 0; i < nall; i++) {
    if (!atoms[i] || !(mask[i] & groupbit)) continue;
    // A ghost may be a periodic image outside the box (and an owned atom may have drifted out
    // since the last reneighboring): meet the region in the box, the same for every copy. The
    // normal and gap do not depend on the image; the contact point stays on this image.
    double xbox[3] = {x[i][0], x[i][1], x[i][2]};
    domain->remap(xbox);
    // Atoms whose centre has left the region's inside are not pulled back.
    if (!region->match(xbox[0], xbox[1], xbox[2])) continue;
    const int nc = region->surface(xbox[0], xbox[1], xbox[2], radius[i] + reach);
    for (int ic = 0; ic < nc; ic++) {
      const Region::Contact &rc = region->contact[ic];
      const Vec3 n = Vec3(rc.delx, rc.dely, rc.delz) / rc.r;    // from the wall to the atom
      Vec3 wall_velocity;    // (its acceleration is not known: taken as 0)
      if (moving) region->velocity_contact(&wall_velocity.x, xbox, ic);
      note_wall_speed(norm(wall_velocity));
      const double gap = rc.r - radius[i];
      if (!ActiveGrain::gap_may_close(gap, Vec3(v[i]) - wall_velocity, spin_speed[i], update->dt)) continue;
      contacts.push_back({i, REGION_SURFACE, n, Vec3(x[i]) - n * radius[i], gap, wall_velocity, Vec3(),
                          models.of_type(type[i])});
    }
  }
}

void FixWallImpulseRegion::write_restart(FILE *fp)
{
  if (comm->me) return;
  int size = 0;
  region->length_restart_string(size);
  fwrite(&size, sizeof(int), 1, fp);
  region->write_restart(fp);
}

void FixWallImpulseRegion::restart(char *buf)
{
  int n = 0;
  if (!region->restart(buf, n)) motion_reset = true;
}

// Impulse on atoms from the region's surface in the last force computation (x, y, z): the
// per-surface blocks of ImpulseWall's layout, for its one surface.
double FixWallImpulseRegion::compute_vector(int n)
{
  return surface_output(world, n);
}
