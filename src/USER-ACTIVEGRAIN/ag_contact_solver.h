// Many simultaneous contacts between rigid bodies, solved by block Gauss-Seidel sweeps
// (sequential impulses): each contact update takes back that contact's accumulated impulse and
// re-applies the single-contact law of ag_impulse.h to the relative velocity the other contacts
// leave it. Restitution aims at e times the pre-solve approach speed; an overlapping contact may
// ask for a minimum separation velocity instead (whichever is larger). No LAMMPS in here.
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
    Mat3 K;
    double target_separation = 0.0;
    Vec3 impulse;                   // on body 2 (minus on body 1)
  };
  struct Result {
    int sweeps = 0;              // sweeps done
    double last_change = 0.0;    // largest impulse change of the last sweep / largest impulse
  };

  void clear();
  int add_body(const RigidBodyState &body);
  // Contact at a point (lever arms from the bodies' centres of mass).
  int add_contact(int body1, int body2, const Vec3 &point, const Vec3 &n,
                  const ContactMaterial &material, double min_separation = 0.0);
  // Contact with explicit lever arms (periodic images: the caller applies the minimum image).
  int add_contact_arms(int body1, int body2, const Vec3 &r1, const Vec3 &r2, const Vec3 &n,
                       const ContactMaterial &material, double min_separation = 0.0);

  // At most max_sweeps sweeps; stops early when no impulse changed by more than tolerance
  // times the largest impulse. Updates the bodies' velocities.
  Result solve(int max_sweeps, double tolerance);

  int num_bodies() const { return static_cast<int>(bodies_.size()); }
  int num_contacts() const { return static_cast<int>(contacts_.size()); }
  const RigidBodyState &body(int i) const { return bodies_[i]; }
  const Contact &contact(int c) const { return contacts_[c]; }
  const Vec3 &impulse(int c) const { return contacts_[c].impulse; }

 private:
  Vec3 relative_velocity(const Contact &c) const;
  void apply(const Contact &c, const Vec3 &J);

  std::vector<RigidBodyState> bodies_;
  std::vector<Contact> contacts_;
};

}    // namespace ActiveGrain
