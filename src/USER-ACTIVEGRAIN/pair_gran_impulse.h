/* -*- c++ -*- ----------------------------------------------------------
   ActiveGrain: pair_style gran/impulse, frictional restitutive impulse contacts.
------------------------------------------------------------------------- */
#ifdef PAIR_CLASS
// clang-format off
PairStyle(gran/impulse,PairGranImpulse);
// clang-format on
#else

#ifndef LMP_PAIR_GRAN_IMPULSE_H
#define LMP_PAIR_GRAN_IMPULSE_H

#include "ag_contact_solver.h"
#include "ag_hash.h"
#include "contact_ranks.h"
#include "impulse_wall.h"
#include "near_pairs.h"
#include "pair.h"

#include <cstdint>
#include <tuple>
#include <vector>

namespace LAMMPS_NS {

class RigidBodyProvider;

class PairGranImpulse : public Pair {
 public:
  PairGranImpulse(class LAMMPS *);
  ~PairGranImpulse() override;

  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void reset_dt() override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  void *extract(const char *, int &) override;
  double memory_usage() override;

  // Global outputs, pvector (compute pair gran/impulse, which sums them over ranks: a maximum is
  // held by rank 0, the other ranks hold 0; a sum is each rank's part). New outputs are appended
  // before NUM_OUTPUTS; existing indices never change.
  enum Output {
    CONTACTS = 0,       // contacts solved in the last step, all ranks
    SUBSTEPS,           // most sub-steps a compliant impact needed in the last step
    SHORTFALL,          // largest separation velocity an overlap still lacks after the last
                        // step, relative to its minimum separation velocity
    LARGEST_OVERLAP,    // largest overlap of a contact since the run's setup (length)
    CAPPED_STEPS,       // steps since the run's setup in which an impact hit the sub-step cap
    // Energies of the last step's solve (energy units), each contact counted on the rank that
    // solved it (docs/pair_gran_impulse.rst: energy balance):
    DISSIPATED_PAIR,    // dissipated at particle-particle contacts
    DISSIPATED_WALL,    // dissipated at wall contacts
    OVERLAP_WORK,       // added by the overlap correction (pushes apart of overlapping contacts)
    WALL_WORK,          // work of the walls on the particles, sum of J . v_wall
    NUM_OUTPUTS
  };
  // Order in which contacts are visited: a hash of the step and the contact's identity (default),
  // or their identity (wall, surface, atom tags) ascending or descending.
  enum class Order { SHUFFLE, TAG, REVERSE };

 private:
  // One contact as LAMMPS sees it: which atoms get the impulse and where.
  struct AtomContact {
    int atom1;                 // -1 for a wall
    int atom2;
    ImpulseWall *wall;         // the wall fix for wall contacts
    int surface;
    ActiveGrain::Vec3 point;
    double approach;           // normal approach speed before the solve (>= 0)
    double time_to_contact;    // after the step's start at which the gap closes (0: overlap)
    ActiveGrain::Vec3 velocity_before;    // relative velocity at the contact before the solve
    ActiveGrain::Vec3 wall_velocity;      // a wall's velocity when the contact closes
  };
  // Who touches whom, the same on every rank: wall index (-1 for a pair), surface, atom tags.
  using ContactIdentity = std::tuple<int, int, tagint, tagint>;
  // A contact found this step, before it goes to the solver. Contacts are solved in an order
  // given by their identity (and, shuffled, the step), not by the order ranks find them, so that
  // a body solved on one rank sees the same order on any number of ranks.
  struct FoundContact {
    std::uint64_t shuffle;
    ContactIdentity identity;
    int body1, body2;
    ActiveGrain::Vec3 r1, r2, n;
    ActiveGrain::ContactMaterial material;
    double min_separation;
    ActiveGrain::Vec3 gain;
    AtomContact atoms;
  };
  // Where a found contact goes in the order (shuffle 0 unless shuffled).
  struct SortKey {
    std::uint64_t shuffle;
    ContactIdentity identity;
    int index;    // in found
  };
  // Columns of the pending store (see pending): the force and torque of the step's contacts, the
  // time step they belong to (their impulse is force times it: a time step change keeps the
  // impulse), and the step.
  enum PendingColumn { PENDING_FORCE = 0, PENDING_TORQUE = 3, PENDING_DT = 6, PENDING_STEP, NUM_PENDING };

  void allocate();
  void refuse_unsupported();
  void grow_buffers();
  int body_of_atom(int i);
  ActiveGrain::Vec3 lever_arm(int i, int body, const ActiveGrain::Vec3 &point) const;
  void add_contact(int body1, int body2, const AtomContact &atoms, const ActiveGrain::Vec3 &n,
                   double gap, const ActiveGrain::ContactMaterial &material,
                   const ActiveGrain::Vec3 &r1, const ActiveGrain::Vec3 &r2,
                   const ActiveGrain::Vec3 &atom_acceleration,
                   const ActiveGrain::Vec3 &wall_acceleration = ActiveGrain::Vec3());
  ActiveGrain::Vec3 gravity_of_atom(int i) const;
  ActiveGrain::Vec3 atom_velocity_at(int i, const ActiveGrain::Vec3 &point) const;
  bool stays_open(double gap, const ActiveGrain::Vec3 &u, const ActiveGrain::Vec3 &n) const;
  void gather_pair_contacts();
  void gather_wall_contacts();
  void add_found_contacts();
  void distribute_impulses();
  void apply_contact_forces(bool store);
  void move_late_atoms();
  void restore_pending_forces();
  void record_solve(const ActiveGrain::ContactSolver::Result &result);
  void tally_energy();
  void tally_virial();
  void restore_virial();

  // settings
  ActiveGrain::ContactSolver::Settings solver_settings;
  double beta;         // overlaps leave at >= beta * overlap / dt
  Order order;

  double **restitution, **friction;
  double *maxrad;    // largest radius per type, present or to be inserted (neighbor cutoff)
  int freeze_groupbit;    // atoms held by fix freeze: bodies of infinite mass

  // The contact force of the last step also acts in the next initial_integrate. Across a run
  // boundary (or a restart) setup() must restore it instead of solving anew; it travels with
  // the atoms as force, torque, their time step and the step they belong to (PendingColumn).
  class FixStoreAtom *pending;
  double force_dt;    // time step of the contact forces now in atom->f (0: none)

  std::vector<RigidBodyProvider *> providers;
  std::vector<ImpulseWall *> walls;
  std::vector<class Fix *> gravities;    // fix gravity: accelerations a contact gains before it closes
  // This step's acceleration (velocity units) and group of each fix gravity.
  std::vector<std::pair<int, ActiveGrain::Vec3>> gravity_now;

  ActiveGrain::ContactSolver solver;
  std::vector<FoundContact> found;
  std::vector<SortKey> sort_keys;
  std::vector<AtomContact> atom_contacts;    // those of the solver's contacts, in its order
  std::vector<ImpulseWall::Contact> wall_scratch;
  ActiveGrain::KeyIndex body_index;    // 2*tag (bead) or 2*body_id+1 (rigid body)
  std::vector<int> atom_body;                     // solver body of each atom, -1 before lookup
  std::vector<double> spin_speed;                 // |omega| radius of each atom, this step

  bool ghost_pairs;       // rigid bodies exist: a full neighbor list with ghosts
  ContactRanks ranks;     // which rank solves which contact
  NearPairs near;         // the pairs of the neighbor list that may touch soon

  // Per owned and ghost atom, summed onto owners by reverse comm: the contact force and torque,
  // and the late impulse and its moment about the atom (each impulse times the time after the
  // step's start at which its contact closed: the atom then moves that impulse / mass less).
  // With per-atom virial (compute stress/atom), also each atom's share of its contacts' virial.
  // (A virial has NUM_VIRIAL components, in LAMMPS's order xx, yy, zz, xy, xz, yz.)
  static constexpr int NUM_VIRIAL = 6;
  enum ContactColumn { FORCE = 0, TORQUE = 3, LATE = 6, LATE_ANGULAR = 9, VIRIAL = 12, NUM_CONTACT_COLUMNS = 18 };
  int nmax;
  int reverse_columns;    // columns that travel in this step's reverse comm (VIRIAL or all)
  double **contact_sums;

  // This rank's atoms in this step: largest |v| + |omega| r (for the skin warning), and largest
  // excess of a radius over its type's neighbor-cutoff radius (an atom inserted by another means).
  double fastest, radius_excess;
  double fastest_near;    // largest |v| + |omega| r of owned and ghost atoms (NearPairs)
  double wall_speed;    // largest speed of a wall in this step (for the skin warning)
  // Global virial of the last step's contacts, and that step: a run that continues from it
  // shows it at its setup, as it shows that step's pending force.
  double last_virial[NUM_VIRIAL];
  bigint last_virial_step;
  bool skin_warned;    // the skin warning is given once per run

  // This rank's solve of the last step, and since the run's setup (reduced into pvector).
  double largest_overlap;
  bigint capped_steps;
  bigint next_cap_warning;    // capped_steps at which to warn next (10, 100, 1000, ...)
};

}    // namespace LAMMPS_NS

#endif
#endif
