/* ----------------------------------------------------------------------
   ActiveGrain: pair_style gran/impulse. Thin adapter from LAMMPS's arrays to the contact core:
   gathers particle and wall contacts, solves them together with the core's ContactSolver, and
   turns each contact impulse J into a force J/dt (and torque) on the contacting atoms. Velocity
   Verlet then applies half of it in this step's final_integrate and half in the next
   initial_integrate, before positions move.
------------------------------------------------------------------------- */

#include "pair_gran_impulse.h"

#include "ag_hash.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "fix_store_atom.h"
#include "force.h"
#include "local_rods.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "rigid_body_provider.h"
#include "update.h"
#include "utils.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using ActiveGrain::ContactMaterial;
using ActiveGrain::Mat3;
using ActiveGrain::RigidBodyState;
using ActiveGrain::Vec3;

static const char *const STYLE = "Pair gran/impulse";
static const char *const PENDING_ID = "AG_GRAN_IMPULSE_DUE";
static constexpr double DEFAULT_BETA = 0.2;
// Below this many sub-steps per half oscillation a compliant impact is too coarse to keep its
// restitution (docs/pair_gran_impulse.rst: the error is about 3/resolution).
static constexpr int MIN_RESOLUTION = 20;
static constexpr bigint FIRST_CAP_WARNING = 10;    // then every tenfold
// The near pairs (NearPairs) are those within this fraction of the neighbor skin.
static constexpr double NEAR_MARGIN = 0.25;
// stays_open() leaves to add_contact() the contacts that close or stay open by less than this
// fraction of their gap and travel: the atoms' and the bodies' velocities differ by round-off.
static constexpr double ROUNDOFF_MARGIN = 1e-6;
// Restart files: the settings' format, stored negative (the first format, without the window,
// began with the resolution).
static constexpr int RESTART_FORMAT = -2;

PairGranImpulse::PairGranImpulse(LAMMPS *lmp) :
    Pair(lmp), beta(DEFAULT_BETA), order(Order::SHUFFLE), restitution(nullptr), friction(nullptr),
    maxrad(nullptr), freeze_groupbit(0), pending(nullptr), force_dt(0.0),
    ghost_pairs(false), ranks(lmp), near(lmp), nmax(0), reverse_columns(NUM_CONTACT_COLUMNS),
    contact_sums(nullptr), fastest(0.0), radius_excess(0.0), fastest_near(0.0), wall_speed(0.0),
    last_virial{}, last_virial_step(-1),
    skin_warned(false), largest_overlap(0.0),
    capped_steps(0), next_cap_warning(FIRST_CAP_WARNING)
{
  single_enable = 0;
  restartinfo = 1;
  finitecutflag = 1;
  // Contact sums of ghost atoms reach their owners with newton off too (Comm sizes its buffers
  // for reverse comm from comm_reverse_off then).
  comm_reverse = comm_reverse_off = NUM_CONTACT_COLUMNS;
  // Contact forces reach owners through this style's own reverse communication, so the f.r
  // virial over owned and ghost atoms would be wrong: the virial is tallied per contact.
  no_virial_fdotr_compute = 1;
  nextra = NUM_OUTPUTS;
  pvector = new double[NUM_OUTPUTS]();
}

PairGranImpulse::~PairGranImpulse()
{
  if (pending) modify->delete_fix(PENDING_ID);
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(restitution);
    memory->destroy(friction);
    delete[] maxrad;
  }
  memory->destroy(contact_sums);
  delete[] pvector;
}

void PairGranImpulse::allocate()
{
  allocated = 1;
  const int n = atom->ntypes + 1;
  memory->create(setflag, n, n, "pair:setflag");
  memory->create(cutsq, n, n, "pair:cutsq");
  memory->create(restitution, n, n, "pair:restitution");
  memory->create(friction, n, n, "pair:friction");
  maxrad = new double[n];
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) setflag[i][j] = 0;
}

/* pair_style gran/impulse [resolution N] [beta B] [order shuffle|tag|reverse] [window W|step];
   every setting not given takes its default */
void PairGranImpulse::settings(int narg, char **arg)
{
  solver_settings = ActiveGrain::ContactSolver::Settings();
  beta = DEFAULT_BETA;
  order = Order::SHUFFLE;
  int iarg = 0;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (key == "coupled" || key == "sweeps" || key == "tolerance")
      error->all(FLERR, "{}: keyword {} is gone: contacts that share a body are solved as one "
                 "compliant impact, whose only setting is resolution", STYLE, key);
    if (iarg + 2 > narg) error->all(FLERR, "{}: missing value after keyword {}", STYLE, key);
    if (key == "window") {
      const std::string value = arg[iarg + 1];
      solver_settings.window =
          value == "step" ? ActiveGrain::ContactSolver::Settings().window : utils::numeric(FLERR, value, false, lmp);
      if (solver_settings.window < 0.0) error->all(FLERR, "{}: window must be >= 0 or step", STYLE);
    } else if (key == "resolution") {
      solver_settings.resolution = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (solver_settings.resolution < MIN_RESOLUTION)
        error->all(FLERR, "{}: resolution must be >= {}", STYLE, MIN_RESOLUTION);
    } else if (key == "beta") {
      beta = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (beta < 0.0 || beta > 1.0) error->all(FLERR, "{}: beta must be in [0, 1]", STYLE);
    } else if (key == "order") {
      const std::string value = arg[iarg + 1];
      if (value == "shuffle") order = Order::SHUFFLE;
      else if (value == "tag") order = Order::TAG;
      else if (value == "reverse") order = Order::REVERSE;
      else error->all(FLERR, "{}: order must be shuffle, tag or reverse (found {})", STYLE, value);
    } else {
      error->all(FLERR, "{}: unknown keyword {}", STYLE, key);
    }
    iarg += 2;
  }
}

/* pair_coeff I J e mu */
void PairGranImpulse::coeff(int narg, char **arg)
{
  if (narg != 4) error->all(FLERR, "{}: pair_coeff needs I J e mu", STYLE);
  if (!allocated) allocate();
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  const double e = utils::numeric(FLERR, arg[2], false, lmp);
  const double mu = utils::numeric(FLERR, arg[3], false, lmp);
  check_material(error, STYLE, e, mu);
  int count = 0;
  for (int i = ilo; i <= ihi; i++)
    for (int j = std::max(jlo, i); j <= jhi; j++) {
      restitution[i][j] = e;
      friction[i][j] = mu;
      setflag[i][j] = 1;
      count++;
    }
  if (count == 0) error->all(FLERR, "{}: incorrect args for pair coefficients", STYLE);
}

void PairGranImpulse::init_style()
{
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "{} requires atom attributes radius, rmass, omega and torque (atom_style sphere)", STYLE);
  if (!atom->tag_enable) error->all(FLERR, "{} requires atom IDs", STYLE);
  if (comm->ghost_velocity == 0)
    error->all(FLERR, "{} requires ghost atoms to store velocity: use comm_modify vel yes", STYLE);
  refuse_unsupported();

  pending = dynamic_cast<FixStoreAtom *>(modify->get_fix_by_id(PENDING_ID));
  if (!pending)
    pending = dynamic_cast<FixStoreAtom *>(
        modify->add_fix(fmt::format("{} all STORE/ATOM {} 0 0 1", PENDING_ID, static_cast<int>(NUM_PENDING))));

  providers.clear();
  walls.clear();
  gravities.clear();
  for (Fix *fix : modify->get_fix_list()) {
    if (auto provider = dynamic_cast<RigidBodyProvider *>(fix)) providers.push_back(provider);
    if (auto wall = dynamic_cast<ImpulseWall *>(fix)) walls.push_back(wall);
    if (utils::strmatch(fix->style, "^gravity")) gravities.push_back(fix);
  }

  // A rigid body's solver rank also solves contacts between two ghost atoms (a ghost atom of
  // its body with a neighbor): that needs the neighbors of ghost atoms, a full list (there is
  // no half list with ghosts for newton on, nor one with per-atom cutoffs: cutoffs come from
  // the largest radii per type). Without rigid bodies, the usual half list.
  ghost_pairs = !providers.empty();
  if (ghost_pairs) {
    if (atom->map_style == Atom::MAP_NONE)
      error->all(FLERR, "{} with rigid bodies requires an atom map (atom_modify map array)", STYLE);
    neighbor->add_request(this, NeighConst::REQ_FULL | NeighConst::REQ_GHOST);
  } else {
    neighbor->add_request(this, NeighConst::REQ_SIZE);
  }

  // Largest radius of each type, present now or to be inserted by fix pour/deposit during the
  // run (as GRANULAR's pair styles do): neighbor cutoffs are radius sums plus the skin. An atom
  // larger than its type's radius here (inserted by other means) is refused in the run.
  const int ntypes = atom->ntypes;
  std::vector<double> local(ntypes + 1, 0.0);
  for (int i = 0; i < atom->nlocal; i++)
    local[atom->type[i]] = std::max(local[atom->type[i]], atom->radius[i]);
  MPI_Allreduce(local.data(), maxrad, ntypes + 1, MPI_DOUBLE, MPI_MAX, world);
  for (int t = 1; t <= ntypes; t++) maxrad[t] = std::max(maxrad[t], inserted_radius(lmp, t));
  const double largest = *std::max_element(maxrad + 1, maxrad + ntypes + 1);
  for (int t = 1; t <= ntypes; t++)
    if (maxrad[t] == 0.0) maxrad[t] = largest;

  // A particle wider than the box would touch its own periodic image or not fit between the
  // box's walls.
  const char axis[3] = {'x', 'y', 'z'};
  for (int d = 0; d < domain->dimension; d++)
    if (2.0 * largest > domain->prd[d])
      error->all(FLERR, "{}: particles of diameter {} are wider than the box ({} length {})", STYLE,
                 2.0 * largest, axis[d], domain->prd[d]);

  auto freezes = modify->get_fix_by_style("^freeze");
  if (freezes.size() > 1) error->all(FLERR, "{}: only one fix freeze is supported", STYLE);
  freeze_groupbit = freezes.empty() ? 0 : freezes.front()->groupbit;
}

// What this style cannot do, refused before a run: other integrators than velocity Verlet, and
// rigid bodies it does not know (it would solve their atoms as free spheres).
void PairGranImpulse::refuse_unsupported()
{
  // Contacts are impulses of one time step applied by velocity Verlet, not forces of a potential.
  if (update->whichflag == 2)
    error->all(FLERR, "{}: minimize is not supported (contacts are impulses of a time step, with "
               "no energy to minimize)", STYLE);
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "{}: run_style respa is not supported (impulses must act within the outer "
               "time step): use run_style verlet", STYLE);
  for (Fix *fix : modify->get_fix_list())
    if (fix->rigid_flag && !dynamic_cast<RigidBodyProvider *>(fix))
      error->all(FLERR, "{}: fix {} (style {}) makes rigid bodies whose atoms this pair style would "
                 "solve as free spheres: use fix rigid/rod (a body's mass, centre of mass and "
                 "inertia enter the contact)", STYLE, fix->id, fix->style);
}

// A time step change (the timestep command between runs, fix dt/reset in a run) while the second
// half of the last step's impulses is still due: atom->f holds it as J/dt_old, which the next
// initial_integrate would apply with the new dt. Rescale it to J/dt_new, so that each impulse
// still acts in full. (Fix rigid/rod then sums the corrected forces into its bodies.)
void PairGranImpulse::reset_dt()
{
  if (!pending || force_dt <= 0.0 || force_dt == update->dt) return;
  double **f = atom->f, **torque = atom->torque, **saved = pending->astore;
  const double step = (double) update->ntimestep;
  for (int i = 0; i < atom->nlocal; i++)
    if (saved[i][PENDING_STEP] == step) {
      // atom->f holds J / force_dt, with J = saved force times its time step
      const double change = saved[i][PENDING_DT] * (1.0 / update->dt - 1.0 / force_dt);
      for (int k = 0; k < 3; k++) {
        f[i][k] += saved[i][PENDING_FORCE + k] * change;
        torque[i][k] += saved[i][PENDING_TORQUE + k] * change;
      }
    }
  force_dt = update->dt;
}

double PairGranImpulse::init_one(int i, int j)
{
  if (setflag[i][j] == 0) {
    // Mixing: geometric means of the like-type coefficients.
    restitution[i][j] = std::sqrt(restitution[i][i] * restitution[j][j]);
    friction[i][j] = std::sqrt(friction[i][i] * friction[j][j]);
  }
  restitution[j][i] = restitution[i][j];
  friction[j][i] = friction[i][j];
  return maxrad[i] + maxrad[j];
}

void PairGranImpulse::grow_buffers()
{
  const int nall = atom->nlocal + atom->nghost;
  if (nall > nmax) {
    nmax = atom->nmax;
    memory->destroy(contact_sums);
    memory->create(contact_sums, nmax, NUM_CONTACT_COLUMNS, "pair:contact_sums");
  }
  if (nall > 0) memset(&contact_sums[0][0], 0, sizeof(double) * NUM_CONTACT_COLUMNS * nall);
  atom_body.assign(nall, -1);
  spin_speed.resize(nall);
  fastest = radius_excess = wall_speed = fastest_near = 0.0;
  for (int i = 0; i < nall; i++) {
    spin_speed[i] = norm(Vec3(atom->omega[i])) * atom->radius[i];
    const double speed = norm(Vec3(atom->v[i])) + spin_speed[i];
    fastest_near = std::max(fastest_near, speed);
    if (i >= atom->nlocal) continue;
    fastest = std::max(fastest, speed);
    radius_excess = std::max(radius_excess, atom->radius[i] - maxrad[atom->type[i]]);
  }
}

// The solver body of atom i: its rigid body if a provider claims it (all atoms of one body
// share one solver body), else a solid sphere. Ghost images of one bead share its body too. The
// body's state is made once, for the first of its atoms met in the step.
int PairGranImpulse::body_of_atom(int i)
{
  if (atom_body[i] >= 0) return atom_body[i];
  const tagint body_id = ranks.body_id(i);
  const tagint key = body_id ? 2 * body_id + 1 : 2 * atom->tag[i];
  atom_body[i] = body_index.find_or_insert(static_cast<std::uint64_t>(key), [&] {
    RigidBodyState state;
    tagint id = 0;
    if (body_id) {
      for (RigidBodyProvider *provider : providers)
        if (provider->body_of_atom(i, state, id)) break;
    } else if (atom->mask[i] & freeze_groupbit) {
      // Held in place by fix freeze: moves no more than a wall does.
      state = RigidBodyState::wall(Vec3(atom->v[i]));
      state.com = Vec3(atom->x[i]);
    } else {
      state = RigidBodyState::sphere(atom->rmass[i], atom->radius[i], Vec3(atom->x[i]),
                                     Vec3(atom->v[i]), Vec3(atom->omega[i]));
      if (atom->radius[i] == 0.0) state.inv_inertia = Mat3();    // a point mass takes no torque
    }
    return solver.add_body(state);
  });
  return atom_body[i];
}

// Lever arm from body's centre of mass to point, taken from atom i's own image of the body (a
// bead's from the atom itself: its images share one body).
Vec3 PairGranImpulse::lever_arm(int i, int body, const Vec3 &point) const
{
  if (!ranks.body_id(i)) return point - Vec3(atom->x[i]);
  double com[3], com_image[3];
  solver.body(body).com.store(com);
  domain->closest_image(atom->x[i], com, com_image);
  return point - Vec3(com_image);
}

// Acceleration of atom i from fix gravity (velocity units per time); none for an atom held by
// fix freeze.
Vec3 PairGranImpulse::gravity_of_atom(int i) const
{
  Vec3 a;
  if (atom->mask[i] & freeze_groupbit) return a;
  for (const auto &g : gravity_now)
    if (atom->mask[i] & g.first) a += g.second;
  return a;
}

// Atom i's velocity at a point of its surface, from the atom's own velocity and spin: the
// velocity of its solver body there, to round-off (a rigid body's atoms move with it; an atom
// held by fix freeze does not turn).
Vec3 PairGranImpulse::atom_velocity_at(int i, const Vec3 &point) const
{
  if (atom->mask[i] & freeze_groupbit) return Vec3(atom->v[i]);
  return Vec3(atom->v[i]) + cross(Vec3(atom->omega[i]), point - Vec3(atom->x[i]));
}

// Whether a contact surely stays open through the step: add_contact's closing test, on the atoms'
// velocities and beyond their round-off from the bodies'. Most near pairs and plate contacts
// part, or close too slowly: they need no solver bodies.
bool PairGranImpulse::stays_open(double gap, const Vec3 &u, const Vec3 &n) const
{
  const double dt = update->dt;
  return gap + dot(u, n) * dt > ROUNDOFF_MARGIN * (std::fabs(gap) + norm(u) * dt);
}

void PairGranImpulse::add_contact(int body1, int body2, const AtomContact &atoms, const Vec3 &n,
                                  double gap, const ContactMaterial &material, const Vec3 &r1,
                                  const Vec3 &r2, const Vec3 &atom_acceleration,
                                  const Vec3 &wall_acceleration)
{
  const double dt = update->dt;
  // Predictive contact: in contact if the gap closes within this step at the current normal
  // velocity, or already overlaps; an overlap must at least open at beta * overlap / dt.
  const Vec3 u = solver.body(body2).velocity_at_arm(r2) - solver.body(body1).velocity_at_arm(r1);
  if (gap + dot(u, n) * dt >= 0.0) return;
  // u is the velocity of the last drift, half a step ago; the contact closes a time t_c after
  // the step's start (0 for an overlap, at most dt). By then the atoms have gained their
  // relative acceleration times dt/2 + t_c, and a wall its own times t_c: the law acts on the
  // relative velocity at that moment, and the atoms move back by J t_c / m (move_late_atoms).
  const double approach_now = -dot(u + atom_acceleration * (0.5 * dt), n);
  const double time_to_contact = gap <= 0.0 ? 0.0 : approach_now * dt > gap ? gap / approach_now : dt;
  const Vec3 gain = atom_acceleration * (0.5 * dt + time_to_contact) - wall_acceleration * time_to_contact;
  const double min_separation = gap < 0.0 ? beta * -gap / dt : 0.0;
  tagint *tag = atom->tag;
  const int wall_index =
      atoms.wall ? static_cast<int>(std::find(walls.begin(), walls.end(), atoms.wall) - walls.begin()) : -1;
  const tagint tag1 = atoms.atom1 >= 0 ? tag[atoms.atom1] : 0, tag2 = tag[atoms.atom2];
  const ContactIdentity identity(wall_index, atoms.surface, std::min(tag1, tag2), std::max(tag1, tag2));
  // The shuffled order: a hash of the step and the contact's identity, the same on any rank.
  const std::uint64_t shuffle = ActiveGrain::hash_words(
      {static_cast<std::uint64_t>(update->ntimestep), static_cast<std::uint64_t>(wall_index + 1),
       static_cast<std::uint64_t>(atoms.surface), static_cast<std::uint64_t>(std::get<2>(identity)),
       static_cast<std::uint64_t>(std::get<3>(identity))});
  AtomContact located = atoms;
  located.approach = std::max(0.0, -dot(u + gain, n));
  located.time_to_contact = time_to_contact;
  located.velocity_before = u;
  located.wall_velocity = solver.body(body1).v + wall_acceleration * time_to_contact;
  found.push_back({shuffle, identity, body1, body2, r1, r2, n, material, min_separation, gain, located});
  largest_overlap = std::max(largest_overlap, -gap);
}

void PairGranImpulse::add_found_contacts()
{
  // Sorted as keys (the contacts themselves are large to move).
  sort_keys.clear();
  for (std::size_t k = 0; k < found.size(); k++) {
    const FoundContact &c = found[k];
    sort_keys.push_back({order == Order::SHUFFLE ? c.shuffle : 0, c.identity, static_cast<int>(k)});
  }
  auto ascending = [](const SortKey &a, const SortKey &b) {
    return std::tie(a.shuffle, a.identity) < std::tie(b.shuffle, b.identity);
  };
  auto descending = [](const SortKey &a, const SortKey &b) { return b.identity < a.identity; };
  if (order == Order::REVERSE) std::sort(sort_keys.begin(), sort_keys.end(), descending);
  else std::sort(sort_keys.begin(), sort_keys.end(), ascending);
  for (const SortKey &key : sort_keys) {
    const FoundContact &c = found[key.index];
    solver.add_contact_arms(c.body1, c.body2, c.r1, c.r2, c.n, c.material, c.min_separation, c.gain,
                            c.atoms.time_to_contact);
    atom_contacts.push_back(c.atoms);
  }
}

void PairGranImpulse::gather_pair_contacts()
{
  double **x = atom->x, **v = atom->v;
  double *radius = atom->radius;
  int *type = atom->type;
  const double margin = NEAR_MARGIN * neighbor->skin;
  near.refresh(list, ranks, margin, fastest_near);
  for (const auto &pair : near.pairs()) {
    const int i = pair.first, j = pair.second;
    if (!ranks.solves_atom(i)) continue;    // a body's copy solved on another rank or image
    Vec3 d = Vec3(x[j]) - Vec3(x[i]);
    const double radsum = radius[i] + radius[j];
    const double rsq = norm2(d);
    if (rsq >= (radsum + margin) * (radsum + margin) || rsq == 0.0) continue;
    const double r = std::sqrt(rsq);
    const double gap = r - radsum;
    if (!gap_may_close(gap, Vec3(v[i]) - Vec3(v[j]), spin_speed[i] + spin_speed[j], update->dt)) continue;
    const Vec3 n = d / r;    // from i to j
    const Vec3 point = Vec3(x[i]) + n * (radius[i] + 0.5 * gap);
    if (stays_open(gap, atom_velocity_at(j, point) - atom_velocity_at(i, point), n)) continue;
    const int bi = body_of_atom(i), bj = body_of_atom(j);
    if (bi == bj) continue;    // constituents of one rigid body, or a bead and its image
    if (solver.body(bi).is_static() && solver.body(bj).is_static()) continue;    // both frozen
    const ContactMaterial material{restitution[type[i]][type[j]], friction[type[i]][type[j]]};
    add_contact(bi, bj, {i, j, nullptr, 0, point, 0.0, 0.0}, n, gap, material, lever_arm(i, bi, point),
                lever_arm(j, bj, point), gravity_of_atom(j) - gravity_of_atom(i));
  }
}

void PairGranImpulse::gather_wall_contacts()
{
  const double reach = neighbor->skin;
  for (ImpulseWall *wall : walls) {
    wall_scratch.clear();
    wall->find_wall_contacts(reach, ranks.solved_atoms(), spin_speed, wall_scratch);
    wall_speed = std::max(wall_speed, wall->wall_speed());
    for (const ImpulseWall::Contact &c : wall_scratch) {
      if (stays_open(c.gap, atom_velocity_at(c.atom, c.point) - c.wall_velocity, c.normal)) continue;
      const int b = body_of_atom(c.atom);
      if (solver.body(b).is_static()) continue;    // a frozen atom
      const int w = solver.add_body(RigidBodyState::wall(c.wall_velocity));
      add_contact(w, b, {-1, c.atom, wall, c.surface, c.point, 0.0, 0.0}, c.normal, c.gap, c.material, Vec3(),
                  lever_arm(c.atom, b, c.point), gravity_of_atom(c.atom), c.wall_acceleration);
    }
  }
}

// Each contact's impulse as a force J / dt (velocity Verlet applies half of it at this step's end
// and half at the next step's start, before the atoms move), and as a late impulse J t_c (the
// solver's sum of impulses times when they acted): a contact that closes a time t_c after the
// step's start has its atoms fly freely until then, so they move J t_c / m less in the next step
// than the force alone would move them.
void PairGranImpulse::distribute_impulses()
{
  const double to_force = 1.0 / update->dt;
  double **x = atom->x;
  auto push = [&](int i, const Vec3 &J, const Vec3 &point, const Vec3 &late) {
    const Vec3 arm = point - Vec3(x[i]);
    double *sums = contact_sums[i];
    (J * to_force).add_to(sums + FORCE);
    cross(arm, J * to_force).add_to(sums + TORQUE);
    if (norm2(late) == 0.0) return;
    late.add_to(sums + LATE);
    cross(arm, late).add_to(sums + LATE_ANGULAR);
  };
  for (int c = 0; c < solver.num_contacts(); c++) {
    const AtomContact &ac = atom_contacts[c];
    const Vec3 &J = solver.impulse(c), &late = solver.contact(c).late;
    push(ac.atom2, J, ac.point, late);
    if (ac.atom1 >= 0) push(ac.atom1, -J, ac.point, -late);
    else ac.wall->add_delivered_impulse(ac.surface, J, ac.approach);
  }
}

// Owned atoms with a late impulse move back by it: a bead by late / mass now, the atoms of a
// rigid body through its provider (the whole body moves and turns, in its final_integrate).
// Atoms held by fix freeze do not move.
void PairGranImpulse::move_late_atoms()
{
  double **x = atom->x;
  for (int i = 0; i < atom->nlocal; i++) {
    const double *sums = contact_sums[i];
    const Vec3 late(sums + LATE);
    if (norm2(late) == 0.0 || (atom->mask[i] & freeze_groupbit)) continue;
    bool in_body = false;
    for (RigidBodyProvider *provider : providers)
      if (provider->add_late_impulse(i, late, Vec3(sums + LATE_ANGULAR))) {
        in_body = true;
        break;
      }
    if (!in_body) (late * (-1.0 / atom->rmass[i])).add_to(x[i]);
  }
}

// Add the contact forces to owned atoms; remember them for a run that continues from here.
void PairGranImpulse::apply_contact_forces(bool store)
{
  double **f = atom->f, **torque = atom->torque, **saved = pending->astore;
  const double step = (double) update->ntimestep, dt = update->dt;
  for (int i = 0; i < atom->nlocal; i++) {
    for (int k = 0; k < 3; k++) {
      f[i][k] += contact_sums[i][FORCE + k];
      torque[i][k] += contact_sums[i][TORQUE + k];
    }
    if (!store) continue;
    for (int k = 0; k < 3; k++) {
      saved[i][PENDING_FORCE + k] = contact_sums[i][FORCE + k];
      saved[i][PENDING_TORQUE + k] = contact_sums[i][TORQUE + k];
    }
    saved[i][PENDING_DT] = dt;
    saved[i][PENDING_STEP] = step;
  }
  force_dt = dt;
}

// The contact forces of the step this run continues from (if any): their half due in its
// initial_integrate, as they were (bit for bit) unless the time step has changed since.
void PairGranImpulse::restore_pending_forces()
{
  double **saved = pending->astore;
  const double step = (double) update->ntimestep, dt = update->dt;
  for (int i = 0; i < atom->nlocal; i++)
    if (saved[i][PENDING_STEP] == step) {
      const double scale = saved[i][PENDING_DT] / dt;    // exactly 1 for the same time step
      for (int k = 0; k < 3; k++) {
        contact_sums[i][FORCE + k] = saved[i][PENDING_FORCE + k] * scale;
        contact_sums[i][TORQUE + k] = saved[i][PENDING_TORQUE + k] * scale;
      }
    }
}

// Solver health into pvector (see Output), and a warning when impacts keep hitting the cap.
void PairGranImpulse::record_solve(const ActiveGrain::ContactSolver::Result &result)
{
  enum Reduced { R_SUBSTEPS, R_SHORTFALL, R_OVERLAP, R_CAPPED, R_FASTEST, R_WALL_SPEED, R_RADIUS, NUM_REDUCED };
  double mine[NUM_REDUCED] = {(double) result.substeps, result.shortfall, largest_overlap,
                              result.converged ? 0.0 : 1.0, fastest, wall_speed, radius_excess};
  double all[NUM_REDUCED];
  if (comm->nprocs > 1) MPI_Allreduce(mine, all, NUM_REDUCED, MPI_DOUBLE, MPI_MAX, world);
  else std::copy(mine, mine + NUM_REDUCED, all);
  if (all[R_CAPPED] > 0.0) capped_steps++;
  if (all[R_RADIUS] > 1e-12 * (*std::max_element(maxrad + 1, maxrad + atom->ntypes + 1)))
    error->all(FLERR, "{}: an atom is larger by {:.3g} than the largest radius of its type known at "
               "the run's setup (atoms then present, fix pour and fix deposit), from which the "
               "neighbor cutoff is made: its contacts would be missed. Insert atoms with fix pour or "
               "fix deposit, or between runs", STYLE, all[R_RADIUS]);
  // LAMMPS rebuilds neighbor lists after an atom moved half the skin: a pair that closes more
  // than the other half in one step can be missing from the list when it is about to touch.
  // Walls are searched up to the skin from each atom: a vibrating plate closes a gap at its own
  // speed plus the particle's, held to the same margin.
  const double pair_closing = 2.0 * all[R_FASTEST] * update->dt;
  const double wall_closing = (all[R_FASTEST] + all[R_WALL_SPEED]) * update->dt;
  if (!skin_warned && std::max(pair_closing, wall_closing) > 0.5 * neighbor->skin) {
    if (comm->me == 0) {
      if (pair_closing >= wall_closing)
        error->warning(FLERR, "{}: two particles can close {:.3g} in one step (2 x largest |v| + "
                       "|omega| r, times dt), more than half the neighbor skin {:.3g}: contacts can be "
                       "missed; use a larger skin or a smaller time step", STYLE, pair_closing, neighbor->skin);
      else
        error->warning(FLERR, "{}: a particle and a wall can close {:.3g} in one step (largest |v| + "
                       "|omega| r plus the wall speed {:.3g}, times dt), more than half the neighbor "
                       "skin {:.3g}: contacts can be missed; use a larger skin or a smaller time step",
                       STYLE, wall_closing, all[R_WALL_SPEED], neighbor->skin);
    }
    skin_warned = true;
  }

  // Maxima go to rank 0 only: compute pair sums pvector over ranks.
  const double here = comm->me == 0 ? 1.0 : 0.0;
  pvector[CONTACTS] = solver.num_contacts();
  pvector[SUBSTEPS] = here * all[R_SUBSTEPS];
  pvector[SHORTFALL] = here * all[R_SHORTFALL];
  pvector[LARGEST_OVERLAP] = here * all[R_OVERLAP];
  pvector[CAPPED_STEPS] = here * (double) capped_steps;

  if (capped_steps == next_cap_warning) {
    if (comm->me == 0)
      error->warning(FLERR, "{}: in {} steps of this run a compliant impact did not end within {} "
                     "sub-steps", STYLE, capped_steps, solver_settings.max_substeps);
    next_cap_warning *= 10;
  }
}

void PairGranImpulse::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  grow_buffers();

  if (update->setupflag) {
    // Contacts are solved in the steps. At setup only the force of the step this run
    // continues from (if any) comes back, so that its initial_integrate completes the impulse.
    restore_pending_forces();
    apply_contact_forces(false);
    restore_virial();
    largest_overlap = 0.0;
    skin_warned = false;
    capped_steps = 0;
    next_cap_warning = FIRST_CAP_WARNING;
    std::fill(pvector, pvector + NUM_OUTPUTS, 0.0);
    if (ghost_pairs) {
      ranks.assign(providers);
      ranks.check_ghost_cutoff(STYLE);
    }
    near.invalidate();    // setup may have sorted the atoms without a new neighbor list build
    return;
  }

  ranks.assign(providers);
  gravity_now.clear();
  for (Fix *gravity : gravities) {
    int dim;
    const auto *gvec = static_cast<const double *>(gravity->extract("gvec", dim));
    if (gvec) gravity_now.emplace_back(gravity->groupbit, Vec3(gvec) * force->ftm2v);
  }
  solver.clear();
  body_index.clear();
  atom_contacts.clear();
  found.clear();
  gather_pair_contacts();
  gather_wall_contacts();
  add_found_contacts();
  solver_settings.step = update->dt;
  record_solve(solver.solve(solver_settings));
  distribute_impulses();
  tally_energy();
  tally_virial();
  reverse_columns = vflag_atom ? NUM_CONTACT_COLUMNS : VIRIAL;
  comm->reverse_comm(this);
  apply_contact_forces(true);
  move_late_atoms();
  if (vflag_atom)
    for (int i = 0; i < atom->nlocal; i++)
      for (int k = 0; k < NUM_VIRIAL; k++) vatom[i][k] += contact_sums[i][VIRIAL + k];
}

// Energies of the step's solve (Output, and per surface to the wall fixes). The bodies' kinetic
// energy (translation and rotation) changes by exactly the sum over contacts of J . (u_before +
// u_after) / 2, u the relative velocity at the contact, plus J . v_wall at wall contacts. The law
// sees u plus the contact's gain (gravity, the plate's acceleration until the contact closes),
// and so does this count: a contact loses J . (u + gain) averaged (an impact alone: (1 - e^2) of
// its energy of approach), a wall works with its velocity when the contact closes. Left out of
// the kinetic energy change: gravity's part of the gain, J . g (dt/2 + t_c), negligible. A
// contact whose overlap correction made it leave at its minimum separation velocity s, faster
// than restitution would (e times its approach a), is credited 1/2 m (s^2 - (e a)^2) to the
// correction (m = 1 / n.K.n, the contact's effective mass: exact for a frictionless contact
// alone); the rest is dissipation. Each contact is counted on the rank that solved it.
void PairGranImpulse::tally_energy()
{
  double dissipated_pair = 0.0, dissipated_wall = 0.0, overlap = 0.0, wall_work = 0.0;
  for (int c = 0; c < solver.num_contacts(); c++) {
    const ActiveGrain::ContactSolver::Contact &contact = solver.contact(c);
    const AtomContact &ac = atom_contacts[c];
    const RigidBodyState &body1 = solver.body(contact.body1), &body2 = solver.body(contact.body2);
    const Vec3 after = body2.velocity_at_arm(contact.r2) - body1.velocity_at_arm(contact.r1);
    const double change = dot(contact.impulse, (ac.velocity_before + after) * 0.5 + contact.gain);
    const double restituted = contact.material.e * ac.approach;
    double push = 0.0;
    if (contact.min_separation > restituted)
      push = 0.5 * (contact.min_separation * contact.min_separation - restituted * restituted) /
          dot(contact.n, contact.K * contact.n);
    const double lost = push - change;
    overlap += push;
    if (ac.atom1 >= 0) {
      dissipated_pair += lost;
    } else {
      const double work = dot(contact.impulse, ac.wall_velocity);
      wall_work += work;
      dissipated_wall += lost;
      ac.wall->add_energy(ac.surface, work, lost, push);
    }
  }
  pvector[DISSIPATED_PAIR] = dissipated_pair;
  pvector[DISSIPATED_WALL] = dissipated_wall;
  pvector[OVERLAP_WORK] = overlap;
  pvector[WALL_WORK] = wall_work;
}

// The virial of the step's contact forces J / dt, as GRANULAR tallies its forces: for a pair,
// the centre-to-centre vector times the force (half of it to each atom's per-atom virial); for a
// wall contact, the arm from the contact point to the atom's centre times the force, to the wall
// fix (fix_modify virial yes; as fix wall/region tallies it). Each contact once, on the rank that
// solved it; per-atom shares of ghost atoms reach their owners with the contact forces.
void PairGranImpulse::tally_virial()
{
  const double to_force = 1.0 / update->dt;
  double **x = atom->x;
  for (int c = 0; c < solver.num_contacts(); c++) {
    const AtomContact &ac = atom_contacts[c];
    const Vec3 force = solver.impulse(c) * to_force;    // on atom2
    if (ac.atom1 < 0) {
      ac.wall->add_virial(Vec3(x[ac.atom2]) - ac.point, force);
      continue;
    }
    const Vec3 d = Vec3(x[ac.atom2]) - Vec3(x[ac.atom1]);
    if (vflag_global) ActiveGrain::add_outer_product(virial, d, force);
    if (vflag_atom)
      for (int i : {ac.atom1, ac.atom2}) ActiveGrain::add_outer_product(contact_sums[i] + VIRIAL, d, force, 0.5);
  }
  if (vflag_global) {
    std::copy(virial, virial + NUM_VIRIAL, last_virial);
    last_virial_step = update->ntimestep;
  }
}

// At a run's setup: the global virial of the step it continues from, if this style solved it.
void PairGranImpulse::restore_virial()
{
  if (vflag_global && last_virial_step == update->ntimestep)
    std::copy(last_virial, last_virial + NUM_VIRIAL, virial);
}

int PairGranImpulse::pack_reverse_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++)
    for (int k = 0; k < reverse_columns; k++) buf[m++] = contact_sums[i][k];
  return m;
}

void PairGranImpulse::unpack_reverse_comm(int n, int *list, double *buf)
{
  int m = 0;
  for (int i = 0; i < n; i++) {
    const int j = list[i];
    for (int k = 0; k < reverse_columns; k++) contact_sums[j][k] += buf[m++];
  }
}

void PairGranImpulse::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      fwrite(&setflag[i][j], sizeof(int), 1, fp);
      if (setflag[i][j]) {
        fwrite(&restitution[i][j], sizeof(double), 1, fp);
        fwrite(&friction[i][j], sizeof(double), 1, fp);
      }
    }
}

void PairGranImpulse::read_restart(FILE *fp)
{
  read_restart_settings(fp);
  allocate();
  const int me = comm->me;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      if (me == 0) utils::sfread(FLERR, &setflag[i][j], sizeof(int), 1, fp, nullptr, error);
      MPI_Bcast(&setflag[i][j], 1, MPI_INT, 0, world);
      if (setflag[i][j]) {
        if (me == 0) {
          utils::sfread(FLERR, &restitution[i][j], sizeof(double), 1, fp, nullptr, error);
          utils::sfread(FLERR, &friction[i][j], sizeof(double), 1, fp, nullptr, error);
        }
        MPI_Bcast(&restitution[i][j], 1, MPI_DOUBLE, 0, world);
        MPI_Bcast(&friction[i][j], 1, MPI_DOUBLE, 0, world);
      }
    }
}

// Settings in restart files: a negative format number first (files of the first format begin with
// the resolution, which is positive), then resolution, beta, order and the window.
void PairGranImpulse::write_restart_settings(FILE *fp)
{
  const int order_code = static_cast<int>(order);
  fwrite(&RESTART_FORMAT, sizeof(int), 1, fp);
  fwrite(&solver_settings.resolution, sizeof(int), 1, fp);
  fwrite(&beta, sizeof(double), 1, fp);
  fwrite(&order_code, sizeof(int), 1, fp);
  fwrite(&solver_settings.window, sizeof(double), 1, fp);
}

void PairGranImpulse::read_restart_settings(FILE *fp)
{
  int order_code = 0;
  solver_settings = ActiveGrain::ContactSolver::Settings();
  if (comm->me == 0) {
    int format = 0;
    utils::sfread(FLERR, &format, sizeof(int), 1, fp, nullptr, error);
    if (format > 0) solver_settings.resolution = format;    // the first format: no window
    else utils::sfread(FLERR, &solver_settings.resolution, sizeof(int), 1, fp, nullptr, error);
    if (format < RESTART_FORMAT) error->one(FLERR, "{}: restart file of a newer format ({})", STYLE, -format);
    utils::sfread(FLERR, &beta, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &order_code, sizeof(int), 1, fp, nullptr, error);
    if (format < 0) utils::sfread(FLERR, &solver_settings.window, sizeof(double), 1, fp, nullptr, error);
  }
  MPI_Bcast(&solver_settings.resolution, 1, MPI_INT, 0, world);
  MPI_Bcast(&beta, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&order_code, 1, MPI_INT, 0, world);
  MPI_Bcast(&solver_settings.window, 1, MPI_DOUBLE, 0, world);
  order = static_cast<Order>(order_code);
}

void *PairGranImpulse::extract(const char *name, int &dim)
{
  dim = 2;
  if (strcmp(name, "e") == 0) return (void *) restitution;
  if (strcmp(name, "mu") == 0) return (void *) friction;
  return nullptr;
}

double PairGranImpulse::memory_usage()
{
  return (double) NUM_CONTACT_COLUMNS * nmax * sizeof(double) + (double) atom_body.capacity() * sizeof(int) +
      ranks.memory_usage() + near.memory_usage() +
      (double) found.capacity() * sizeof(FoundContact) + (double) sort_keys.capacity() * sizeof(SortKey) +
      (double) solver.num_contacts() * sizeof(ActiveGrain::ContactSolver::Contact);
}
