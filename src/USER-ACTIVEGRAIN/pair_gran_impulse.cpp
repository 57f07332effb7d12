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

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using ActiveGrain::ContactMaterial;
using ActiveGrain::Mat3;
using ActiveGrain::RigidBodyState;
using ActiveGrain::Vec3;

static const char *const STYLE = "Pair gran/impulse";
static const char *const PENDING_ID = "AG_GRAN_IMPULSE_PENDING";
// Sweep defaults per law of coupled contacts. Stronge's law (the default for now) is swept a
// fixed few times: more sweeps do not converge it, they only move its order-dependent result
// (docs/pair_gran_impulse.rst). The projection converges: its sweeps stop at the tolerance, and
// the cap only guards against a solve that does not; a rod landing flat on a plate (nine
// redundant contacts) can need thousands of sweeps to 1e-8.
static constexpr int STRONGE_SWEEPS = 8;
static constexpr double STRONGE_TOLERANCE = 1.0e-4;
static constexpr int PROJECTION_SWEEPS = 10000;
static constexpr double PROJECTION_TOLERANCE = 1.0e-8;
static constexpr double DEFAULT_BETA = 0.2;
static constexpr bigint FIRST_CAP_WARNING = 10;    // then every tenfold

PairGranImpulse::PairGranImpulse(LAMMPS *lmp) :
    Pair(lmp), max_sweeps(STRONGE_SWEEPS), tolerance(STRONGE_TOLERANCE), beta(DEFAULT_BETA),
    order(Order::SHUFFLE), coupled_law(ActiveGrain::ContactSolver::CoupledLaw::STRONGE), restitution(nullptr), friction(nullptr), maxrad(nullptr), pending(nullptr),
    ghost_pairs(false), nmax(0), fcontact(nullptr), tcontact(nullptr), largest_overlap(0.0),
    capped_steps(0), next_cap_warning(FIRST_CAP_WARNING)
{
  single_enable = 0;
  restartinfo = 1;
  finitecutflag = 1;
  comm_reverse = 6;
  // Contact forces reach owners through this style's own reverse communication, so the f.r
  // virial over owned and ghost atoms would be wrong: no virial from this style.
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
  memory->destroy(fcontact);
  memory->destroy(tcontact);
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

/* pair_style gran/impulse [coupled stronge|projection] [sweeps N] [tolerance T] [beta B]
                           [order shuffle|tag|reverse]; every setting not given takes its default */
void PairGranImpulse::settings(int narg, char **arg)
{
  using CoupledLaw = ActiveGrain::ContactSolver::CoupledLaw;
  coupled_law = CoupledLaw::STRONGE;
  max_sweeps = -1;
  tolerance = -1.0;
  beta = DEFAULT_BETA;
  order = Order::SHUFFLE;
  int iarg = 0;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (iarg + 2 > narg) error->all(FLERR, "{}: missing value after keyword {}", STYLE, key);
    if (key == "sweeps") {
      max_sweeps = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (max_sweeps < 1) error->all(FLERR, "{}: sweeps must be >= 1", STYLE);
    } else if (key == "tolerance") {
      tolerance = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (tolerance < 0.0) error->all(FLERR, "{}: tolerance must be >= 0", STYLE);
    } else if (key == "beta") {
      beta = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (beta < 0.0 || beta > 1.0) error->all(FLERR, "{}: beta must be in [0, 1]", STYLE);
    } else if (key == "order") {
      const std::string value = arg[iarg + 1];
      if (value == "shuffle") order = Order::SHUFFLE;
      else if (value == "tag") order = Order::TAG;
      else if (value == "reverse") order = Order::REVERSE;
      else error->all(FLERR, "{}: order must be shuffle, tag or reverse (found {})", STYLE, value);
    } else if (key == "coupled") {
      const std::string value = arg[iarg + 1];
      if (value == "stronge") coupled_law = CoupledLaw::STRONGE;
      else if (value == "projection") coupled_law = CoupledLaw::PROJECTION;
      else error->all(FLERR, "{}: coupled must be stronge or projection (found {})", STYLE, value);
    } else {
      error->all(FLERR, "{}: unknown keyword {}", STYLE, key);
    }
    iarg += 2;
  }
  const bool stronge = coupled_law == CoupledLaw::STRONGE;
  if (max_sweeps < 0) max_sweeps = stronge ? STRONGE_SWEEPS : PROJECTION_SWEEPS;
  if (tolerance < 0.0) tolerance = stronge ? STRONGE_TOLERANCE : PROJECTION_TOLERANCE;
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

  pending = dynamic_cast<FixStoreAtom *>(modify->get_fix_by_id(PENDING_ID));
  if (!pending)
    pending = dynamic_cast<FixStoreAtom *>(
        modify->add_fix(fmt::format("{} all STORE/ATOM {} 0 0 1", PENDING_ID, static_cast<int>(NUM_PENDING))));

  providers.clear();
  walls.clear();
  for (Fix *fix : modify->get_fix_list()) {
    if (auto provider = dynamic_cast<RigidBodyProvider *>(fix)) providers.push_back(provider);
    if (auto wall = dynamic_cast<ImpulseWall *>(fix)) walls.push_back(wall);
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

  // Largest radius of each type present now: neighbor cutoffs are radius sums plus the skin.
  const int ntypes = atom->ntypes;
  std::vector<double> local(ntypes + 1, 0.0);
  for (int i = 0; i < atom->nlocal; i++)
    local[atom->type[i]] = std::max(local[atom->type[i]], atom->radius[i]);
  MPI_Allreduce(local.data(), maxrad, ntypes + 1, MPI_DOUBLE, MPI_MAX, world);
  const double largest = *std::max_element(maxrad + 1, maxrad + ntypes + 1);
  for (int t = 1; t <= ntypes; t++)
    if (maxrad[t] == 0.0) maxrad[t] = largest;
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
    memory->destroy(fcontact);
    memory->destroy(tcontact);
    memory->create(fcontact, nmax, 3, "pair:fcontact");
    memory->create(tcontact, nmax, 3, "pair:tcontact");
  }
  if (nall > 0) {
    memset(&fcontact[0][0], 0, sizeof(double) * 3 * nall);
    memset(&tcontact[0][0], 0, sizeof(double) * 3 * nall);
  }
  atom_body.assign(nall, -1);
}

// Rigid body IDs of all atoms, and which atoms' contacts this rank solves: owned beads, and the
// atoms of bodies this rank decides (LowestTagRule), one copy each: the owned one, else the
// ghost image nearest the body's lowest-tag atom.
void PairGranImpulse::assign_contact_ranks()
{
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  tagint *tag = atom->tag;
  rigid_body_id.assign(nall, 0);
  solved_here.assign(nall, 0);
  std::fill(solved_here.begin(), solved_here.begin() + nlocal, 1);
  if (!ghost_pairs) return;

  LowestTagRule solving;
  RigidBodyState state;
  for (int i = 0; i < nall; i++)
    for (RigidBodyProvider *provider : providers)
      if (provider->body_of_atom(i, state, rigid_body_id[i])) {
        solving.add(rigid_body_id[i], tag[i]);
        break;
      }
  for (int i = 0; i < nall; i++) {
    if (!rigid_body_id[i]) continue;
    const int solver_atom = solving.deciding_atom(atom, rigid_body_id[i]);
    solved_here[i] = 0;
    if (solver_atom < 0) continue;
    const int owned = atom->map(tag[i]);    // map() prefers the owned copy
    solved_here[i] = (owned < nlocal ? owned : nearest_copy(atom, domain, solver_atom, i)) == i;
  }
}

// Whether this rank solves the contact of i with neighbor j, so that each physical contact is
// solved on one rank, once: a contact with a rigid body's atom from that atom if its body has
// the lower ID of the two and i is the copy solved here; a pair of beads from the owned bead i
// (with a full list or a ghost j listed on both ranks, only from the lower tag).
bool PairGranImpulse::solves_pair(int i, int j) const
{
  const tagint body_i = rigid_body_id[i], body_j = rigid_body_id[j];
  if (body_i || body_j) return body_i && (!body_j || body_i < body_j) && solved_here[i];
  const int nlocal = atom->nlocal;
  if (i >= nlocal) return false;
  if (ghost_pairs || (!force->newton_pair && j >= nlocal)) return atom->tag[i] < atom->tag[j];
  return true;
}

// On several ranks, the solver rank of a body sees all its atoms and their contacts only if
// its ghost shell reaches a neighbor cutoff beyond the body's far end: span + neighbor cutoff
// <= ghost cutoff. The span (largest distance between two atoms of a body) is measured where a
// whole body is visible (fix rigid/small's ghost cutoff check ensures one rank sees it).
void PairGranImpulse::check_ghost_cutoff()
{
  if (comm->nprocs == 1) return;
  const int nlocal = atom->nlocal;
  double **x = atom->x;
  std::unordered_map<tagint, std::vector<int>> visible;    // bodies with an owned atom
  for (int i = 0; i < nlocal; i++)
    if (rigid_body_id[i]) visible[rigid_body_id[i]];
  for (int j = 0; j < (int) rigid_body_id.size(); j++) {
    auto found = visible.find(rigid_body_id[j]);
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
  const double needed = largest + neighbor->cutneighmax;
  if (needed > comm->get_comm_cutoff())
    error->all(FLERR, "{}: rigid body span {:.6g} + neighbor cutoff {:.6g} exceeds the ghost cutoff "
               "{:.6g}: use comm_modify cutoff {:.6g}", STYLE, largest, neighbor->cutneighmax,
               comm->get_comm_cutoff(), needed);
}

// The solver body of atom i: its rigid body if a provider claims it (all atoms of one body
// share one solver body), else a solid sphere. Ghost images of one bead share its body too.
int PairGranImpulse::body_of_atom(int i)
{
  if (atom_body[i] >= 0) return atom_body[i];
  RigidBodyState state;
  tagint id = 0;
  tagint key = -1;
  for (RigidBodyProvider *provider : providers)
    if (provider->body_of_atom(i, state, id)) {
      key = 2 * id + 1;
      break;
    }
  if (key < 0) {
    key = 2 * atom->tag[i];
    state = RigidBodyState::sphere(atom->rmass[i], atom->radius[i], Vec3(atom->x[i]),
                                   Vec3(atom->v[i]), Vec3(atom->omega[i]));
    if (atom->radius[i] == 0.0) state.inv_inertia = Mat3();    // a point mass takes no torque
  }
  auto found = body_index.find(key);
  const int body = found != body_index.end() ? found->second : solver.add_body(state);
  if (found == body_index.end()) body_index.emplace(key, body);
  atom_body[i] = body;
  return body;
}

// Lever arm from body's centre of mass to point, taken from atom i's own image of the body.
Vec3 PairGranImpulse::lever_arm(int i, int body, const Vec3 &point) const
{
  double com[3], com_image[3];
  solver.body(body).com.store(com);
  domain->closest_image(atom->x[i], com, com_image);
  return point - Vec3(com_image);
}

void PairGranImpulse::add_contact(int body1, int body2, const AtomContact &atoms, const Vec3 &n,
                                  double gap, const ContactMaterial &material, const Vec3 &r1,
                                  const Vec3 &r2)
{
  const double dt = update->dt;
  // Predictive contact: in contact if the gap closes within this step at the current normal
  // velocity, or already overlaps; an overlap must at least open at beta * overlap / dt.
  const Vec3 u = solver.body(body2).velocity_at_arm(r2) - solver.body(body1).velocity_at_arm(r1);
  if (gap + dot(u, n) * dt >= 0.0) return;
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
  found.push_back({shuffle, identity, body1, body2, r1, r2, n, material, min_separation, atoms});
  largest_overlap = std::max(largest_overlap, -gap);
}

void PairGranImpulse::add_found_contacts()
{
  auto shuffled = [](const FoundContact &a, const FoundContact &b) {
    return std::tie(a.shuffle, a.identity) < std::tie(b.shuffle, b.identity);
  };
  auto ascending = [](const FoundContact &a, const FoundContact &b) { return a.identity < b.identity; };
  auto descending = [](const FoundContact &a, const FoundContact &b) { return b.identity < a.identity; };
  if (order == Order::SHUFFLE) std::sort(found.begin(), found.end(), shuffled);
  else if (order == Order::TAG) std::sort(found.begin(), found.end(), ascending);
  else std::sort(found.begin(), found.end(), descending);
  for (const FoundContact &c : found) {
    solver.add_contact_arms(c.body1, c.body2, c.r1, c.r2, c.n, c.material, c.min_separation);
    atom_contacts.push_back(c.atoms);
  }
}

// An upper bound of the speed at which atom i closes in on atom j (j < 0: a wall moving at
// wall_velocity), surface speeds of spins included, from the atoms' own velocities. Pairs and
// walls farther apart than it carries them in one step are skipped before bodies are built.
double PairGranImpulse::closing_speed_bound(int i, int j, const Vec3 &wall_velocity) const
{
  double **v = atom->v, **omega = atom->omega;
  double *radius = atom->radius;
  const Vec3 partner = j >= 0 ? Vec3(v[j]) : wall_velocity;
  const double spins = norm(Vec3(omega[i])) * radius[i] + (j >= 0 ? norm(Vec3(omega[j])) * radius[j] : 0.0);
  return norm(Vec3(v[i]) - partner) + spins;
}

void PairGranImpulse::gather_pair_contacts()
{
  double **x = atom->x;
  double *radius = atom->radius;
  int *type = atom->type;
  const double reach = neighbor->skin;
  const double dt = update->dt;

  const int nlist = list->inum + (list->ghost ? list->gnum : 0);
  for (int ii = 0; ii < nlist; ii++) {
    const int i = list->ilist[ii];
    if (i >= atom->nlocal && !solved_here[i]) continue;    // most ghosts: nothing to solve here
    const int *jlist = list->firstneigh[i];
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (!solves_pair(i, j)) continue;
      Vec3 d = Vec3(x[j]) - Vec3(x[i]);
      const double radsum = radius[i] + radius[j];
      const double rsq = norm2(d);
      if (rsq >= (radsum + reach) * (radsum + reach) || rsq == 0.0) continue;
      const double r = std::sqrt(rsq);
      const double gap = r - radsum;
      if (gap > 0.0 && gap >= closing_speed_bound(i, j, Vec3()) * dt) continue;
      const Vec3 n = d / r;    // from i to j
      const Vec3 point = Vec3(x[i]) + n * (radius[i] + 0.5 * gap);
      const int bi = body_of_atom(i), bj = body_of_atom(j);
      if (bi == bj) continue;    // constituents of one rigid body, or a bead and its image
      const ContactMaterial material{restitution[type[i]][type[j]], friction[type[i]][type[j]]};
      add_contact(bi, bj, {i, j, nullptr, 0, point}, n, gap, material, lever_arm(i, bi, point),
                  lever_arm(j, bj, point));
    }
  }
}

void PairGranImpulse::gather_wall_contacts()
{
  const double reach = neighbor->skin;
  for (ImpulseWall *wall : walls) {
    wall_scratch.clear();
    wall->find_wall_contacts(reach, solved_here, wall_scratch);
    for (const ImpulseWall::Contact &c : wall_scratch) {
      if (c.gap > 0.0 && c.gap >= closing_speed_bound(c.atom, -1, c.wall_velocity) * update->dt) continue;
      const int b = body_of_atom(c.atom);
      const int w = solver.add_body(RigidBodyState::wall(c.wall_velocity));
      add_contact(w, b, {-1, c.atom, wall, c.surface, c.point}, c.normal, c.gap, c.material, Vec3(),
                  lever_arm(c.atom, b, c.point));
    }
  }
}

void PairGranImpulse::distribute_impulses()
{
  const double to_force = 1.0 / update->dt;
  double **x = atom->x;
  auto push = [&](int i, const Vec3 &F, const Vec3 &point) {
    const Vec3 torque = cross(point - Vec3(x[i]), F);
    F.add_to(fcontact[i]);
    torque.add_to(tcontact[i]);
  };
  for (int c = 0; c < solver.num_contacts(); c++) {
    const AtomContact &ac = atom_contacts[c];
    const Vec3 &J = solver.impulse(c);
    const Vec3 F = J * to_force;
    push(ac.atom2, F, ac.point);
    if (ac.atom1 >= 0) push(ac.atom1, -F, ac.point);
    else ac.wall->add_delivered_impulse(ac.surface, J);
  }
}

// Add the contact forces to owned atoms; remember them for a run that continues from here.
void PairGranImpulse::apply_contact_forces(bool store)
{
  double **f = atom->f, **torque = atom->torque, **saved = pending->astore;
  const double step = (double) update->ntimestep;
  for (int i = 0; i < atom->nlocal; i++) {
    for (int k = 0; k < 3; k++) {
      f[i][k] += fcontact[i][k];
      torque[i][k] += tcontact[i][k];
    }
    if (!store) continue;
    for (int k = 0; k < 3; k++) {
      saved[i][PENDING_FORCE + k] = fcontact[i][k];
      saved[i][PENDING_TORQUE + k] = tcontact[i][k];
    }
    saved[i][PENDING_STEP] = step;
  }
}

// The contact forces of the step this run continues from (if any): their half due in its
// initial_integrate.
void PairGranImpulse::restore_pending_forces()
{
  double **saved = pending->astore;
  const double step = (double) update->ntimestep;
  for (int i = 0; i < atom->nlocal; i++)
    if (saved[i][PENDING_STEP] == step)
      for (int k = 0; k < 3; k++) {
        fcontact[i][k] = saved[i][PENDING_FORCE + k];
        tcontact[i][k] = saved[i][PENDING_TORQUE + k];
      }
}

// Solver health into pvector (see Output), and a warning when the sweep cap keeps stopping the
// solve before the tolerance.
void PairGranImpulse::record_solve(const ActiveGrain::ContactSolver::Result &result)
{
  enum Reduced { R_SWEEPS, R_RESIDUAL, R_OVERLAP, R_CAPPED, NUM_REDUCED };
  double mine[NUM_REDUCED] = {(double) result.sweeps, result.residual, largest_overlap,
                              result.converged ? 0.0 : 1.0};
  double all[NUM_REDUCED];
  if (comm->nprocs > 1) MPI_Allreduce(mine, all, NUM_REDUCED, MPI_DOUBLE, MPI_MAX, world);
  else std::copy(mine, mine + NUM_REDUCED, all);
  if (all[R_CAPPED] > 0.0) capped_steps++;

  // Maxima go to rank 0 only: compute pair sums pvector over ranks.
  const double here = comm->me == 0 ? 1.0 : 0.0;
  pvector[CONTACTS] = solver.num_contacts();
  pvector[SWEEPS] = here * all[R_SWEEPS];
  pvector[RESIDUAL] = here * all[R_RESIDUAL];
  pvector[LARGEST_OVERLAP] = here * all[R_OVERLAP];
  pvector[CAPPED_STEPS] = here * (double) capped_steps;

  // Stronge's law is swept a fixed number of times by design: only a converging law warns.
  if (capped_steps == next_cap_warning && coupled_law == ActiveGrain::ContactSolver::CoupledLaw::PROJECTION) {
    if (comm->me == 0)
      error->warning(FLERR, "{}: the contact solve stopped at the sweep cap ({} sweeps) in {} steps of "
                     "this run, residual {:.3g} > tolerance {:.3g}: raise sweeps", STYLE, max_sweeps,
                     capped_steps, all[R_RESIDUAL], tolerance);
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
    largest_overlap = 0.0;
    capped_steps = 0;
    next_cap_warning = FIRST_CAP_WARNING;
    std::fill(pvector, pvector + NUM_OUTPUTS, 0.0);
    if (ghost_pairs) {
      assign_contact_ranks();
      check_ghost_cutoff();
    }
    return;
  }

  assign_contact_ranks();
  solver.clear();
  body_index.clear();
  atom_contacts.clear();
  found.clear();
  gather_pair_contacts();
  gather_wall_contacts();
  add_found_contacts();
  record_solve(solver.solve(max_sweeps, tolerance, coupled_law));
  distribute_impulses();
  comm->reverse_comm(this);
  apply_contact_forces(true);
}

int PairGranImpulse::pack_reverse_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++)
    for (int k = 0; k < 3; k++) {
      buf[m++] = fcontact[i][k];
      buf[m++] = tcontact[i][k];
    }
  return m;
}

void PairGranImpulse::unpack_reverse_comm(int n, int *list, double *buf)
{
  int m = 0;
  for (int i = 0; i < n; i++) {
    const int j = list[i];
    for (int k = 0; k < 3; k++) {
      fcontact[j][k] += buf[m++];
      tcontact[j][k] += buf[m++];
    }
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

void PairGranImpulse::write_restart_settings(FILE *fp)
{
  const int order_code = static_cast<int>(order), law_code = static_cast<int>(coupled_law);
  fwrite(&max_sweeps, sizeof(int), 1, fp);
  fwrite(&tolerance, sizeof(double), 1, fp);
  fwrite(&beta, sizeof(double), 1, fp);
  fwrite(&order_code, sizeof(int), 1, fp);
  fwrite(&law_code, sizeof(int), 1, fp);
}

void PairGranImpulse::read_restart_settings(FILE *fp)
{
  int order_code = 0, law_code = 0;
  if (comm->me == 0) {
    utils::sfread(FLERR, &max_sweeps, sizeof(int), 1, fp, nullptr, error);
    utils::sfread(FLERR, &tolerance, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &beta, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &order_code, sizeof(int), 1, fp, nullptr, error);
    utils::sfread(FLERR, &law_code, sizeof(int), 1, fp, nullptr, error);
  }
  MPI_Bcast(&max_sweeps, 1, MPI_INT, 0, world);
  MPI_Bcast(&tolerance, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&beta, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&order_code, 1, MPI_INT, 0, world);
  MPI_Bcast(&law_code, 1, MPI_INT, 0, world);
  order = static_cast<Order>(order_code);
  coupled_law = static_cast<ActiveGrain::ContactSolver::CoupledLaw>(law_code);
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
  return 6.0 * nmax * sizeof(double) + (double) atom_body.capacity() * sizeof(int) +
      (double) rigid_body_id.capacity() * sizeof(tagint) + (double) solved_here.capacity() +
      (double) found.capacity() * sizeof(FoundContact) +
      (double) solver.num_contacts() * sizeof(ActiveGrain::ContactSolver::Contact);
}
