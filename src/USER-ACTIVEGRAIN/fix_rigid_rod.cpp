#include "fix_rigid_rod.h"

#include "ag_rod_geometry.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "ghost_cutoff.h"
#include "math_extra.h"
#include "memory.h"
#include "molecule.h"
#include "neighbor.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <unordered_map>
#include <vector>

using namespace LAMMPS_NS;
using namespace FixConst;
using ActiveGrain::Mat3;
using ActiveGrain::NSYMMETRIC;
using ActiveGrain::VEC3_SIZE;
using ActiveGrain::Vec3;

static const char *const STYLE = "Fix rigid/rod";

namespace {
// Layout of one atom's row of `state`: what a contact style needs of its body. The offset is
// the atom's world-frame displacement from the COM, so that the COM of any periodic image of
// the atom is its own position minus the offset.
enum {
  STATE_ID,
  STATE_INVMASS,
  STATE_OFFSET,
  STATE_INVI = STATE_OFFSET + VEC3_SIZE,
  STATE_V = STATE_INVI + NSYMMETRIC,
  STATE_OMEGA = STATE_V + VEC3_SIZE,
  NSTATE = STATE_OMEGA + VEC3_SIZE
};
// Columns of `polar_sum` (per body): the sum of nose - tail offsets, and the counts of each.
enum { SUM_VEC, SUM_NTAIL = SUM_VEC + VEC3_SIZE, SUM_NNOSE, NSUM };
// Columns of `late` (per atom) and `late_move` (per body): a late impulse and its moment; for a
// body, once summed on its owner, its displacement and rotation vector.
enum { LATE_LINEAR, LATE_ANGULAR = LATE_LINEAR + VEC3_SIZE, NLATE = LATE_ANGULAR + VEC3_SIZE };
// Columns of the per-atom output (f_ID[1] .. f_ID[4]): the rod's 3-D axis (body x, tail to
// nose), then its body ID, which tells rods apart in dumps whatever the molecule IDs say.
enum { OUT_AXIS, OUT_BODY = OUT_AXIS + VEC3_SIZE, NOUT };

// A direction across the template's axis is built from the x axis, or from the y axis where the
// rod lies within about 26 degrees of x (|axis.x| >= 0.9).
constexpr double TRIAL_AXIS_COSINE = 0.9;
// The template's inertia tensor must have the axis and a transverse direction as eigenvectors,
// to this tolerance relative to I_axial + I_transverse (room for the template's round-off).
constexpr double AXISYMMETRY_TOLERANCE = 1e-8;
// extract()'s dim for a per-atom array.
constexpr int EXTRACT_ARRAY = 2;

Vec3 v3(const double *a) { return Vec3(a); }
}    // namespace

FixRigidRod::FixRigidRod(LAMMPS *lmp, int narg, char **arg) : FixRigidSmall(lmp, narg, arg)
{
  if (!onemols)
    error->all(FLERR, "{}: requires the mol keyword naming a rod template (rod_template)", STYLE);
  if (nmol != 1) error->all(FLERR, "{}: the mol template must hold exactly one rod", STYLE);
  if (!atom->radius_flag || !atom->rmass_flag)
    error->all(FLERR, "{}: needs an atom style with per-atom diameter and mass (sphere)", STYLE);

  // The template: an axisymmetric rod along its first (tail) to last (nose) atom.
  Molecule *rod = onemols[0];
  const int n = rod->natoms;
  if (n < ActiveGrain::MIN_ROD_SPHERES)
    error->all(FLERR, "{}: template {} has fewer than {} atoms", STYLE, rod->id,
               ActiveGrain::MIN_ROD_SPHERES);
  tail_type = rod->type[0];
  nose_type = rod->type[n - 1];
  for (int i = 1; i < n - 1; ++i)
    if (rod->type[i] == tail_type || rod->type[i] == nose_type)
      error->all(FLERR, "{}: template {}: only the first (tail) and last (nose) atoms may "
                 "have the tail and nose types", STYLE, rod->id);
  if (tail_type == nose_type)
    error->all(FLERR, "{}: template {}: tail and nose atoms have the same type", STYLE, rod->id);

  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const double d = ActiveGrain::norm(v3(rod->x[j]) - v3(rod->x[i]));
      if (d > template_span) {
        template_span = d;
        template_length = d + (rod->radiusflag ? rod->radius[i] + rod->radius[j] : 0.0);
      }
    }
  Vec3 axis = v3(rod->x[n - 1]) - v3(rod->x[0]);
  axis = axis / ActiveGrain::norm(axis);
  const Vec3 trial = std::fabs(axis.x) < TRIAL_AXIS_COSINE ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  Vec3 across = ActiveGrain::cross(axis, trial);
  across = across / ActiveGrain::norm(across);
  const Mat3 itensor = Mat3::symmetric(rod->itensor);
  inertia_axial = ActiveGrain::dot(axis, itensor * axis);
  inertia_transverse = ActiveGrain::dot(across, itensor * across);
  const double scale = inertia_axial + inertia_transverse;
  if (ActiveGrain::norm(itensor * axis - axis * inertia_axial) > AXISYMMETRY_TOLERANCE * scale ||
      ActiveGrain::norm(itensor * across - across * inertia_transverse) > AXISYMMETRY_TOLERANCE * scale ||
      !(inertia_axial > 0.0) || !(inertia_transverse > 0.0))
    error->all(FLERR, "{}: template {} is not an axisymmetric rod along its tail-to-nose axis", STYLE,
               rod->id);

  peratom_flag = 1;
  size_peratom_cols = NOUT;
  peratom_freq = 1;
  grow_arrays(atom->nmax);
}

FixRigidRod::~FixRigidRod() noexcept
{
  memory->destroy(state);
  memory->destroy(output);
  memory->destroy(polar_sum);
  memory->destroy(late);
  memory->destroy(late_move);
}

int FixRigidRod::setmask()
{
  return FixRigidSmall::setmask() | PRE_FORCE;
}

void FixRigidRod::init()
{
  // fix rigid/small warns that gravity may be misapplied to bodies from a molecule template
  // (overlapping particles); rod_template's sphere masses give exactly the solid's weight at
  // its centre of mass, so the warning does not apply here.
  Molecule **templates = onemols;
  onemols = nullptr;
  FixRigidSmall::init();
  onemols = templates;
  // Any other pair style would treat rod spheres as independent grains or as bodies without
  // rotational inertia; without one, rods would pass through everything.
  if (!force->pair || !force->pair_match("gran/impulse", 0))
    error->all(FLERR, "{}: rods need pair_style gran/impulse (found pair_style {})", STYLE,
               force->pair ? force->pair_style : "none");
  check_molecule_ids();
  // A rod as long as a periodic box length would touch its own image.
  const char axis[3] = {'x', 'y', 'z'};
  for (int d = 0; d < domain->dimension; d++)
    if (domain->periodicity[d] && template_length >= domain->prd[d])
      error->all(FLERR, "{}: rods of template {} are {:.6g} long, longer than the periodic box ({} length "
                 "{:.6g}): a rod would touch its own image; enlarge the box", STYLE, onemols[0]->id,
                 template_length, axis[d], domain->prd[d]);
}

// A body is the atoms of one molecule ID: a rod whose atoms carry two IDs (a stray set ... mol, a
// data file edited by hand) leaves a molecule ID with more or fewer atoms than the template.
void FixRigidRod::check_molecule_ids()
{
  std::unordered_map<tagint, int> local;
  for (int i = 0; i < atom->nlocal; ++i)
    if ((atom->mask[i] & groupbit) && atom->molecule[i] > 0) ++local[atom->molecule[i]];
  std::vector<tagint> ids;
  std::vector<int> counts;
  for (const auto &entry : local) {
    ids.push_back(entry.first);
    counts.push_back(entry.second);
  }
  const int n = (int) ids.size(), nprocs = comm->nprocs;
  std::vector<int> sizes(nprocs), offsets(nprocs, 0);
  MPI_Allgather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, world);
  for (int p = 1; p < nprocs; ++p) offsets[p] = offsets[p - 1] + sizes[p - 1];
  const int total = offsets[nprocs - 1] + sizes[nprocs - 1];
  std::vector<tagint> all_ids(std::max(total, 1));
  std::vector<int> all_counts(std::max(total, 1));
  MPI_Allgatherv(ids.data(), n, MPI_LMP_TAGINT, all_ids.data(), sizes.data(), offsets.data(), MPI_LMP_TAGINT, world);
  MPI_Allgatherv(counts.data(), n, MPI_INT, all_counts.data(), sizes.data(), offsets.data(), MPI_INT, world);
  std::map<tagint, int> atoms_of;
  for (int k = 0; k < total; ++k) atoms_of[all_ids[k]] += all_counts[k];
  for (const auto &entry : atoms_of)
    if (entry.second != onemols[0]->natoms)
      error->all(FLERR, "{}: molecule ID {} has {} atoms, a rod of template {} has {}: a rod's atoms must carry "
                 "one molecule ID of their own (check set ... mol and the data file's Molecules section)", STYLE,
                 entry.first, entry.second, onemols[0]->id, onemols[0]->natoms);
}

void FixRigidRod::setup_pre_neighbor()
{
  // The whole rod must be visible as ghosts where any of its atoms is.
  // The value quoted is the rule of ghost_cutoff.h (what pair gran/impulse asks for on more than
  // one rank), not the extent alone, so that it holds on any number of ranks.
  const double cutghost = std::max(neighbor->cutneighmax, comm->cutghostuser);
  if (maxextent > cutghost)
    error->all(FLERR, "{}: rod extent {:.6g} exceeds the ghost cutoff {:.6g}: use comm_modify cutoff {:.6g} "
               "(valid on any number of ranks)", STYLE, maxextent, cutghost, ghost_cutoff_quoted(lmp, template_span));
  const bool reinit = reinitflag || !setupflag;
  FixRigidSmall::setup_pre_neighbor();
  if (reinit) impose_rod_bodies();
}

// A time step change: pair gran/impulse has rescaled the contact forces of the last step in
// atom->f (the half impulse still due); the bodies' forces, summed from them in final_integrate,
// must follow, or the next initial_integrate applies the old ones with the new dt.
void FixRigidRod::reset_dt()
{
  FixRigidSmall::reset_dt();
  if (setupflag) compute_forces_and_torques();
}

/* The base class built each body from its atoms: their masses already sum to the solid's mass
   and centre of mass (rod_template), but their inertia is that of point masses and spheres.
   Give every body the solid's inertia, keep its angular velocity, and rotate its body frame so
   that body x is the polar axis (tail -> nose): the quaternion then carries the polarity. */
void FixRigidRod::impose_rod_bodies()
{
  const int nlocal = atom->nlocal;
  const int nall_body = nlocal_body + nghost_body;
  double **x = atom->x;
  int *type = atom->type;

  memory->destroy(polar_sum);
  memory->create(polar_sum, std::max(nall_body, 1), NSUM, "rigid/rod:polar_sum");
  for (int ib = 0; ib < nall_body; ++ib)
    for (int k = 0; k < NSUM; ++k) polar_sum[ib][k] = 0.0;

  double unwrap[3];
  for (int i = 0; i < nlocal; ++i) {
    if (atom2body[i] < 0) continue;
    const double sign = type[i] == nose_type ? 1.0 : (type[i] == tail_type ? -1.0 : 0.0);
    if (sign == 0.0) continue;
    double *sum = polar_sum[atom2body[i]];
    domain->unmap(x[i], xcmimage[i], unwrap);
    for (int k = 0; k < 3; ++k) sum[SUM_VEC + k] += sign * (unwrap[k] - body[atom2body[i]].xcm[k]);
    sum[sign > 0 ? SUM_NNOSE : SUM_NTAIL] += 1.0;
  }
  rod_comm = RodComm::POLAR_SUM;
  comm->reverse_comm(this, NSUM);
  rod_comm = RodComm::NONE;

  int bad = 0;
  for (int ib = 0; ib < nlocal_body; ++ib) {
    Body &b = body[ib];
    const double *sum = polar_sum[ib];
    const Vec3 tail_to_nose = v3(sum + SUM_VEC);
    if (sum[SUM_NTAIL] != 1.0 || sum[SUM_NNOSE] != 1.0 || ActiveGrain::norm(tail_to_nose) == 0.0) {
      bad = 1;
      continue;
    }
    double omega[3];
    MathExtra::angmom_to_omega(b.angmom, b.ex_space, b.ey_space, b.ez_space, b.inertia, omega);

    const Vec3 ex = tail_to_nose / ActiveGrain::norm(tail_to_nose);
    const Vec3 old_axes[3] = {v3(b.ex_space), v3(b.ey_space), v3(b.ez_space)};
    int least = 0;
    for (int k = 1; k < 3; ++k)
      if (std::fabs(ActiveGrain::dot(old_axes[k], ex)) < std::fabs(ActiveGrain::dot(old_axes[least], ex)))
        least = k;
    Vec3 ey = old_axes[least] - ex * ActiveGrain::dot(old_axes[least], ex);
    ey = ey / ActiveGrain::norm(ey);
    const Vec3 ez = ActiveGrain::cross(ex, ey);
    ex.store(b.ex_space);
    ey.store(b.ey_space);
    ez.store(b.ez_space);
    b.inertia[0] = inertia_axial;
    b.inertia[1] = b.inertia[2] = inertia_transverse;
    MathExtra::exyz_to_q(b.ex_space, b.ey_space, b.ez_space, b.quat);

    const Vec3 w(omega);
    const Vec3 angmom = ex * (inertia_axial * ActiveGrain::dot(w, ex)) +
        ey * (inertia_transverse * ActiveGrain::dot(w, ey)) + ez * (inertia_transverse * ActiveGrain::dot(w, ez));
    angmom.store(b.angmom);
    w.store(b.omega);
    double delta[3];
    MathExtra::sub3(b.xgc, b.xcm, delta);
    MathExtra::transpose_matvec(b.ex_space, b.ey_space, b.ez_space, delta, b.xgc_body);
  }
  int anybad = 0;
  MPI_Allreduce(&bad, &anybad, 1, MPI_INT, MPI_MAX, world);
  if (anybad)
    error->all(FLERR, "{}: every rod needs exactly one tail atom (type {}) and one nose atom (type {})",
               STYLE, tail_type, nose_type);

  // Ghost copies of the bodies, then every atom's body-frame displacement in the new frame.
  pre_neighbor();
  for (int i = 0; i < nlocal; ++i) {
    if (atom2body[i] < 0) continue;
    Body &b = body[atom2body[i]];
    double delta[3];
    domain->unmap(x[i], xcmimage[i], unwrap);
    MathExtra::sub3(unwrap, b.xcm, delta);
    MathExtra::transpose_matvec(b.ex_space, b.ey_space, b.ez_space, delta, displace[i]);
  }
}

void FixRigidRod::setup_pre_force(int)
{
  fill_body_state();
}

void FixRigidRod::pre_force(int)
{
  fill_body_state();
}

// Runs after this step's positions and communication, before forces: the state contact styles
// see is that of the bodies at the current positions (half-step velocities, as velocity Verlet).
void FixRigidRod::fill_body_state()
{
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; ++i) {
    double *s = state[i];
    if (atom2body[i] < 0) {
      s[STATE_ID] = 0.0;
      for (int k = 0; k < NOUT; ++k) output[i][k] = 0.0;
      continue;
    }
    const Body &b = body[atom2body[i]];
    const Vec3 axes[3] = {v3(b.ex_space), v3(b.ey_space), v3(b.ez_space)};
    const Vec3 offset = axes[0] * displace[i][0] + axes[1] * displace[i][1] + axes[2] * displace[i][2];
    Mat3 inv_inertia;
    for (int k = 0; k < 3; ++k) {
      if (b.inertia[k] <= 0.0) continue;
      const Vec3 &e = axes[k];
      const double c = 1.0 / b.inertia[k];
      const double ee[3][3] = {{e.x * e.x, e.x * e.y, e.x * e.z}, {e.y * e.x, e.y * e.y, e.y * e.z},
                               {e.z * e.x, e.z * e.y, e.z * e.z}};
      for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q) inv_inertia.m[r][q] += c * ee[r][q];
    }
    s[STATE_ID] = static_cast<double>(bodytag[i]);
    s[STATE_INVMASS] = 1.0 / b.mass;
    offset.store(s + STATE_OFFSET);
    double *inv_i = s + STATE_INVI;
    inv_i[ActiveGrain::XX] = inv_inertia.m[0][0];
    inv_i[ActiveGrain::YY] = inv_inertia.m[1][1];
    inv_i[ActiveGrain::ZZ] = inv_inertia.m[2][2];
    inv_i[ActiveGrain::XY] = inv_inertia.m[0][1];
    inv_i[ActiveGrain::XZ] = inv_inertia.m[0][2];
    inv_i[ActiveGrain::YZ] = inv_inertia.m[1][2];
    for (int k = 0; k < 3; ++k) {
      s[STATE_V + k] = b.vcm[k];
      s[STATE_OMEGA + k] = b.omega[k];
      output[i][OUT_AXIS + k] = b.ex_space[k];
    }
    output[i][OUT_BODY] = static_cast<double>(bodytag[i]);
  }
  rod_comm = RodComm::STATE;
  comm->forward_comm(this, NSTATE);
  rod_comm = RodComm::NONE;
}

bool FixRigidRod::body_of_atom(int i, ActiveGrain::RigidBodyState &b, tagint &body_id) const
{
  if (i < 0 || i >= atom->nlocal + atom->nghost || i >= nmax_atom) return false;
  const double *s = state[i];
  if (s[STATE_ID] <= 0.0) return false;
  body_id = static_cast<tagint>(s[STATE_ID]);
  b.inv_mass = s[STATE_INVMASS];
  b.inv_inertia = Mat3::symmetric(s + STATE_INVI);
  b.com = v3(atom->x[i]) - v3(s + STATE_OFFSET);
  b.v = v3(s + STATE_V);
  b.omega = v3(s + STATE_OMEGA);
  return true;
}

void FixRigidRod::setup(int vflag)
{
  FixRigidSmall::setup(vflag);
  setup_forces_due = true;
}

// The base class sums the bodies' forces in its setup, before fixes defined after it (fix gravity)
// have added theirs: every run's first half kick would miss them, and a run continued in parts or
// from a restart would drift from one long run (by half a step of gravity per part). Sum them
// again from the complete setup forces.
void FixRigidRod::initial_integrate(int vflag)
{
  if (setup_forces_due) {
    compute_forces_and_torques();
    setup_forces_due = false;
  }
  FixRigidSmall::initial_integrate(vflag);
}

bool FixRigidRod::add_late_impulse(int i, const Vec3 &late_impulse, const Vec3 &late_angular)
{
  if (i >= atom->nlocal || atom2body[i] < 0) return false;
  late_impulse.add_to(late[i] + LATE_LINEAR);
  late_angular.add_to(late[i] + LATE_ANGULAR);
  late_here = true;
  return true;
}

void FixRigidRod::final_integrate()
{
  move_late_bodies();
  FixRigidSmall::final_integrate();
}

// The late impulses of this step's contacts (add_late_impulse): each body sums them on its owner,
// moves back by late / mass and turns back by its inverse inertia times their moment, and its atoms
// follow, before the base class completes the step. The next step's flight then starts where the
// body would be had each impulse acted when its contact closed, not at the step's start.
void FixRigidRod::move_late_bodies()
{
  int mine = late_here ? 1 : 0, anywhere = 0;
  MPI_Allreduce(&mine, &anywhere, 1, MPI_INT, MPI_MAX, world);
  if (!anywhere) return;
  const int nall_body = nlocal_body + nghost_body;
  if (nall_body > nmax_late_body) {
    nmax_late_body = nmax_body;
    memory->destroy(late_move);
    memory->create(late_move, nmax_late_body, NLATE, "rigid/rod:late_move");
  }
  for (int ib = 0; ib < nall_body; ++ib)
    for (int k = 0; k < NLATE; ++k) late_move[ib][k] = 0.0;
  double **x = atom->x;
  double unwrap[3];
  for (int i = 0; i < atom->nlocal; ++i) {
    if (atom2body[i] < 0) continue;
    double *sum = late_move[atom2body[i]];
    const Vec3 impulse(late[i] + LATE_LINEAR);
    domain->unmap(x[i], xcmimage[i], unwrap);
    const Vec3 arm = v3(unwrap) - v3(body[atom2body[i]].xcm);
    impulse.add_to(sum + LATE_LINEAR);
    (Vec3(late[i] + LATE_ANGULAR) + ActiveGrain::cross(arm, impulse)).add_to(sum + LATE_ANGULAR);
    for (int k = 0; k < NLATE; ++k) late[i][k] = 0.0;
  }
  late_here = false;
  rod_comm = RodComm::LATE_MOVE;
  comm->reverse_comm(this, NLATE);
  for (int ib = 0; ib < nlocal_body; ++ib) {
    Body &b = body[ib];
    double *move = late_move[ib];
    double turn[3];
    MathExtra::angmom_to_omega(move + LATE_ANGULAR, b.ex_space, b.ey_space, b.ez_space, b.inertia, turn);
    for (int k = 0; k < 3; ++k) {
      move[LATE_LINEAR + k] *= -1.0 / b.mass;
      move[LATE_ANGULAR + k] = -turn[k];
    }
  }
  comm->forward_comm(this, NLATE);
  rod_comm = RodComm::NONE;
  for (int ib = 0; ib < nall_body; ++ib) {
    Body &b = body[ib];
    const double *move = late_move[ib];
    double dq[4];
    MathExtra::vecquat(const_cast<double *>(move + LATE_ANGULAR), b.quat, dq);
    for (int k = 0; k < 4; ++k) b.quat[k] += 0.5 * dq[k];
    MathExtra::qnormalize(b.quat);
    MathExtra::q_to_exyz(b.quat, b.ex_space, b.ey_space, b.ez_space);
    for (int k = 0; k < 3; ++k) b.xcm[k] += move[LATE_LINEAR + k];
    MathExtra::matvec(b.ex_space, b.ey_space, b.ez_space, b.xgc_body, b.xgc);
    MathExtra::add3(b.xgc, b.xcm, b.xgc);
  }
  // Positions from the moved bodies; velocities as the base class's set_v will set them. No
  // virial: the move is no force.
  const int virial_flag = evflag;
  evflag = 0;
  set_xv();
  evflag = virial_flag;
}

void FixRigidRod::grow_arrays(int nmax)
{
  FixRigidSmall::grow_arrays(nmax);
  if (nmax <= nmax_atom) return;
  memory->grow(state, nmax, NSTATE, "rigid/rod:state");
  memory->grow(output, nmax, NOUT, "rigid/rod:output");
  memory->grow(late, nmax, NLATE, "rigid/rod:late");
  for (int i = nmax_atom; i < nmax; ++i) {
    state[i][STATE_ID] = 0.0;
    for (int k = 0; k < NOUT; ++k) output[i][k] = 0.0;
    for (int k = 0; k < NLATE; ++k) late[i][k] = 0.0;
  }
  nmax_atom = nmax;
  array_atom = output;
}

// Our own passes: per-atom body state forward; per-body rows (polar sums, late moves) the base
// class's way, through the atoms that own a body (bodyown): sums back to the owner, the owner's
// values forward to the ghost copies.
double **FixRigidRod::body_rows(int &width) const
{
  if (rod_comm == RodComm::POLAR_SUM) {
    width = NSUM;
    return polar_sum;
  }
  width = NLATE;
  return late_move;
}

int FixRigidRod::pack_forward_comm(int n, int *list, double *buf, int pbc_flag, int *pbc)
{
  int m = 0;
  if (rod_comm == RodComm::STATE) {
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < NSTATE; ++k) buf[m++] = state[list[i]][k];
  } else if (rod_comm == RodComm::LATE_MOVE) {
    int width;
    double **rows = body_rows(width);
    for (int i = 0; i < n; ++i) {
      if (bodyown[list[i]] < 0) continue;
      for (int k = 0; k < width; ++k) buf[m++] = rows[bodyown[list[i]]][k];
    }
  } else {
    return FixRigidSmall::pack_forward_comm(n, list, buf, pbc_flag, pbc);
  }
  return m;
}

void FixRigidRod::unpack_forward_comm(int n, int first, double *buf)
{
  int m = 0;
  if (rod_comm == RodComm::STATE) {
    for (int i = first; i < first + n; ++i)
      for (int k = 0; k < NSTATE; ++k) state[i][k] = buf[m++];
  } else if (rod_comm == RodComm::LATE_MOVE) {
    int width;
    double **rows = body_rows(width);
    for (int i = first; i < first + n; ++i) {
      if (bodyown[i] < 0) continue;
      for (int k = 0; k < width; ++k) rows[bodyown[i]][k] = buf[m++];
    }
  } else {
    FixRigidSmall::unpack_forward_comm(n, first, buf);
  }
}

int FixRigidRod::pack_reverse_comm(int n, int first, double *buf)
{
  if (rod_comm != RodComm::POLAR_SUM && rod_comm != RodComm::LATE_MOVE)
    return FixRigidSmall::pack_reverse_comm(n, first, buf);
  int width, m = 0;
  double **rows = body_rows(width);
  for (int i = first; i < first + n; ++i) {
    if (bodyown[i] < 0) continue;
    for (int k = 0; k < width; ++k) buf[m++] = rows[bodyown[i]][k];
  }
  return m;
}

void FixRigidRod::unpack_reverse_comm(int n, int *list, double *buf)
{
  if (rod_comm != RodComm::POLAR_SUM && rod_comm != RodComm::LATE_MOVE)
    return FixRigidSmall::unpack_reverse_comm(n, list, buf);
  int width, m = 0;
  double **rows = body_rows(width);
  for (int i = 0; i < n; ++i) {
    const int j = list[i];
    if (bodyown[j] < 0) continue;
    for (int k = 0; k < width; ++k) rows[bodyown[j]][k] += buf[m++];
  }
}

void *FixRigidRod::extract(const char *name, int &dim)
{
  if (strcmp(name, "polar") == 0) {    // the per-atom output, the polar axis first
    dim = EXTRACT_ARRAY;
    return output;
  }
  return FixRigidSmall::extract(name, dim);
}

double FixRigidRod::memory_usage()
{
  return FixRigidSmall::memory_usage() + (double) nmax_atom * (NSTATE + NOUT + NLATE) * sizeof(double) +
      (double) nmax_late_body * NLATE * sizeof(double);
}
