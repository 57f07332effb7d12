#include "fix_store_impulse.h"

#include <algorithm>

using namespace LAMMPS_NS;

FixStoreImpulse::FixStoreImpulse(LAMMPS *lmp, int narg, char **arg) : FixStoreAtom(lmp, narg, arg)
{
  columns = utils::inumeric(FLERR, arg[3], false, lmp);
  create_attribute = 1;
}

void FixStoreImpulse::set_arrays(int i)
{
  std::fill(astore[i], astore[i] + columns, 0.0);
}
