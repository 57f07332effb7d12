#include "impulse_carry.h"

#include "atom.h"
#include "fix_store_impulse.h"
#include "impulse_delivery.h"
#include "modify.h"
#include "update.h"

#include <algorithm>

using namespace LAMMPS_NS;

static const char *const PENDING_ID = "AG_GRAN_IMPULSE_DUE";

void ImpulseCarry::create_store()
{
  pending = dynamic_cast<FixStoreImpulse *>(modify->get_fix_by_id(PENDING_ID));
  if (!pending)
    pending = dynamic_cast<FixStoreImpulse *>(
        modify->add_fix(fmt::format("{} all STORE/IMPULSE {} 0 0 1", PENDING_ID, static_cast<int>(NUM_SAVED))));
}

void ImpulseCarry::delete_store()
{
  if (pending) modify->delete_fix(PENDING_ID);
  pending = nullptr;
}

void ImpulseCarry::store(const ImpulseDelivery &delivery)
{
  double **saved = pending->astore;
  const double step = (double) update->ntimestep, dt = update->dt;
  for (int i = 0; i < atom->nlocal; i++) {
    const double *sums = delivery.sums_of(i);
    for (int k = 0; k < 3; k++) {
      saved[i][SAVED_FORCE + k] = sums[ImpulseDelivery::FORCE + k];
      saved[i][SAVED_TORQUE + k] = sums[ImpulseDelivery::TORQUE + k];
    }
    saved[i][SAVED_DT] = dt;
    saved[i][SAVED_STEP] = step;
  }
  force_dt = dt;
}

void ImpulseCarry::restore(ImpulseDelivery &delivery)
{
  double **saved = pending->astore;
  const double step = (double) update->ntimestep, dt = update->dt;
  for (int i = 0; i < atom->nlocal; i++)
    if (saved[i][SAVED_STEP] == step) {
      double *sums = delivery.sums_of(i);
      const double scale = saved[i][SAVED_DT] / dt;    // exactly 1 for the same time step
      for (int k = 0; k < 3; k++) {
        sums[ImpulseDelivery::FORCE + k] = saved[i][SAVED_FORCE + k] * scale;
        sums[ImpulseDelivery::TORQUE + k] = saved[i][SAVED_TORQUE + k] * scale;
      }
    }
  force_dt = dt;
}

// atom->f holds J / force_dt, which the next initial_integrate would apply with the new dt: it
// becomes J / dt. (Fix rigid/rod then sums the corrected forces into its bodies.)
void ImpulseCarry::rescale_for_dt()
{
  if (!pending || force_dt <= 0.0 || force_dt == update->dt) return;
  double **f = atom->f, **torque = atom->torque, **saved = pending->astore;
  const double step = (double) update->ntimestep;
  for (int i = 0; i < atom->nlocal; i++)
    if (saved[i][SAVED_STEP] == step) {
      // J = saved force times its time step
      const double change = saved[i][SAVED_DT] * (1.0 / update->dt - 1.0 / force_dt);
      for (int k = 0; k < 3; k++) {
        f[i][k] += saved[i][SAVED_FORCE + k] * change;
        torque[i][k] += saved[i][SAVED_TORQUE + k] * change;
      }
    }
  force_dt = update->dt;
}

void ImpulseCarry::keep_virial(const double *virial)
{
  std::copy(virial, virial + ImpulseDelivery::NUM_VIRIAL, last_virial);
  last_virial_step = update->ntimestep;
}

void ImpulseCarry::restore_virial(double *virial) const
{
  if (last_virial_step == update->ntimestep) std::copy(last_virial, last_virial + ImpulseDelivery::NUM_VIRIAL, virial);
}
