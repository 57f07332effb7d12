// Many simultaneous contacts between rigid bodies (SPEC section 4b). No LAMMPS in here.
//
// A contact alone on its bodies (walls aside) is one two-body impact: Stronge's law of
// ag_impulse.h, exactly. Contacts that share a body (a rod on a plate touches it with several
// spheres; a bead in a packing touches its neighbours) form one problem whose contact impulses
// are not unique, while the bodies' velocities after the step are: every contact must leave with
// a normal velocity of at least its target (e times its pre-solve approach speed, or an overlap's
// minimum separation velocity), pushing only where it reaches it exactly, and either stick or
// slide with Coulomb friction against its final slip. Projected Gauss-Seidel sweeps solve it:
// each contact update takes back the contact's impulse and applies coupled_contact_impulse, a
// projection whose result depends only on those conditions, so the fixed point does not depend
// on the order of the sweeps. Sweeps go on until no contact update in the last sweep changed
// its contact's velocity by more than tolerance times the island's velocity scale (a residual
// on velocities: it vanishes when every contact meets its conditions, whichever of the many
// impulse sets of redundant contacts was reached).
//
// Every solve starts from zero impulses (no warm start): the result is a function of the state
// alone, so restarts continue a run exactly and every rank count solves the same problem.
#pragma once

#include "ag_impulse.h"

#include <vector>

namespace ActiveGrain {

class ContactSolver {
 public:
  struct Contact {
    int body1 = 0, body2 = 0;       // solver body indices; the normal points from 1 to 2
    Vec3 r1, r2;                    // lever arms: contact point minus each body's centre of mass
    Vec3 n;                         // unit normal
    ContactMaterial material;
    double min_separation = 0.0;    // normal velocity the contact must at least leave with
    // Filled by solve():
    Mat3 K, K_inverse;
    double target_separation = 0.0;
    double speed = 0.0;             // pre-solve relative speed, or the target if larger
    bool isolated = false;          // the only contact of both its (movable) bodies
    Vec3 impulse;                   // on body 2 (minus on body 1)
  };
  struct Result {
    int sweeps = 0;            // most Gauss-Seidel sweeps an island needed (0: none coupled)
    double residual = 0.0;     // largest velocity correction of a contact in an island's last
                               // sweep / velocity scale
    bool converged = true;     // every island reached the tolerance (false: one stopped at max_sweeps)
  };

  void clear();
  int add_body(const RigidBodyState &body);
  // Contact at a point (lever arms from the bodies' centres of mass).
  int add_contact(int body1, int body2, const Vec3 &point, const Vec3 &n,
                  const ContactMaterial &material, double min_separation = 0.0);
  // Contact with explicit lever arms (periodic images: the caller applies the minimum image).
  int add_contact_arms(int body1, int body2, const Vec3 &r1, const Vec3 &r2, const Vec3 &n,
                       const ContactMaterial &material, double min_separation = 0.0);

  // How a contact that shares a body with others is updated in the sweeps:
  //   PROJECTION  coupled_contact_impulse (conditions on the final velocity only): the sweeps
  //               converge to body velocities independent of their order;
  //   STRONGE     contact_law_impulse, Stronge's law of an isolated impact: no such fixed point,
  //               so a fixed number of sweeps gives an order-dependent iterate. It is the law of
  //               isolated contacts, and the two disagree where slip reverses within an impact.
  enum class CoupledLaw { PROJECTION, STRONGE };

  // Isolated contacts once, then each island of coupled contacts (linked through movable
  // bodies) by at most max_sweeps sweeps in the order the contacts were added, until its
  // residual is at most tolerance. Updates the bodies' velocities.
  Result solve(int max_sweeps, double tolerance, CoupledLaw law = CoupledLaw::PROJECTION);

  int num_bodies() const { return static_cast<int>(bodies_.size()); }
  int num_contacts() const { return static_cast<int>(contacts_.size()); }
  const RigidBodyState &body(int i) const { return bodies_[i]; }
  const Contact &contact(int c) const { return contacts_[c]; }
  const Vec3 &impulse(int c) const { return contacts_[c].impulse; }

 private:
  // The stages of solve().
  void prepare();
  void solve_isolated();
  void find_islands();
  double sweep(const std::vector<int> &island, double speed, CoupledLaw law);    // returns the residual

  Vec3 relative_velocity(const Contact &c) const;
  void apply(const Contact &c, const Vec3 &J);

  std::vector<RigidBodyState> bodies_;
  std::vector<Contact> contacts_;
  std::vector<int> coupled_;              // indices of the contacts that share a body
  std::vector<std::vector<int>> islands_;    // coupled contacts linked by movable bodies, in order
  std::vector<int> island_root_;             // per body (union-find)

};

}    // namespace ActiveGrain
