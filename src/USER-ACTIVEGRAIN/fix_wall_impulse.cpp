/* ----------------------------------------------------------------------
   ActiveGrain: fix wall/impulse. The base plate z_base(t) = z0 + A sin(2 pi f t + phase) and
   a lid at z_base + gap (moving with it), at z0 + gap (fixed), or none. Provides contact
   geometry to pair gran/impulse, which resolves the contacts with the same impulse law as
   particle contacts.
------------------------------------------------------------------------- */

#include "fix_wall_impulse.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "modify.h"
#include "update.h"
#include "utils.h"

#include "ag_hash.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;
using ActiveGrain::PI;
using ActiveGrain::Vec3;

static const char *const STYLE = "Fix wall/impulse";

// A vibration needs at least this many time steps per period.
static constexpr double MIN_STEPS_PER_PERIOD = 20.0;
// Warn when the plates move more than this fraction of the gap in one step.
static constexpr double MAX_STEP_TRAVEL = 0.01;
// Roughness is a small tilt of the contact normal (the slope is evaluated under the sphere's
// centre, not at its true foot point): keep it small.
static constexpr double MAX_ROUGH_SLOPE = 0.3;
// A contact approaching faster than this fraction of the plates' peak speed A 2 pi f is an impact
// (output IMPACTS).
static constexpr double IMPACT_FRACTION = 0.01;
// The restart record: the clock's origin (time and step), its time step, and the file's step.
enum ClockRecord { CLOCK_TIME = 0, CLOCK_STEP, CLOCK_DT, FILE_STEP, NCLOCK };

/* fix ID group wall/impulse zlo Z0 e E mu MU [gap G] [lid moving|fixed|none]
       [vibrate A F PHASE] [type T E MU] [rough SLOPE LENGTH SEED] */
FixWallImpulse::FixWallImpulse(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), ImpulseWall(this, NUM_SURFACES), z0(0.0), gap(0.0), amplitude(0.0), frequency(0.0), phase(0.0),
    lid(Lid::NONE), own_clock(false), clock_time(0.0), clock_dt(0.0), clock_step(0), rough_slope(0.0),
    rough_length(0.0), rough_seed(0), models(lmp, STYLE)
{
  if (narg < 5 || strcmp(arg[3], "zlo") != 0)
    error->all(FLERR, "{}: expected 'zlo Z0' after the style name", STYLE);
  z0 = utils::numeric(FLERR, arg[4], false, lmp);
  bool lid_given = false;
  Lid lid_motion = Lid::MOVING;
  int iarg = 5;
  while (iarg < narg) {
    const int next = models.parse(narg, arg, iarg);
    if (next != iarg) { iarg = next; continue; }
    const std::string key = arg[iarg];
    if (key == "gap") {
      if (iarg + 2 > narg) error->all(FLERR, "{}: missing value after gap", STYLE);
      gap = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (gap <= 0.0) error->all(FLERR, "{}: gap must be > 0", STYLE);
      lid_given = true;
      iarg += 2;
    } else if (key == "lid") {
      if (iarg + 2 > narg) error->all(FLERR, "{}: missing value after lid", STYLE);
      const std::string mode = arg[iarg + 1];
      if (mode == "moving") lid_motion = Lid::MOVING;
      else if (mode == "fixed") lid_motion = Lid::FIXED;
      else if (mode == "none") lid_motion = Lid::NONE;
      else error->all(FLERR, "{}: lid must be moving, fixed or none, not {}", STYLE, mode);
      iarg += 2;
    } else if (key == "vibrate") {
      if (iarg + 4 > narg) error->all(FLERR, "{}: vibrate needs amplitude, frequency, phase", STYLE);
      amplitude = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      frequency = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
      phase = utils::numeric(FLERR, arg[iarg + 3], false, lmp);
      if (amplitude < 0.0 || frequency < 0.0)
        error->all(FLERR, "{}: vibration amplitude and frequency must be >= 0", STYLE);
      iarg += 4;
    } else if (key == "rough") {
      if (iarg + 4 > narg) error->all(FLERR, "{}: rough needs rms slope, correlation length, seed", STYLE);
      rough_slope = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      rough_length = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
      rough_seed = utils::inumeric(FLERR, arg[iarg + 3], false, lmp);
      if (rough_slope < 0.0 || rough_slope > MAX_ROUGH_SLOPE)
        error->all(FLERR, "{}: rough rms slope {} must be in [0, {}]", STYLE, rough_slope, MAX_ROUGH_SLOPE);
      if (rough_length <= 0.0) error->all(FLERR, "{}: rough correlation length must be > 0", STYLE);
      if (rough_seed <= 0) error->all(FLERR, "{}: rough seed must be a positive integer", STYLE);
      iarg += 4;
    } else {
      error->all(FLERR, "{}: unknown keyword {}", STYLE, key);
    }
  }
  models.check_complete();
  if (lid_motion == Lid::FIXED && !lid_given)
    error->all(FLERR, "{}: lid fixed needs a gap", STYLE);
  lid = lid_given ? lid_motion : Lid::NONE;
  if (domain->zperiodic)
    error->all(FLERR, "{}: cannot be used with a periodic z dimension (use boundary ... f or m)", STYLE);

  scalar_flag = 1;
  vector_flag = 1;
  size_vector = NUM_STATE + num_surface_outputs();
  global_freq = 1;
  extscalar = 0;
  extvector = 0;
  // fix_modify virial yes: the virial of the plates' contact forces (global, as pair
  // gran/impulse tallies them; off by default as for fix wall/gran).
  virial_global_flag = 1;
  restart_global = 1;
}

int FixWallImpulse::setmask()
{
  return 0;    // the pair style calls this fix; it has no integration hooks
}

void FixWallImpulse::init()
{
  check_wall_host(lmp, STYLE);
  // Periodic directions get a lattice commensurate with the box (made here: the box may change
  // between runs); the lid's surface is another frozen field of the same statistics.
  const double period_x = domain->xperiodic ? domain->xprd : 0.0;
  const double period_y = domain->yperiodic ? domain->yprd : 0.0;
  for (int s : {BASE, LID})
    surface[s] = ActiveGrain::RoughSurface(rough_slope, rough_length,
                                           ActiveGrain::hash_words({(std::uint64_t) rough_seed, (std::uint64_t) s}),
                                           period_x, period_y);
  // The largest particle of the group, present or to be inserted, must fit between the plates.
  if (lid != Lid::NONE) {
    const double diameter = 2.0 * largest_radius(lmp, groupbit);
    if (diameter > gap)
      error->all(FLERR, "{}: gap {} is narrower than the largest particle of group {} (diameter {})",
                 STYLE, gap, group->names[igroup], diameter);
  }
  check_time_step(true);
  check_deck();
}

// Two fixes wall/impulse on the same atoms would each add their plates' impulses (plates counted
// twice). Vibrated flat plates under beads: the deterministic model (a bed that soon stops moving
// sideways), told once, since rough plates are what the calibration used.
void FixWallImpulse::check_deck()
{
  bool after = false;
  for (Fix *fix : modify->get_fix_list()) {
    if (fix == this) {
      after = true;
      continue;
    }
    if (!after || strcmp(fix->style, "wall/impulse") != 0) continue;
    int shared = 0, any = 0;
    for (int i = 0; i < atom->nlocal && !shared; i++)
      if ((atom->mask[i] & groupbit) && (atom->mask[i] & fix->groupbit)) shared = 1;
    MPI_Allreduce(&shared, &any, 1, MPI_INT, MPI_MAX, world);
    if (any)
      error->all(FLERR, "{}: fixes {} and {} act on the same atoms: their plates would be counted twice; one fix "
                 "wall/impulse holds both plates (keywords gap and lid), so unfix one of them", STYLE, id, fix->id);
  }
  if (warned_flat || rough_slope > 0.0 || !(amplitude > 0.0 && frequency > 0.0)) return;
  int beads = 0, any = 0;
  for (int i = 0; i < atom->nlocal && !beads; i++)
    if ((atom->mask[i] & groupbit) && !(atom->molecule_flag && atom->molecule[i] > 0)) beads = 1;
  MPI_Allreduce(&beads, &any, 1, MPI_INT, MPI_MAX, world);
  if (any && comm->me == 0)
    error->warning(FLERR, "{}: vibrated flat plates (no keyword rough) with beads: the deterministic model, in "
                   "which a bead bed soon stops moving sideways; for the calibrated plates add rough SLOPE LENGTH "
                   "SEED (docs/calibration.rst)", STYLE);
  warned_flat = any != 0;
}

// The drive must be resolved in time: checked before each run (with a warning when the plates
// move far in one step) and whenever the time step changes (timestep, fix dt/reset).
void FixWallImpulse::check_time_step(bool warn)
{
  const double dt = update->dt;
  if (amplitude > 0.0 && frequency > 0.0) {
    const double steps_per_period = 1.0 / (frequency * dt);
    if (steps_per_period < MIN_STEPS_PER_PERIOD)
      error->all(FLERR, "{}: time step {} too large for the vibration: {:.3g} steps per period (need >= {})",
                 STYLE, dt, steps_per_period, MIN_STEPS_PER_PERIOD);
    const double travel = 2.0 * PI * frequency * amplitude * dt;
    if (warn && lid != Lid::NONE && travel > MAX_STEP_TRAVEL * gap && comm->me == 0)
      error->warning(FLERR, "{}: plates move {:.3g} per step, more than {} of the gap", STYLE, travel,
                     MAX_STEP_TRAVEL);
  }
}

void FixWallImpulse::reset_dt()
{
  if (own_clock) {
    clock_time += (update->ntimestep - clock_step) * clock_dt;
    clock_step = update->ntimestep;
    clock_dt = update->dt;
  }
  check_time_step(false);
}

// Simulation time of the current positions; continues exactly across restarts.
double FixWallImpulse::time_now() const
{
  if (own_clock) return clock_time + (update->ntimestep - clock_step) * update->dt;
  return update->atime + (update->ntimestep - update->atimestep) * update->dt;
}

void FixWallImpulse::write_restart(FILE *fp)
{
  if (comm->me != 0) return;
  double clock[NCLOCK];
  clock[CLOCK_TIME] = own_clock ? clock_time : update->atime;
  clock[CLOCK_STEP] = (double) (own_clock ? clock_step : update->atimestep);
  clock[CLOCK_DT] = update->dt;
  clock[FILE_STEP] = (double) update->ntimestep;
  const int size = sizeof(clock);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(clock, sizeof(double), NCLOCK, fp);
}

void FixWallImpulse::restart(char *buf)
{
  const auto *clock = reinterpret_cast<const double *>(buf);
  clock_time = clock[CLOCK_TIME];
  clock_step = static_cast<bigint>(clock[CLOCK_STEP]);
  clock_dt = clock[CLOCK_DT];
  // A time step set after read_restart, before this fix was defined, counts from the file's step.
  if (update->dt != clock_dt) {
    const auto file_step = static_cast<bigint>(clock[FILE_STEP]);
    clock_time += (file_step - clock_step) * clock_dt;
    clock_step = file_step;
    clock_dt = update->dt;
  }
  own_clock = true;
}

double FixWallImpulse::base_z(double t) const
{
  return z0 + amplitude * std::sin(2.0 * PI * frequency * t + phase);
}

double FixWallImpulse::base_vz(double t) const
{
  return 2.0 * PI * frequency * amplitude * std::cos(2.0 * PI * frequency * t + phase);
}

double FixWallImpulse::base_az(double t) const
{
  return -peak_acceleration() * std::sin(2.0 * PI * frequency * t + phase);
}

double FixWallImpulse::peak_acceleration() const
{
  const double omega = 2.0 * PI * frequency;
  return omega * omega * amplitude;
}

void FixWallImpulse::find_wall_contacts(double reach, const std::vector<char> &atoms,
                                        const std::vector<double> &spin_speed, std::vector<Contact> &contacts)
{
  const double t = time_now();
  const double zb = base_z(t), vb = base_vz(t), ab = base_az(t);
  const double zlid = lid == Lid::MOVING ? zb + gap : z0 + gap;
  const double vlid = lid == Lid::MOVING ? vb : 0.0;
  const double alid = lid == Lid::MOVING ? ab : 0.0;
  // Impacts for the lock-in tally: contacts approaching faster than a small fraction of the
  // plate's peak speed (resting contacts approach at about g dt), at the drive's phase.
  const double peak_speed = 2.0 * PI * frequency * amplitude;
  clear_delivered(std::fmod(2.0 * PI * frequency * t + phase, 2.0 * PI),
                  peak_speed > 0.0 ? IMPACT_FRACTION * peak_speed : NO_IMPACTS);
  note_wall_speed(std::fabs(vb));

  double **x = atom->x, **v = atom->v;
  double *radius = atom->radius;
  int *type = atom->type;
  int *mask = atom->mask;
  const double dt = update->dt;
  const int nall = atom->nlocal + atom->nghost;
  for (int i = 0; i < nall; i++) {
    if (!atoms[i] || !(mask[i] & groupbit)) continue;
    const Vec3 centre(x[i]);
    const double r = radius[i];
    auto may_close = [&](double gap, double wall_vz) {
      return gap < reach && ActiveGrain::gap_may_close(gap, Vec3(v[i]) - Vec3(0, 0, wall_vz), spin_speed[i], dt);
    };
    // Most atoms are out of reach of a plate within a step: the surface's bounds (its largest
    // height, its steepest tilt) tell so from the centre's height above the mean plane alone,
    // and evaluating the surface is the costly part.
    auto surely_out_of_reach = [&](const ActiveGrain::RoughSurface &s, double height, double wall_vz) {
      return height > s.max_height() && !may_close((height - s.max_height()) * s.min_normal_z() - r, wall_vz);
    };
    // The plate's tangent plane under the sphere: through the surface point above (below) the
    // centre, normal tilted by the local slope. The gap is the centre's distance from that plane
    // less the radius.
    if (!surely_out_of_reach(surface[BASE], centre.z - zb, vb)) {
      const ActiveGrain::SurfacePoint below = surface[BASE].at(centre.x, centre.y);
      const Vec3 n_base = below.normal_up();
      const double base_gap = (centre.z - zb - below.height) * n_base.z - r;
      if (may_close(base_gap, vb))
        contacts.push_back({i, BASE, n_base, centre - n_base * r, base_gap, Vec3(0, 0, vb), Vec3(0, 0, ab),
                            models.of_type(type[i])});
    }
    if (lid == Lid::NONE || surely_out_of_reach(surface[LID], zlid - centre.z, vlid)) continue;
    const ActiveGrain::SurfacePoint above = surface[LID].at(centre.x, centre.y);
    const Vec3 n_lid = -above.normal_up();
    const double lid_gap = (zlid + above.height - centre.z) * -n_lid.z - r;
    if (may_close(lid_gap, vlid))
      contacts.push_back({i, LID, n_lid, centre - n_lid * r, lid_gap, Vec3(0, 0, vlid), Vec3(0, 0, alid),
                          models.of_type(type[i])});
  }
}

// Base plate position at the current step.
double FixWallImpulse::compute_scalar()
{
  return base_z(time_now());
}

// The fix's state (State), then the impulse on atoms from the base and from the lid in the
// last force computation (ImpulseWall::SurfaceQuantity).
double FixWallImpulse::compute_vector(int n)
{
  const double t = time_now();
  switch (n) {
    case BASE_Z: return base_z(t);
    case LID_Z: return lid == Lid::MOVING ? base_z(t) + gap : lid == Lid::FIXED ? z0 + gap : base_z(t);
    case PLATE_VZ: return base_vz(t);
    default: return surface_output(world, n - NUM_STATE);
  }
}
