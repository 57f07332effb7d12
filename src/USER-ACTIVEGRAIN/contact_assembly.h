// This step's contacts for pair gran/impulse, from LAMMPS's arrays to the contact solver: the
// near pairs and the wall fixes' contacts whose gaps close within the step (predictive contact),
// each with its bodies, lever arms and contact model, handed to the solver in an order given by the
// contacts' identity, and what each solver contact means for the atoms.
#pragma once

#include "ag_contact_prediction.h"
#include "ag_contact_solver.h"
#include "impulse_wall.h"
#include "pointers.h"

#include <cstdint>
#include <tuple>
#include <vector>

namespace LAMMPS_NS {

class ContactRanks;
class NearPairs;
class SolverBodies;

// Order in which contacts are visited: a hash of the step and the contact's identity (default),
// or their identity (wall, surface, atom tags) ascending or descending.
enum class ContactOrder { SHUFFLE, TAG, REVERSE };

class ContactAssembly : protected Pointers {
 public:
  // One contact as LAMMPS sees it: which atoms get the impulse and where.
  struct AtomContact {
    int atom1;                            // -1 for a wall
    int atom2;
    ImpulseWall *wall;                    // the wall fix for wall contacts
    int surface;
    ActiveGrain::Vec3 point;
    ActiveGrain::Vec3 velocity_before;    // relative velocity at the contact before the solve
    double approach;                      // normal approach speed when it closes (>= 0)
    ActiveGrain::Vec3 wall_velocity;      // a wall's velocity when the contact closes (0 for a pair)
  };
  // Who touches whom, the same on every rank: wall index (-1 for a pair), surface, atom tags.
  using ContactIdentity = std::tuple<int, int, tagint, tagint>;
  // Where a contact goes in the order: its shuffle (0 unless shuffled) and identity. Contacts are
  // solved in this order, not in the order ranks find them, so that a body sees the same order
  // on any number of ranks.
  struct OrderKey {
    std::uint64_t shuffle;
    ContactIdentity identity;
  };
  static bool precedes(const OrderKey &a, const OrderKey &b, ContactOrder order);

  // What the atoms did at the step's start: largest |v| + |omega| r of owned atoms and of owned
  // and ghost atoms, largest speed of a wall, largest excess of an owned atom's radius over its
  // type's neighbor-cutoff radius, and largest overlap of a contact.
  struct StepExtremes {
    double fastest = 0.0, fastest_near = 0.0, wall_speed = 0.0, radius_excess = 0.0, overlap = 0.0;
  };

  ContactAssembly(LAMMPS *lmp, ActiveGrain::ContactSolver &solver, SolverBodies &bodies,
                  const ContactRanks &ranks, NearPairs &near) :
      Pointers(lmp), solver(solver), bodies(bodies), ranks(ranks), near(near)
  {
  }

  // The pair style's settings and coefficients (per type pair), and the wall fixes.
  void init(double beta, double slop, ContactOrder order, const PairContactModels *models,
            const std::vector<ImpulseWall *> &walls);
  // Each atom's spin speed and this step's extremes; maxrad: the neighbor-cutoff radius per type.
  void scan_atoms(const double *maxrad);
  // The step's contacts, into the (cleared) solver in their order.
  void assemble(class NeighList *list);

  const AtomContact &atoms_of(int c) const { return atom_contacts[c]; }
  const OrderKey &order_key(int c) const { return order_keys[c]; }
  ContactOrder contact_order() const { return order; }
  const StepExtremes &extremes() const { return step; }
  double memory_usage() const;

 private:
  // A contact found this step, before it goes to the solver.
  struct FoundContact {
    std::uint64_t shuffle;
    ContactIdentity identity;
    int body1, body2;
    ActiveGrain::Vec3 r1, r2, n;
    ActiveGrain::ContactModel model;
    ActiveGrain::ContactPrediction prediction;
    AtomContact atoms;
  };
  struct SortKey {
    OrderKey key;
    int index;    // in found
  };

  void gather_pair_contacts(class NeighList *list);
  void gather_wall_contacts();
  void add_contact(int body1, int body2, const AtomContact &atoms, const ActiveGrain::Vec3 &n,
                   double gap, const ActiveGrain::ContactModel &model,
                   const ActiveGrain::Vec3 &r1, const ActiveGrain::Vec3 &r2,
                   const ActiveGrain::Vec3 &atom_acceleration,
                   const ActiveGrain::Vec3 &wall_acceleration = ActiveGrain::Vec3());
  ContactIdentity identity_of(const AtomContact &atoms) const;
  void add_found_contacts();

  ActiveGrain::ContactSolver &solver;
  SolverBodies &bodies;
  const ContactRanks &ranks;
  NearPairs &near;
  double beta = 0.0;    // overlaps leave at >= beta * (overlap - slop) / dt
  double slop = 0.0;
  ContactOrder order = ContactOrder::SHUFFLE;
  const PairContactModels *models = nullptr;    // per type pair
  std::vector<ImpulseWall *> walls;

  std::vector<double> spin_speed;    // |omega| radius of each atom, this step
  StepExtremes step;
  std::vector<FoundContact> found;
  std::vector<SortKey> sort_keys;
  std::vector<AtomContact> atom_contacts;    // those of the solver's contacts, in its order
  std::vector<OrderKey> order_keys;          // ... and their keys
  std::vector<ImpulseWall::Contact> wall_contacts;
};

}    // namespace LAMMPS_NS
