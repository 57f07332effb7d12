/* -*- c++ -*- ----------------------------------------------------------
   ActiveGrain: internal fix STORE/IMPULSE, pair gran/impulse's per-atom store of the impulses
   still due (impulse_carry.h). Not a user command.
------------------------------------------------------------------------- */
#ifdef FIX_CLASS
// clang-format off
FixStyle(STORE/IMPULSE,FixStoreImpulse);
// clang-format on
#else

#ifndef LMP_FIX_STORE_IMPULSE_H
#define LMP_FIX_STORE_IMPULSE_H

#include "fix_store_atom.h"

namespace LAMMPS_NS {

// Fix STORE/ATOM (same arguments) that zeroes the values of atoms created after it
// (create_atoms, read_data, fix pour): their slots may hold what a deleted atom, or memory freed
// by an earlier LAMMPS instance, left there, which would pass for impulses due.
class FixStoreImpulse : public FixStoreAtom {
 public:
  FixStoreImpulse(class LAMMPS *, int, char **);
  void set_arrays(int) override;

 private:
  int columns;
};

}    // namespace LAMMPS_NS

#endif
#endif
