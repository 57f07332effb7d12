// fix rigid/rod on 1, 2 and 4 ranks with a rod straddling periodic and sub-domain boundaries:
// the body state it gives contact styles (owned and ghost atoms) is the rod's, with the solid's
// mass and inertia; a free rod (no walls, no gravity, its own spheres never collide) keeps its linear and angular momentum; the polar axis points from
// the tail atom to the nose atom and survives a restart; every atom of the rod outputs its body ID.
#include "lammps_fixture.h"
#include "rod_deck.h"

#include "ag_rod_geometry.h"
#include "atom.h"
#include "domain.h"
#include "fix.h"
#include "modify.h"
#include "rigid_body_provider.h"

#include <algorithm>
#include <cmath>
#include <vector>

using namespace rod_deck;
using ActiveGrain::Mat3;
using ActiveGrain::RigidBodyState;
using ActiveGrain::Vec3;

namespace {
const Vec3 V0(0.01, -0.02, 0.005);        // m/s
const Vec3 OMEGA0(30.0, -20.0, 50.0);     // rad/s
}    // namespace

class RigidRodTest : public LammpsTest {
 protected:
  const std::string file = "test_mpi_rigid_rod.mol";

  // One rod across the periodic x boundary (and the sub-domain boundaries in x, y and z),
  // moving with V0 and spinning with OMEGA0 about its COM, no gravity, no contacts.
  void make_rod(double nose = NOSE, double tail = TAIL)
  {
    command(box() + rod_template(file, tail, nose) +
            "create_atoms 0 single 5.9e-3 1e-4 -1e-4 mol rod 4321 units box\n"
            "fix r all rigid/rod molecule mol rod\n"
            "pair_style gran/impulse\npair_coeff * * 0.3 0.05\n"
            "comm_modify vel yes cutoff 5e-3\nneighbor 1e-4 bin\n"
            "compute t all temp/sphere\nthermo_modify temp t\n"
            "compute c all com\n"
            "compute u all property/atom xu yu zu\n"
            "variable cx equal c_c[1]\nvariable cy equal c_c[2]\nvariable cz equal c_c[3]\n"
            "variable vx atom " + std::to_string(V0.x) + "+(" + std::to_string(OMEGA0.y) + ")*(c_u[3]-v_cz)-(" +
            std::to_string(OMEGA0.z) + ")*(c_u[2]-v_cy)\n"
            "variable vy atom " + std::to_string(V0.y) + "+(" + std::to_string(OMEGA0.z) + ")*(c_u[1]-v_cx)-(" +
            std::to_string(OMEGA0.x) + ")*(c_u[3]-v_cz)\n"
            "variable vz atom " + std::to_string(V0.z) + "+(" + std::to_string(OMEGA0.x) + ")*(c_u[2]-v_cy)-(" +
            std::to_string(OMEGA0.y) + ")*(c_u[1]-v_cx)\n"
            "run 0 post no\n"
            "velocity all set v_vx v_vy v_vz\n"
            // Collinear atoms carry the spin about the rod axis only through their own omega.
            "set group all omega " + std::to_string(OMEGA0.x) + " " + std::to_string(OMEGA0.y) + " " +
            std::to_string(OMEGA0.z) + "\n"
            "timestep 1e-5\n"
            "run 0 post no");
  }

  LAMMPS_NS::RigidBodyProvider *provider()
  {
    return dynamic_cast<LAMMPS_NS::RigidBodyProvider *>(lmp->modify->get_fix_by_id("r"));
  }

  // Unwrapped positions of all atoms, by tag, on every rank.
  std::vector<Vec3> positions()
  {
    const int n = static_cast<int>(lmp->atom->natoms);
    std::vector<double> x(3 * n);
    lammps_gather_atoms(lmp, (char *) "x", 1, 3, x.data());
    std::vector<int> image(n);
    lammps_gather_atoms(lmp, (char *) "image", 0, 1, image.data());
    std::vector<Vec3> out;
    for (int i = 0; i < n; ++i) {
      double u[3];
      LAMMPS_NS::imageint img = image[i];
      lmp->domain->unmap(&x[3 * i], img, u);
      out.emplace_back(u);
    }
    return out;
  }

  Vec3 com() { return {value("v_cx"), value("v_cy"), value("v_cz")}; }

  // The integrator's own state of the one rod: v and angular momentum, on every rank.
  std::vector<double> exact_state()
  {
    if (!lmp->modify->get_compute_by_id("rl")) command("compute rl all rigid/local r vx vy vz angmomx angmomy angmomz");
    double local[7] = {0, 0, 0, 0, 0, 0, 0}, all[7];
    auto **rows = (double **) lammps_extract_compute(lmp, "rl", LMP_STYLE_LOCAL, LMP_TYPE_ARRAY);
    auto *nrows = (int *) lammps_extract_compute(lmp, "rl", LMP_STYLE_LOCAL, LMP_SIZE_ROWS);
    if (nrows && *nrows == 1) {
      for (int k = 0; k < 6; ++k) local[k] = rows[0][k];
      local[6] = 1.0;
    }
    MPI_Allreduce(local, all, 7, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    EXPECT_EQ(all[6], 1.0);
    return std::vector<double>(all, all + 6);
  }

  // Every atom this rank holds, owned and ghost, that belongs to the rod.
  std::vector<std::pair<int, RigidBodyState>> rod_atoms()
  {
    std::vector<std::pair<int, RigidBodyState>> out;
    auto *p = provider();
    const int nall = lmp->atom->nlocal + lmp->atom->nghost;
    for (int i = 0; i < nall; ++i) {
      RigidBodyState b;
      LAMMPS_NS::tagint id = 0;
      if (p->body_of_atom(i, b, id)) out.emplace_back(i, b);
    }
    return out;
  }
};

TEST_F(RigidRodTest, ProviderGivesSolidRodStateToOwnedAndGhostAtoms)
{
  make_rod();
  const auto g = ActiveGrain::rod_solid({LENGTH, TAIL, NOSE, SPHERES, DENSITY});
  const auto x = positions();
  const Vec3 polar = (x[SPHERES - 1] - x[0]) / ActiveGrain::norm(x[SPHERES - 1] - x[0]);
  const Vec3 xcm = com();
  // The solid's COM lies g.com from the tail face along the polar axis.
  const Vec3 tail_face = x[0] - polar * ActiveGrain::make_rod_geometry({LENGTH, TAIL, NOSE, SPHERES, DENSITY}).spheres[0].x;
  EXPECT_NEAR(ActiveGrain::norm(xcm - (tail_face + polar * g.com)), 0.0, 1e-9);

  Vec3 across = ActiveGrain::cross(polar, Vec3(0, 0, 1));
  across = across / ActiveGrain::norm(across);
  int nghost_seen = 0;
  LAMMPS_NS::tagint first_id = -1;
  for (auto &[i, b] : rod_atoms()) {
    if (i >= lmp->atom->nlocal) ++nghost_seen;
    LAMMPS_NS::tagint id = 0;
    RigidBodyState again;
    provider()->body_of_atom(i, again, id);
    if (first_id < 0) first_id = id;
    EXPECT_EQ(id, first_id);
    EXPECT_NEAR(b.inv_mass * g.mass, 1.0, 1e-9);
    // COM of this image: the atom's own position minus its offset, i.e. within a rod length of
    // the atom, and equal to the true COM up to a whole box image.
    const Vec3 xi(lmp->atom->x[i]);
    EXPECT_LT(ActiveGrain::norm(b.com - xi), LENGTH);
    double com[3], true_com[3], true_com_image[3];
    b.com.store(com);
    xcm.store(true_com);
    lmp->domain->closest_image(com, true_com, true_com_image);
    EXPECT_NEAR(ActiveGrain::norm(b.com - Vec3(true_com_image)), 0.0, 1e-12);
    // World inverse inertia: 1/I_axial along the polar axis, 1/I_transverse across it.
    EXPECT_NEAR(ActiveGrain::norm(b.inv_inertia * polar - polar / g.inertia_axial) * g.inertia_axial, 0.0, 1e-8);
    EXPECT_NEAR(ActiveGrain::norm(b.inv_inertia * across - across / g.inertia_transverse) * g.inertia_transverse, 0.0, 1e-8);
    EXPECT_NEAR(ActiveGrain::norm(b.v - V0), 0.0, 1e-12);
    EXPECT_NEAR(ActiveGrain::norm(b.omega - OMEGA0), 0.0, 1e-8);
  }
  // Ghost images exist (periodic and/or sub-domain), and every rank saw the whole rod.
  EXPECT_GT(nghost_seen, 0);
  int seen_rank = static_cast<int>(rod_atoms().size()), min_seen = 0;
  MPI_Allreduce(&seen_rank, &min_seen, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  int nprocs = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &nprocs);
  if (nprocs <= 2) EXPECT_GE(min_seen, SPHERES);
}

TEST_F(RigidRodTest, PolarAxisPointsTailToNose)
{
  make_rod();
  const auto x = positions();
  const Vec3 polar = (x[SPHERES - 1] - x[0]) / ActiveGrain::norm(x[SPHERES - 1] - x[0]);
  int dim = 0;
  auto **p = (double **) lmp->modify->get_fix_by_id("r")->extract("polar", dim);
  ASSERT_EQ(dim, 2);
  for (int i = 0; i < lmp->atom->nlocal; ++i) EXPECT_NEAR(ActiveGrain::norm(Vec3(p[i]) - polar), 0.0, 1e-12);
  // Per-atom output (dumps, computes) is the same array.
  EXPECT_EQ(lmp->modify->get_fix_by_id("r")->array_atom, p);
}

TEST_F(RigidRodTest, PerAtomBodyIdIsTheRodsOnEveryRank)
{
  make_rod();
  auto *fix = lmp->modify->get_fix_by_id("r");
  ASSERT_EQ(fix->size_peratom_cols, 4);
  double body_min = 1e300, body_max = -1e300;
  int rod_atoms_here = 0;
  for (int i = 0; i < lmp->atom->nlocal; ++i) {
    const double id = fix->array_atom[i][3];
    RigidBodyState b;
    LAMMPS_NS::tagint body_id = 0;
    ASSERT_TRUE(provider()->body_of_atom(i, b, body_id));
    EXPECT_EQ(id, static_cast<double>(body_id));
    body_min = std::min(body_min, id);
    body_max = std::max(body_max, id);
    ++rod_atoms_here;
  }
  double all_min = 0, all_max = 0;
  int all_rod_atoms = 0;
  MPI_Allreduce(&body_min, &all_min, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(&body_max, &all_max, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(&rod_atoms_here, &all_rod_atoms, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  EXPECT_EQ(all_rod_atoms, SPHERES);
  EXPECT_GE(all_min, 1.0);    // one body ID, an atom ID of the rod, on every rank
  EXPECT_EQ(all_min, all_max);
}

TEST_F(RigidRodTest, ReversedTaperKeepsTailToNoseAxis)
{
  // Tail is still the first atom, now the narrow one: the polar axis follows the atom order.
  make_rod(TAIL, NOSE);
  const auto x = positions();
  const Vec3 polar = (x[SPHERES - 1] - x[0]) / ActiveGrain::norm(x[SPHERES - 1] - x[0]);
  int dim = 0;
  auto **p = (double **) lmp->modify->get_fix_by_id("r")->extract("polar", dim);
  for (int i = 0; i < lmp->atom->nlocal; ++i) EXPECT_NEAR(ActiveGrain::norm(Vec3(p[i]) - polar), 0.0, 1e-12);
}

TEST_F(RigidRodTest, FreeRodKeepsLinearAndAngularMomentum)
{
  make_rod();
  const auto g = ActiveGrain::rod_solid({LENGTH, TAIL, NOSE, SPHERES, DENSITY});
  auto state_of_rod = [&]() {
    auto atoms = rod_atoms();
    double local[7] = {0, 0, 0, 0, 0, 0, 0}, all[7];
    if (!atoms.empty()) {
      const auto &b = atoms.front().second;
      const Vec3 L = b.inv_inertia.inverse() * b.omega;
      const double s[7] = {b.v.x, b.v.y, b.v.z, L.x, L.y, L.z, 1.0};
      for (int k = 0; k < 7; ++k) local[k] = s[k];
    }
    MPI_Allreduce(local, all, 7, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    for (int k = 0; k < 6; ++k) all[k] /= all[6];
    return std::vector<double>(all, all + 6);
  };
  // Exact conservation by the integrator (torque-free rigid body).
  command("compute rl all rigid/local r vx vy vz angmomx angmomy angmomz\nrun 0 post no");
  const auto before = exact_state();
  const auto provided_before = state_of_rod();
  const Vec3 x0 = com();
  command("run 2000 post no");    // 0.02 s: the rod turns by about 1 rad and crosses the boundary
  const auto after = exact_state();
  const auto provided_after = state_of_rod();
  const double Lnorm = std::sqrt(before[3] * before[3] + before[4] * before[4] + before[5] * before[5]);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(after[k], before[k], 1e-12) << "v " << k;
  for (int k = 3; k < 6; ++k) EXPECT_NEAR(after[k] / Lnorm, before[k] / Lnorm, 1e-10) << "L " << k;
  // What contact styles see: the same v; I omega from the half-step omega matches L to O(omega dt).
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(provided_after[k], before[k], 1e-12) << "provided v " << k;
  for (int k = 3; k < 6; ++k) {
    EXPECT_NEAR(provided_before[k] / Lnorm, before[k] / Lnorm, 1e-3) << "provided L " << k;
    EXPECT_NEAR(provided_after[k] / Lnorm, before[k] / Lnorm, 1e-3) << "provided L " << k;
  }
  // The COM moved ballistically.
  EXPECT_NEAR(ActiveGrain::norm(com() - (x0 + V0 * 0.02)), 0.0, 1e-10);
}

TEST_F(RigidRodTest, RestartKeepsBodyState)
{
  make_rod();
  command("run 500 post no");
  const auto x_before = positions();
  const Vec3 polar = (x_before[SPHERES - 1] - x_before[0]) / ActiveGrain::norm(x_before[SPHERES - 1] - x_before[0]);
  command("compute rl all rigid/local r vx vy vz angmomx angmomy angmomz\nrun 0 post no");
  const auto before = exact_state();
  command("write_restart test_mpi_rigid_rod.restart\nclear\n"
          "plugin load " ACTIVEGRAIN_PLUGIN_FILE "\n"
          "atom_modify map array\n"
          "read_restart test_mpi_rigid_rod.restart\n"
          "fix molecule_ids all property/atom mol ghost yes\n" + rod_template(file) +
          "fix r all rigid/rod molecule mol rod\n"
          "pair_style gran/impulse\npair_coeff * * 0.3 0.05\n"
          "comm_modify vel yes cutoff 5e-3\nneighbor 1e-4 bin\n"
          "compute t all temp/sphere\nthermo_modify temp t\ncompute c all com\n"
          "run 0 post no");
  command("compute rl all rigid/local r vx vy vz angmomx angmomy angmomz\nrun 0 post no");
  const auto after = exact_state();
  const double Lnorm = std::sqrt(before[3] * before[3] + before[4] * before[4] + before[5] * before[5]);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(after[k], before[k], 1e-12) << "v " << k;
  for (int k = 3; k < 6; ++k) EXPECT_NEAR(after[k] / Lnorm, before[k] / Lnorm, 1e-10) << "L " << k;
  int dim = 0;
  auto **p = (double **) lmp->modify->get_fix_by_id("r")->extract("polar", dim);
  for (int i = 0; i < lmp->atom->nlocal; ++i) EXPECT_NEAR(ActiveGrain::norm(Vec3(p[i]) - polar), 0.0, 1e-12);
}

// An untapered rod falls flat onto a still plate (e = 0.5, no gravity): all its spheres touch
// in the same step, so it must leave at e * 0.05 m/s without spinning. With `processors * 1 1`
// the rod is split between ranks on 2 and 4 ranks. KNOWN FAILURE, disabled: pair gran/impulse
// solves each rank's contacts separately; on 2 ranks the rod leaves at 0.092 m/s spinning at
// 14.7 rad/s (kinetic energy gained). Passes on 1 rank. Enable when contacts of one body are
// solved together.
TEST_F(RigidRodTest, FlatRodSplitBetweenRanksBouncesAsOnOneRank)
{
  command("units si\natom_style sphere\natom_modify map array\nboundary p p f\nprocessors * 1 1\n"
          "fix molecule_ids all property/atom mol ghost yes\n"
          "region box block 0 40e-3 0 40e-3 -1e-3 3e-3\ncreate_box 3 box\n" +
          rod_deck::rod_template(file, 0.9e-3, 0.9e-3) +
          "create_atoms 0 single 20e-3 10e-3 0.5e-3 mol rod 1 units box rotate 0 0 0 1\n"
          "neigh_modify exclude molecule/intra all\n"
          "pair_style gran/impulse\npair_coeff * * 0.3 0.05\n"
          "fix r all rigid/rod molecule mol rod\n"
          "fix plate all wall/impulse zlo 0.0 e 0.5 mu 0.03\n"
          "comm_modify vel yes cutoff 6e-3\n"
          "compute t all temp/sphere\nthermo_modify temp t\n"
          "velocity all set 0 0 -0.05\ntimestep 1e-6\nrun 2000 post no");
  EXPECT_NEAR(value("vcm(all,z)"), 0.025, 1e-4);
  EXPECT_NEAR(value("omega(all,y)"), 0.0, 1e-2);
}
