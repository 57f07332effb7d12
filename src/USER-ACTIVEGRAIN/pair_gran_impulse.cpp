/* ----------------------------------------------------------------------
   ActiveGrain: pair_style gran/impulse. Each step is three stages: assemble (LAMMPS's atoms and
   wall fixes to the core's bodies and contacts), solve (the core's ContactSolver), deliver (each
   contact impulse J as a force J/dt and torque on its atoms, which velocity Verlet applies half
   in this step's final_integrate and half in the next initial_integrate).
------------------------------------------------------------------------- */

#include "pair_gran_impulse.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "impulse_wall.h"
#include "style_inputs.h"
#include "memory.h"
#include "modify.h"
#include "molecule.h"
#include "neighbor.h"
#include "rigid_body_provider.h"
#include "update.h"
#include "utils.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

static const char *const STYLE = "Pair gran/impulse";
// The units check (check_deck): in lj units, grains smaller than this are SI numbers when gravity
// or the plates' acceleration is >= 1 or the skin is this many diameters; in si units, grains
// this large with gravity below SI_SMALL_GRAVITY are lj numbers.
static constexpr double LJ_SMALL_DIAMETER = 0.01;
static constexpr double LJ_SKIN_DIAMETERS = 10.0;
static constexpr double SI_LARGE_DIAMETER = 0.5;
static constexpr double SI_SMALL_GRAVITY = 2.0;

PairGranImpulse::PairGranImpulse(LAMMPS *lmp) :
    Pair(lmp), models(lmp),
    maxrad(nullptr), ghost_pairs(false), ranks(lmp), near(lmp), bodies(lmp, solver, ranks),
    assembly(lmp, solver, bodies, ranks, near), exchange(lmp), delivery(lmp), carry(lmp), diagnostics(lmp, STYLE)
{
  single_enable = 0;
  restartinfo = 1;
  finitecutflag = 1;
  // Contact sums of ghost atoms reach their owners with newton off too (Comm sizes its buffers
  // for reverse comm from comm_reverse_off then).
  comm_reverse = comm_reverse_off = ImpulseDelivery::NUM_COLUMNS;
  // Contact forces reach owners through this style's own reverse communication, so the f.r
  // virial over owned and ghost atoms would be wrong: the virial is tallied per contact.
  no_virial_fdotr_compute = 1;
  nextra = NUM_OUTPUTS;
  pvector = new double[NUM_OUTPUTS]();
}

PairGranImpulse::~PairGranImpulse()
{
  carry.delete_store();
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    delete[] maxrad;
  }
  delete[] pvector;
}

void PairGranImpulse::allocate()
{
  allocated = 1;
  const int n = atom->ntypes + 1;
  memory->create(setflag, n, n, "pair:setflag");
  memory->create(cutsq, n, n, "pair:cutsq");
  models.allocate(atom->ntypes);
  maxrad = new double[n];
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) setflag[i][j] = 0;
}

void PairGranImpulse::settings(int narg, char **arg)
{
  style_settings.parse(lmp, STYLE, narg, arg);
}

/* pair_coeff I J e mu [tangential stick|compliant R] */
void PairGranImpulse::coeff(int narg, char **arg)
{
  if (narg < 4) error->all(FLERR, "{}: pair_coeff needs I J e mu", STYLE);
  if (!allocated) allocate();
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  const ActiveGrain::ContactModel model = parse_contact_model(lmp, STYLE, narg - 2, arg + 2);
  int count = 0;
  for (int i = ilo; i <= ihi; i++)
    for (int j = std::max(jlo, i); j <= jhi; j++) {
      models.set(i, j, model);
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
  carry.create_store();
  find_fixes();
  request_neighbors();
  find_type_radii();
  check_deck();
  warn_silent_inputs(lmp, STYLE, warned_inputs, style_settings.slop);
  assembly.init(style_settings.beta, style_settings.slop, style_settings.order, &models, walls);
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
  refuse_integrated_rod_atoms();
}

// Rod atoms (a molecule ID, with a template of several atoms defined: rod_template; with fix
// rigid/rod, those of its group) moved by an integrator of free particles (fix nve/sphere and the
// like) fall apart or are integrated twice.
void PairGranImpulse::refuse_integrated_rod_atoms()
{
  if (!atom->molecule_flag) return;
  int largest_template = 0;
  for (int m = 0; m < atom->nmolecule; m++) largest_template = std::max(largest_template, atom->molecules[m]->natoms);
  if (largest_template < 2) return;
  // Rod atoms: those of fix rigid/rod's groups, or without such a fix, all with a molecule ID.
  int rod_groups = 0;
  bool rod_fix = false;
  for (Fix *fix : modify->get_fix_list())
    if (fix->rigid_flag && dynamic_cast<RigidBodyProvider *>(fix)) {
      rod_groups |= fix->groupbit;
      rod_fix = true;
    }
  for (Fix *fix : modify->get_fix_list()) {
    if (!fix->time_integrate || fix->rigid_flag) continue;
    int found = 0, any = 0;
    for (int i = 0; i < atom->nlocal && !found; i++)
      if ((atom->mask[i] & fix->groupbit) && atom->molecule[i] > 0 && (!rod_fix || (atom->mask[i] & rod_groups)))
        found = 1;
    MPI_Allreduce(&found, &any, 1, MPI_INT, MPI_MAX, world);
    if (any)
      error->all(FLERR, "{}: fix {} (style {}) integrates rod atoms (atoms with a molecule ID) as free "
                 "particles: rods need fix rigid/rod (fix ID rods rigid/rod molecule mol TEMPLATE), and fix {} "
                 "only the beads (a group without the rods)", STYLE, fix->id, fix->style, fix->style);
  }
}

// Inputs that run but do not mean what they say, checked before each run (a variable gravity
// counts from its first step's value): LAMMPS's default lj units with SI-sized numbers (or the reverse), and gravity
// with nothing to hold the particles.
void PairGranImpulse::check_deck()
{
  const double diameter = 2.0 * largest_type_radius();
  const double acceleration = largest_wall_acceleration();
  bodies.begin_step();
  const double gravity = bodies.largest_gravity();
  // lj units measure lengths in grain diameters (LAMMPS's granular decks: d = 1, g = 1). Grains a
  // hundredth of the length unit are SI numbers (metres) when gravity or the plates' acceleration
  // is of order 1 or more (9.81, 4e-5 (2 pi 200)^2 = 63) or the skin is many diameters (lj's
  // default 0.3): forgotten units si.
  if (diameter > 0.0 && diameter < LJ_SMALL_DIAMETER && strcmp(update->unit_style, "lj") == 0) {
    const bool si_numbers = gravity >= 1.0 || acceleration >= 1.0 || neighbor->skin >= LJ_SKIN_DIAMETERS * diameter;
    const std::string what = fmt::format("particles of diameter {:.3g} in units lj (LAMMPS's default units, "
                                         "lengths in grain diameters); gravity {:.3g}, skin {:.3g}", diameter,
                                         gravity, neighbor->skin);
    if (si_numbers)
      error->all(FLERR, "{}: {}: these are SI numbers: add units si at the top of the deck (before create_box "
                 "or read_data)", STYLE, what);
    else if (comm->me == 0 && !warned_units)
      error->warning(FLERR, "{}: {}: if these are SI numbers, add units si at the top of the deck", STYLE, what);
    warned_units = true;
  }
  // The reverse: SI units, grains of half a metre or more and a gravity of order 1 (lj's g = 1).
  if (diameter >= SI_LARGE_DIAMETER && gravity > 0.0 && gravity < SI_SMALL_GRAVITY &&
      strcmp(update->unit_style, "si") == 0 && comm->me == 0 && !warned_units) {
    error->warning(FLERR, "{}: particles of diameter {:.3g} m with gravity {:.3g} m/s^2 in units si: if these are "
                   "lj numbers (lengths in grain diameters), remove units si", STYLE, diameter, gravity);
    warned_units = true;
  }
  // Gravity with no plate (nor frozen grains to rest on): particles fall out of a bounded box ("Lost atoms") or forever.
  if (gravity > 0.0 && walls.empty() && modify->get_fix_by_style("^freeze").empty() && comm->me == 0 &&
      !warned_no_walls) {
    error->warning(FLERR, "{}: fix gravity acts but no fix wall/impulse or wall/impulse/region holds the "
                   "particles: they will fall through (Lost atoms in a bounded box); add fix wall/impulse", STYLE);
    warned_no_walls = true;
  }
}

// Rigid-body providers, wall fixes, fix gravity and fix freeze (its atoms are bodies of infinite
// mass).
void PairGranImpulse::find_fixes()
{
  std::vector<Fix *> gravities;
  providers.clear();
  walls.clear();
  for (Fix *fix : modify->get_fix_list()) {
    if (auto provider = dynamic_cast<RigidBodyProvider *>(fix)) providers.push_back(provider);
    if (auto wall = dynamic_cast<ImpulseWall *>(fix)) walls.push_back(wall);
    if (utils::strmatch(fix->style, "^gravity")) gravities.push_back(fix);
  }
  auto freezes = modify->get_fix_by_style("^freeze");
  if (freezes.size() > 1) error->all(FLERR, "{}: only one fix freeze is supported", STYLE);
  bodies.init(providers, freezes.empty() ? 0 : freezes.front()->groupbit, gravities);
}

// A rigid body's solver rank also solves contacts between two ghost atoms (a ghost atom of its
// body with a neighbor): that needs the neighbors of ghost atoms, a full list (there is no half
// list with ghosts for newton on, nor one with per-atom cutoffs: cutoffs come from the largest
// radii per type). Without rigid bodies, the usual half list.
void PairGranImpulse::request_neighbors()
{
  ghost_pairs = !providers.empty();
  if (ghost_pairs) {
    if (atom->map_style == Atom::MAP_NONE)
      error->all(FLERR, "{} with rigid bodies requires an atom map (atom_modify map array)", STYLE);
    neighbor->add_request(this, NeighConst::REQ_FULL | NeighConst::REQ_GHOST);
  } else {
    neighbor->add_request(this, NeighConst::REQ_SIZE);
  }
}

// Largest radius of each type, present now or to be inserted by fix pour/deposit during the run
// (as GRANULAR's pair styles do): neighbor cutoffs are radius sums plus the skin. An atom larger
// than its type's radius here (inserted by other means) is refused in the run. A particle wider
// than the box would touch its own periodic image or not fit between the box's walls.
void PairGranImpulse::find_type_radii()
{
  const int ntypes = atom->ntypes;
  std::vector<double> local(ntypes + 1, 0.0);
  for (int i = 0; i < atom->nlocal; i++) local[atom->type[i]] = std::max(local[atom->type[i]], atom->radius[i]);
  MPI_Allreduce(local.data(), maxrad, ntypes + 1, MPI_DOUBLE, MPI_MAX, world);
  for (int t = 1; t <= ntypes; t++) maxrad[t] = std::max(maxrad[t], inserted_radius(lmp, t));
  const double largest = largest_type_radius();
  for (int t = 1; t <= ntypes; t++)
    if (maxrad[t] == 0.0) maxrad[t] = largest;
  const char axis[3] = {'x', 'y', 'z'};
  for (int d = 0; d < domain->dimension; d++)
    if (2.0 * largest > domain->prd[d])
      error->all(FLERR, "{}: particles of diameter {} are wider than the box ({} length {})", STYLE,
                 2.0 * largest, axis[d], domain->prd[d]);
}

double PairGranImpulse::largest_type_radius() const
{
  return *std::max_element(maxrad + 1, maxrad + atom->ntypes + 1);
}

// A time step change (the timestep command between runs, fix dt/reset in a run) while the second
// half of the last step's impulses is still due.
void PairGranImpulse::reset_dt() { carry.rescale_for_dt(); }

double PairGranImpulse::init_one(int i, int j)
{
  if (setflag[i][j] == 0) models.mix(i, j);
  models.set(j, i, models.of(i, j));
  return maxrad[i] + maxrad[j];
}

void PairGranImpulse::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  delivery.begin_step();
  assembly.scan_atoms(maxrad);
  if (update->setupflag) {
    setup_step();
    return;
  }
  assemble();
  solve();
  deliver();
}

// Contacts are solved in the steps. At setup only the force of the step this run continues from
// (if any) comes back, so that its initial_integrate completes the impulse.
void PairGranImpulse::setup_step()
{
  carry.restore(delivery);
  delivery.apply_forces();
  if (vflag_global) carry.restore_virial(virial);
  diagnostics.setup();
  std::fill(pvector, pvector + NUM_OUTPUTS, 0.0);
  if (ghost_pairs) {
    ranks.assign(providers);
    ranks.check_ghost_cutoff(STYLE);
  }
  near.invalidate();    // setup may have sorted the atoms without a new neighbor list build
}

void PairGranImpulse::assemble()
{
  ranks.assign(providers);
  solver.clear();
  bodies.begin_step();
  assembly.assemble(list);
  exchange.split(solver, bodies, assembly);
}

void PairGranImpulse::solve()
{
  ActiveGrain::SolverSettings &solver_settings = style_settings.solver;
  solver_settings.set_step(update->dt, largest_acceleration());
  ActiveGrain::ContactSolver::Result result = solver.solve(solver_settings);
  result.merge(exchange.solve(solver, solver_settings, style_settings.order));
  report(diagnostics.record(result, assembly.extremes(), largest_type_radius(), solver_settings.max_substeps),
         diagnostics.tally_energy(solver, assembly));
}

// What sets the speed below which contacts rest: gravity, the walls' vibration.
double PairGranImpulse::largest_acceleration() const
{
  return std::max(bodies.largest_gravity(), largest_wall_acceleration());
}

double PairGranImpulse::largest_wall_acceleration() const
{
  double largest = 0.0;
  for (const ImpulseWall *wall : walls) largest = std::max(largest, wall->peak_acceleration());
  return largest;
}

void PairGranImpulse::deliver()
{
  delivery.distribute(solver, assembly);
  delivery.tally_virial(solver, assembly, virial, vflag_global, vflag_atom);
  if (vflag_global) carry.keep_virial(virial);
  delivery.reverse_sum(this, vflag_atom);
  delivery.apply_forces();
  carry.store(delivery);
  delivery.move_late_atoms(bodies);
  if (vflag_atom) delivery.add_atom_virial(vatom);
}

// Maxima go to rank 0 only: compute pair sums pvector over ranks.
void PairGranImpulse::report(const SolveDiagnostics::Health &health, const SolveDiagnostics::Energies &energies)
{
  const double here = comm->me == 0 ? 1.0 : 0.0;
  pvector[CONTACTS] = solver.num_contacts();
  pvector[SUBSTEPS] = here * health.substeps;
  pvector[SHORTFALL] = here * health.shortfall;
  pvector[LARGEST_OVERLAP] = here * health.largest_overlap;
  pvector[CAPPED_STEPS] = here * health.capped_steps;
  pvector[DISSIPATED_PAIR] = energies.dissipated_pair;
  pvector[DISSIPATED_WALL] = energies.dissipated_wall;
  pvector[OVERLAP_WORK] = energies.overlap_work;
  pvector[WALL_WORK] = energies.wall_work;
  pvector[RESTING_SWEEPS] = here * health.resting_sweeps;
}

int PairGranImpulse::pack_reverse_comm(int n, int first, double *buf)
{
  return delivery.pack_reverse(n, first, buf);
}

void PairGranImpulse::unpack_reverse_comm(int n, int *list, double *buf)
{
  delivery.unpack_reverse(n, list, buf);
}

void PairGranImpulse::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      fwrite(&setflag[i][j], sizeof(int), 1, fp);
      if (setflag[i][j]) models.write_restart(fp, i, j);
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
      if (setflag[i][j]) models.read_restart(fp, i, j, style_settings.restart_model_coeffs);
    }
}

void PairGranImpulse::write_restart_settings(FILE *fp)
{
  style_settings.write_restart(fp);
}

void PairGranImpulse::read_restart_settings(FILE *fp)
{
  style_settings.read_restart(lmp, STYLE, fp);
}

void *PairGranImpulse::extract(const char *name, int &dim)
{
  dim = 2;
  return (void *) models.extract(name);
}

double PairGranImpulse::memory_usage()
{
  return delivery.memory_usage() + bodies.memory_usage() + assembly.memory_usage() + ranks.memory_usage() +
      near.memory_usage() + exchange.memory_usage() + (double) solver.num_contacts() * sizeof(ActiveGrain::ContactSolver::Contact);
}
