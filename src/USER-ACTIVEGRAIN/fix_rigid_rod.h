// fix rigid/rod: tapered polar rods as rigid bodies (fix rigid/small) with the solid's true
// inertia, a body frame whose x axis is the polar axis (tail -> nose), and per-atom body state
// for the contact styles (RigidBodyProvider), owned and ghost atoms. See docs/fix_rigid_rod.rst.
#ifdef FIX_CLASS
// clang-format off
FixStyle(rigid/rod,FixRigidRod);
// clang-format on
#else

#ifndef LMP_FIX_RIGID_ROD_H
#define LMP_FIX_RIGID_ROD_H

#include "fix_rigid_small.h"
#include "rigid_body_provider.h"

namespace LAMMPS_NS {

class FixRigidRod : public FixRigidSmall, public RigidBodyProvider {
 public:
  FixRigidRod(class LAMMPS *, int, char **);
  ~FixRigidRod() noexcept override;
  int setmask() override;
  void init() override;
  void setup_pre_neighbor() override;
  void setup_pre_force(int) override;
  void setup(int) override;
  void initial_integrate(int) override;
  void reset_dt() override;
  void pre_force(int) override;
  void final_integrate() override;
  void grow_arrays(int) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  void *extract(const char *, int &) override;
  double memory_usage() override;

  bool body_of_atom(int i, ActiveGrain::RigidBodyState &body, tagint &body_id) const override;
  bool add_late_impulse(int i, const ActiveGrain::Vec3 &late, const ActiveGrain::Vec3 &late_angular) override;

 private:
  enum class RodComm { NONE, STATE, POLAR_SUM, LATE_MOVE };
  RodComm rod_comm = RodComm::NONE;    // our own comm pass, else the base class's

  int tail_type = 0, nose_type = 0;                           // from the template's end atoms
  double inertia_axial = 0.0, inertia_transverse = 0.0;       // of the solid rod
  void check_molecule_ids();
  double template_span = 0.0;      // largest distance between two atom centres of the template
  double template_length = 0.0;    // tip to tip: the span plus the end spheres' radii
  double **state = nullptr;        // per atom (owned + ghost): see STATE_* in the .cpp
  double **output = nullptr;       // per owned atom: its rod's polar axis and body ID, else 0 (OUT_*)
  double **polar_sum = nullptr;    // per body, during setup: sum of nose - tail offsets, counts
  double **late = nullptr;         // per owned atom: late impulse and its moment (LATE_*)
  double **late_move = nullptr;    // per body: summed late impulse and moment, then its move
  int nmax_late_body = 0;
  bool late_here = false;          // some owned atom has a late impulse this step
  bool setup_forces_due = false;   // the bodies' forces of the run's setup are incomplete
  int nmax_atom = 0;

  void impose_rod_bodies();
  void fill_body_state();
  void move_late_bodies();
  double **body_rows(int &width) const;    // the per-body rows of the current pass
};

}    // namespace LAMMPS_NS

#endif
#endif
