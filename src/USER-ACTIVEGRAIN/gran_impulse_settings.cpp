#include "gran_impulse_settings.h"

#include "comm.h"
#include "error.h"
#include "utils.h"

#include <string>

using namespace LAMMPS_NS;

// Below this many sub-steps per half oscillation a compliant impact is too coarse to keep its
// restitution (docs/pair_gran_impulse.rst: the error is about 3/resolution).
static constexpr int MIN_RESOLUTION = 20;
// Restart files: the settings' format, stored negative (the first format, without the window,
// began with the resolution). The resting speed is stored as RESTING_AUTO for resting yes.
// From format -7 on, the pair coefficients that follow carry the tangential law too.
static constexpr int RESTART_FORMAT = -7;
static constexpr int COEFFS_BEFORE_TANGENTIAL_LAW = 2;    // e, mu
static constexpr double RESTING_AUTO = -1.0;

void GranImpulseSettings::parse(LAMMPS *lmp, const char *style, int narg, char **arg)
{
  Error *error = lmp->error;
  *this = GranImpulseSettings();
  bool resting_setting_given = false;
  for (int iarg = 0; iarg < narg; iarg += 2) {
    const std::string key = arg[iarg];
    if (key == "coupled" || key == "sweeps")
      error->all(FLERR, "{}: keyword {} is gone: contacts that share a body are solved as one "
                 "compliant impact, whose only setting is resolution", style, key);
    if (iarg + 2 > narg) error->all(FLERR, "{}: missing value after keyword {}", style, key);
    const std::string value = arg[iarg + 1];
    if (key == "window") {
      solver.window = value == "step" ? ActiveGrain::SolverSettings().window : utils::numeric(FLERR, value, false, lmp);
      if (solver.window < 0.0) error->all(FLERR, "{}: window must be >= 0 or step", style);
    } else if (key == "resolution") {
      solver.resolution = utils::inumeric(FLERR, value, false, lmp);
      if (solver.resolution < MIN_RESOLUTION) error->all(FLERR, "{}: resolution must be >= {}", style, MIN_RESOLUTION);
    } else if (key == "beta") {
      beta = utils::numeric(FLERR, value, false, lmp);
      if (beta < 0.0 || beta > 1.0) error->all(FLERR, "{}: beta must be in [0, 1]", style);
    } else if (key == "slop") {
      slop = utils::numeric(FLERR, value, false, lmp);
      if (!(slop >= 0.0)) error->all(FLERR, "{}: slop must be >= 0 (found {})", style, value);
    } else if (key == "order") {
      if (value == "shuffle") order = ContactOrder::SHUFFLE;
      else if (value == "tag") order = ContactOrder::TAG;
      else if (value == "reverse") order = ContactOrder::REVERSE;
      else error->all(FLERR, "{}: order must be shuffle, tag or reverse (found {})", style, value);
    } else if (key == "resting") {
      const bool named = value == "yes" || value == "no" || value == "newton";
      solver.resting_from_acceleration = value == "yes" || value == "newton";
      solver.resting_restitution = value == "newton";
      solver.resting_speed = named ? 0.0 : utils::numeric(FLERR, value, false, lmp);
      if (!(solver.resting_speed >= 0.0))
        error->all(FLERR, "{}: resting must be yes, newton, no or a speed >= 0 (found {})", style, value);
    } else if (key == "tolerance") {
      solver.resting_tolerance = utils::numeric(FLERR, value, false, lmp);
      if (!(solver.resting_tolerance > 0.0 && solver.resting_tolerance < 1.0))
        error->all(FLERR, "{}: tolerance must be in (0, 1) (found {})", style, value);
      resting_setting_given = true;
    } else if (key == "max_sweeps") {
      solver.max_resting_sweeps = utils::inumeric(FLERR, value, false, lmp);
      if (solver.max_resting_sweeps < 1) error->all(FLERR, "{}: max_sweeps must be >= 1 (found {})", style, value);
      resting_setting_given = true;
    } else {
      error->all(FLERR, "{}: unknown keyword {}", style, key);
    }
  }
  if (resting_setting_given && !solver.resting_from_acceleration && solver.resting_speed == 0.0)
    error->all(FLERR, "{}: keywords tolerance and max_sweeps set the resting solve's: they need resting yes or a "
               "speed", style);
}

// A negative format number first (files of the first format begin with the resolution, which is
// positive), then resolution, beta, order, the window, resting, the resting solve's tolerance,
// the slop, the resting solve's sweep cap and whether it keeps restitution.
void GranImpulseSettings::write_restart(FILE *fp) const
{
  const int order_code = static_cast<int>(order);
  const double resting = solver.resting_from_acceleration ? RESTING_AUTO : solver.resting_speed;
  fwrite(&RESTART_FORMAT, sizeof(int), 1, fp);
  fwrite(&solver.resolution, sizeof(int), 1, fp);
  fwrite(&beta, sizeof(double), 1, fp);
  fwrite(&order_code, sizeof(int), 1, fp);
  fwrite(&solver.window, sizeof(double), 1, fp);
  fwrite(&resting, sizeof(double), 1, fp);
  fwrite(&solver.resting_tolerance, sizeof(double), 1, fp);
  fwrite(&slop, sizeof(double), 1, fp);
  fwrite(&solver.max_resting_sweeps, sizeof(int), 1, fp);
  const int restitution = solver.resting_restitution ? 1 : 0;
  fwrite(&restitution, sizeof(int), 1, fp);
}

void GranImpulseSettings::read_restart(LAMMPS *lmp, const char *style, FILE *fp)
{
  Error *error = lmp->error;
  *this = GranImpulseSettings();
  int order_code = 0, restitution = 0;
  double resting = 0.0;
  if (lmp->comm->me == 0) {
    int format = 0;
    utils::sfread(FLERR, &format, sizeof(int), 1, fp, nullptr, error);
    if (format > 0) solver.resolution = format;    // the first format: no window
    else utils::sfread(FLERR, &solver.resolution, sizeof(int), 1, fp, nullptr, error);
    if (format < RESTART_FORMAT) error->one(FLERR, "{}: restart file of a newer format ({})", style, -format);
    utils::sfread(FLERR, &beta, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &order_code, sizeof(int), 1, fp, nullptr, error);
    if (format < 0) utils::sfread(FLERR, &solver.window, sizeof(double), 1, fp, nullptr, error);
    if (format < -2) utils::sfread(FLERR, &resting, sizeof(double), 1, fp, nullptr, error);
    if (format < -3) utils::sfread(FLERR, &solver.resting_tolerance, sizeof(double), 1, fp, nullptr, error);
    if (format < -4) {
      utils::sfread(FLERR, &slop, sizeof(double), 1, fp, nullptr, error);
      utils::sfread(FLERR, &solver.max_resting_sweeps, sizeof(int), 1, fp, nullptr, error);
    }
    if (format < -5) utils::sfread(FLERR, &restitution, sizeof(int), 1, fp, nullptr, error);
    if (format >= -6) restart_model_coeffs = COEFFS_BEFORE_TANGENTIAL_LAW;
  }
  MPI_Comm world = lmp->world;
  MPI_Bcast(&solver.resolution, 1, MPI_INT, 0, world);
  MPI_Bcast(&beta, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&slop, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&order_code, 1, MPI_INT, 0, world);
  MPI_Bcast(&solver.window, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&resting, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&solver.resting_tolerance, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&solver.max_resting_sweeps, 1, MPI_INT, 0, world);
  MPI_Bcast(&restitution, 1, MPI_INT, 0, world);
  order = static_cast<ContactOrder>(order_code);
  solver.resting_from_acceleration = resting == RESTING_AUTO;
  solver.resting_speed = solver.resting_from_acceleration ? 0.0 : resting;
  solver.resting_restitution = restitution != 0;
}
