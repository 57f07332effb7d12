// The dense bead monolayer gives the same mean kinetic energy on 1, 2 and 4 ranks (this file
// also runs under mpirun -np 2 and -np 4): rank 0 runs the serial reference on its own.
#include "beads_deck.h"

#include "comm.h"

#include <cmath>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

namespace {

constexpr int kWarmup = 5000;     // steps (10 vibration periods)
constexpr int kChunks = 20;
constexpr int kChunk = 1000;      // steps per block average (2 periods)

struct MeanAndError {
  double mean = 0, error = 0;
};

// Block averages of the kinetic energy of the deck run by the LAMMPS instance `lmp`.
MeanAndError mean_kinetic_energy(void *lmp)
{
  lammps_commands_string(lmp, "variable steps index 0\n"
                              "include " ACTIVEGRAIN_SOURCE_DIR "/examples/beads-vibrated/in.beads-vibrated\n"
                              "thermo 0\n");
  lammps_command(lmp, fmt::format("run {} post no", kWarmup).c_str());
  lammps_command(lmp, fmt::format("fix keavg all ave/time 10 {} {} c_ke", kChunk / 10, kChunk).c_str());
  std::vector<double> blocks;
  for (int k = 0; k < kChunks; ++k) {
    lammps_command(lmp, fmt::format("run {} post no", kChunk).c_str());
    lammps_command(lmp, "variable agtest_ke equal f_keavg");
    auto *p = (double *) lammps_extract_variable(lmp, "agtest_ke", nullptr);
    blocks.push_back(*p);
    lammps_free(p);
  }
  MeanAndError r;
  for (double b : blocks) r.mean += b / kChunks;
  double var = 0;
  for (double b : blocks) var += (b - r.mean) * (b - r.mean) / (kChunks - 1);
  r.error = std::sqrt(var / kChunks);
  return r;
}

}    // namespace

TEST_F(BeadMonolayer, SameMeanKineticEnergyOnAnyNumberOfRanks)
{
  int me = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  const std::vector<double> reference = serial_reference(2, [](LAMMPS_NS::LAMMPS *serial) {
    const MeanAndError r = mean_kinetic_energy(serial);
    EXPECT_FALSE(lammps_has_error(serial));
    return std::vector<double>{r.mean, r.error};
  });

  const MeanAndError parallel = mean_kinetic_energy(lmp);
  ASSERT_FALSE(lammps_has_error(lmp));
  ASSERT_GT(reference[0], 0.0);
  // Within four combined standard errors, or 0.5 per cent where the blocks hardly fluctuate.
  const double allowed = 4.0 * std::hypot(reference[1], parallel.error) + 5e-3 * reference[0];
  if (me == 0)
    std::cout << "mean kinetic energy: serial " << reference[0] << " +- " << reference[1] << ", "
              << "parallel " << parallel.mean << " +- " << parallel.error << "\n";
  EXPECT_NEAR(parallel.mean, reference[0], allowed)
      << "serial " << reference[0] << " +- " << reference[1] << ", parallel " << parallel.mean
      << " +- " << parallel.error;
}

TEST_F(BeadMonolayer, RunBoundariesAndRestartsContinueTheRun)
{
  // A run split in two, or interrupted by write_restart/read_restart, continues like the
  // uninterrupted one: the half of the last contact impulse still due is stored with the atoms.
  // The split is put on a step with contacts.
  command("atom_modify map array");
  load_deck();
  command("run 2000 post no");
  int split = 2000;
  for (double contacts = 0; contacts == 0; ++split) {
    command("run 1 post no");
    contacts = solver_output(LAMMPS_NS::PairGranImpulse::CONTACTS);
    ASSERT_LT(split, 3000);
  }
  // The kinetic energy and the heights of a few beads after the continuation.
  auto probe = [&]() { return std::make_pair(value("c_ke"), value("z[7]+z[100]+z[250]")); };
  auto expect_same = [&](const std::pair<double, double> &a, const std::pair<double, double> &b,
                         double tolerance, const std::string &what) {
    EXPECT_NEAR(a.first, b.first, tolerance * b.first) << what;
    EXPECT_NEAR(a.second, b.second, tolerance * 1e-3) << what;
  };

  auto fresh = [&]() {
    TearDown();
    SetUp();
    command("atom_modify map array");
  };
  fresh();
  load_deck();
  command(fmt::format("run {} post no", split + 600));
  const auto continuous = probe();

  fresh();
  load_deck();
  command(fmt::format("run {} post no\nwrite_restart beads-restart-test.bin\nrun 600 post no", split));
  expect_same(probe(), continuous, 1e-12, fmt::format("run split at step {}", split));

  fresh();
  command("read_restart beads-restart-test.bin\n"
          "comm_modify vel yes\n"
          "neighbor 1.0e-4 bin\n"
          "neigh_modify delay 0 every 1 check yes\n"
          "fix plates all wall/impulse zlo 0.0 gap 1.12e-3 vibrate 4.0e-5 200.0 0.0 e 0.3 mu 0.01\n"
          "fix gravity all gravity 9.81 vector 0 0 -1\n"
          "fix integrate all nve/sphere\n"
          "timestep 1.0e-5\n"
          "compute ke all ke\n"
          "thermo_style custom step c_ke\n"
          "run 600 post no");
  expect_same(probe(), continuous, 1e-9, fmt::format("restarted at step {}", split));
}

TEST_F(BeadMonolayer, NewtonOffAndOnGiveTheSameCollisionAcrossRanksAndPeriodicBoundaries)
{
  // Two beads collide across the periodic x boundary (and, on several ranks, across
  // sub-domains): exact restitution and momentum with newton on and off.
  for (const char *newton : {"on", "off"}) {
    TearDown();
    SetUp();
    command(fmt::format("newton {}", newton));
    command("units si\natom_style sphere\natom_modify map array\nboundary p p f\n"
            "region box block 0 0.01 0 0.01 0 0.002\ncreate_box 1 box\ncomm_modify vel yes\n"
            "neighbor 0.0002 bin\ntimestep 1e-5\n"
            "create_atoms 1 single 0.0092 0.005 0.001\ncreate_atoms 1 single 0.0012 0.005 0.001\n"
            "set atom * diameter 0.001\nset atom * density 2700\n"
            "velocity all set 0 0 0\nset atom 1 vx 0.1\nset atom 2 vx -0.05\n"
            "pair_style gran/impulse\npair_coeff * * 0.3 0.05\nfix nve all nve/sphere\n"
            "run 3000");
    EXPECT_NEAR(value("vx[2]-vx[1]"), 0.3 * 0.15, 1e-12) << "newton " << newton;
    EXPECT_NEAR(value("vx[1]+vx[2]"), 0.05, 1e-12) << "newton " << newton;
  }
}

namespace {
// Comm's largest reverse communication, in datums per atom (protected: read through a member
// pointer of a derived class).
struct CommReverseSize : LAMMPS_NS::Comm {
  static int of(LAMMPS_NS::Comm *comm) { return comm->*(&CommReverseSize::maxreverse); }
};
}    // namespace

TEST_F(BeadMonolayer, NewtonOffSizesReverseCommForTheContactSums)
{
  // The contact sums of ghost atoms (force, torque, late impulse and virial) travel to their
  // owners with newton off too. Comm sizes its buffers for that from the pair style's
  // comm_reverse_off: without it, they overflowed on several ranks (the 2-rank pour of
  // examples/lammps-granular then hung in the next forward communication).
  command("newton off\nunits si\natom_style sphere\nboundary p p f\n"
          "region box block 0 0.01 0 0.01 0 0.002\ncreate_box 1 box\ncomm_modify vel yes\n"
          "create_atoms 1 single 0.005 0.005 0.001\nset atom * diameter 0.001\n"
          "pair_style gran/impulse\npair_coeff * * 0.3 0.05\nfix nve all nve/sphere\nrun 0 post no");
  EXPECT_GE(CommReverseSize::of(lmp->comm), lmp->force->pair->comm_reverse);
}
