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
#include "contact_assembly.h"
#include "contact_ranks.h"
#include "gran_impulse_settings.h"
#include "impulse_carry.h"
#include "impulse_delivery.h"
#include "island_exchange.h"
#include "near_pairs.h"
#include "pair.h"
#include "solve_diagnostics.h"
#include "solver_bodies.h"

#include <set>
#include <string>
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
    RESTING_SWEEPS,     // most sweeps a resting solve needed in the last step (keyword resting)
    NUM_OUTPUTS
  };

 private:
  void allocate();
  void find_fixes();
  void request_neighbors();
  void find_type_radii();
  void refuse_unsupported();
  void refuse_integrated_rod_atoms();
  void check_deck();
  bool warned_no_walls = false, warned_units = false;
  std::set<std::string> warned_inputs;    // warn_silent_inputs()'s warnings given
  void setup_step();
  void assemble();
  void solve();
  void deliver();
  void report(const SolveDiagnostics::Health &health, const SolveDiagnostics::Energies &energies);
  double largest_type_radius() const;
  double largest_acceleration() const;
  double largest_wall_acceleration() const;

  GranImpulseSettings style_settings;    // the keywords of pair_style
  PairContactModels models;    // per type pair
  double *maxrad;    // largest radius per type, present or to be inserted (neighbor cutoff)

  std::vector<RigidBodyProvider *> providers;
  std::vector<ImpulseWall *> walls;
  bool ghost_pairs;    // rigid bodies exist: a full neighbor list with ghosts

  ActiveGrain::ContactSolver solver;
  ContactRanks ranks;              // which rank solves which contact
  NearPairs near;                  // the pairs of the neighbor list that may touch soon
  SolverBodies bodies;             // the solver's bodies of this step's atoms
  ContactAssembly assembly;        // this step's contacts, in their order
  IslandExchange exchange;         // islands that cross ranks, solved whole
  ImpulseDelivery delivery;        // impulses to atoms: forces, late moves, virial
  ImpulseCarry carry;              // the half impulses still due across runs
  SolveDiagnostics diagnostics;    // outputs, errors and warnings of the solves
};

}    // namespace LAMMPS_NS

#endif
#endif
