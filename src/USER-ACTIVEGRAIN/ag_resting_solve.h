// The resting contacts of an island (ag_contact_solver.h) solved together. No LAMMPS in here.
//
// A contact that approaches no faster than the velocity gravity or the plates give a body within
// a step (SolverSettings::resting_speed) is resting: whether it would bounce at e times that
// approach is below what the step resolves. The island's contacts are then one velocity-level
// complementarity problem, as Moreau-Jean time stepping poses it: after the step every contact
// separates at least at its target (0, or an overlap's minimum separation velocity) or carries a
// normal impulse >= 0 that makes it do exactly that, and its tangential impulse stops its slip
// within the Coulomb disc mu P_n, else lies on the disc's edge. It is solved by projected
// Gauss-Seidel sweeps on accumulated impulses (normal, over-relaxed, then friction, per contact),
// from zero: the plates' kicks change a packing's impulses from step to step, so that the last
// step's take as many sweeps, and a solve from the state alone lets restarts continue exactly
// and every rank count solve the same problem. The contacts are coloured so that no two of a colour share a movable
// body, in the order of their keys (SolverContact::key, from their identity): a sweep visits the
// colours in turn, and its result does not depend on the order in which the contacts came, bit
// for bit. Sweeps stop once none changes a contact's velocity by more than
// SolverSettings::resting_tolerance of the resting speed.
//
// With SolverSettings::resting_restitution a contact that approaches faster than its gain makes
// it (a collision, not a body settling under gravity) keeps its restitution, as Poisson's
// hypothesis has it: after the plastic solve (the compression), each such contact gets e times
// its normal impulse again (the expansion), and its normal impulse keeps that floor while further
// sweeps stop the approaches and slips the expansion starts. (Newton's law, leaving at e times the
// approach, has no solution in a jammed packing.) With restitutions that differ between contacts
// the expansion can gain energy, so the solve measures what its impulses change, sum
// J . (u_before + u_after) / 2 over its contacts (the kinetic energy in the walls' frames), and
// takes the blend with the compression closest to the expanded solution that gains no more than
// its overlaps' pushes add (an overlap's push is no part of the compression given back: the
// compression only stops the approaches, and the sweeps after the expansion open the overlaps).
// A plate accelerating into a body it touches is a collision (a contact's gain holds a wall's
// acceleration only until the contact closes): the body leaves at e times that approach, as from
// a compliant impact.
#pragma once

#include "ag_solver_contact.h"
#include "ag_solver_settings.h"

#include <cstddef>
#include <vector>

namespace ActiveGrain {

class RestingSolve {
 public:
  void resize(std::size_t num_bodies);    // before a solve of num_bodies bodies
  // The island's contacts (indices into contacts): adds their resting impulses to the contacts'
  // impulse and resting and updates the bodies' velocities. Returns the sweeps it took, -1 if it
  // stopped at settings.max_resting_sweeps.
  int solve(std::vector<RigidBodyState> &bodies, std::vector<SolverContact> &contacts,
            const std::vector<int> &island, const SolverSettings &settings);

 private:
  // The stages of solve().
  void prepare(std::vector<RigidBodyState> &bodies, std::vector<SolverContact> &contacts,
               const std::vector<int> &island, const SolverSettings &settings);
  int sweeps_to_tolerance(const SolverSettings &settings);    // -1: stopped at the cap
  double sweep();    // the square of the largest velocity change a contact asked for
  void keep_compression();
  void expand();
  double overlap_credit() const;
  void blend_within_overlap_credit();
  void store();

  // What a sweep needs of an island contact, in sweep order and in one place: its bodies and
  // lever arms, its frame, what an impulse along it does to its velocity, and its accumulated
  // normal and tangential impulse.
  struct Row {
    int contact, body1, body2;    // island contact (index into island_contacts)
    Vec3 r1, r2, gain, n;
    TangentPlane plane;
    double target, normal_mass, mu;    // the separation it must reach, 1 / n.K.n, friction
    double overlap_target;             // max(0, min separation)
    double restitution;                // kept in a collision (Poisson's), else 0
    double floor;                      // the least normal impulse (after the expansion)
    Vec3 before;                       // relative velocity at the start (with restitution)
    Vec3 kn, kt1, kt2;                 // K n, K t1, K t2
    double normal = 0.0, tangent1 = 0.0, tangent2 = 0.0;
    bool with_next = false;    // the next row has the same colour: no movable body in common
  };
  // A row's impulse for relative velocity u (accumulated into the row), and the square of the
  // velocity change it asked for.
  static Vec3 row_impulse(Row &row, const Vec3 &u, double &asked2);

  // The island (prepare()): its bodies' and contacts' lists, and its contacts in them.
  std::vector<RigidBodyState> *solver_bodies = nullptr;
  std::vector<SolverContact> *solver_contacts = nullptr;
  const std::vector<int> *island_contacts = nullptr;
  std::vector<Row> rows;
  std::vector<int> colour_of;
  std::vector<int> by_key, sweep_order;    // island contacts by key, and colour by colour
  std::vector<std::vector<int>> body_colours;    // per body: the colours of its contacts so far
  // With collisions: the island's movable bodies, and the compression's velocities, row impulses
  // and relative velocities after.
  bool collisions = false;    // a row keeps restitution
  std::vector<int> island_bodies;
  std::vector<Vec3> compression_v, compression_omega, compression_after;
  struct RowImpulse {
    double normal, tangent1, tangent2;
  };
  std::vector<RowImpulse> compression_impulse;
  Vec3 row_impulse_sum(const Row &row) const
  {
    return row.n * row.normal + row.plane.tangent1 * row.tangent1 + row.plane.tangent2 * row.tangent2;
  }

  SolverContact &contact(std::size_t k) const { return (*solver_contacts)[(*island_contacts)[k]]; }
};

}    // namespace ActiveGrain
