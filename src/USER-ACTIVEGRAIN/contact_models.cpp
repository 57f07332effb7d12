#include "contact_models.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "memory.h"
#include "utils.h"

#include <cstring>

using namespace LAMMPS_NS;
using ActiveGrain::ContactModel;

static constexpr int NUM_COEFFS = ContactModel::NUM_COEFFS;

static void check_contact_model(Error *error, const std::string &style, const ContactModel &model)
{
  const std::string invalid = model.invalid();
  if (!invalid.empty()) error->all(FLERR, "{}: {}", style, invalid);
}

ContactModel LAMMPS_NS::parse_contact_model(LAMMPS *lmp, const std::string &style, char **coeffs)
{
  double values[NUM_COEFFS];
  for (int k = 0; k < NUM_COEFFS; ++k) values[k] = utils::numeric(FLERR, coeffs[k], false, lmp);
  const ContactModel model = ContactModel::from_coeffs(values);
  check_contact_model(lmp->error, style, model);
  return model;
}

PairContactModels::~PairContactModels()
{
  for (double **&array : coeffs) memory->destroy(array);
}

void PairContactModels::allocate(int ntypes)
{
  for (int k = 0; k < NUM_COEFFS; ++k)
    memory->create(coeffs[k], ntypes + 1, ntypes + 1, ("pair:" + std::string(ContactModel::COEFF_NAMES[k])).c_str());
}

void PairContactModels::set(int i, int j, const ContactModel &model)
{
  double values[NUM_COEFFS];
  model.to_coeffs(values);
  for (int k = 0; k < NUM_COEFFS; ++k) coeffs[k][i][j] = values[k];
}

void PairContactModels::mix(int i, int j)
{
  set(i, j, ContactModel::mixed(of(i, i), of(j, j)));
}

ContactModel PairContactModels::of(int i, int j) const
{
  double values[NUM_COEFFS];
  for (int k = 0; k < NUM_COEFFS; ++k) values[k] = coeffs[k][i][j];
  return ContactModel::from_coeffs(values);
}

void PairContactModels::write_restart(FILE *fp, int i, int j) const
{
  for (int k = 0; k < NUM_COEFFS; ++k) fwrite(&coeffs[k][i][j], sizeof(double), 1, fp);
}

void PairContactModels::read_restart(FILE *fp, int i, int j)
{
  for (int k = 0; k < NUM_COEFFS; ++k) {
    if (comm->me == 0) utils::sfread(FLERR, &coeffs[k][i][j], sizeof(double), 1, fp, nullptr, error);
    MPI_Bcast(&coeffs[k][i][j], 1, MPI_DOUBLE, 0, world);
  }
}

double **PairContactModels::extract(const char *name) const
{
  for (int k = 0; k < NUM_COEFFS; ++k)
    if (strcmp(name, ContactModel::COEFF_NAMES[k]) == 0) return coeffs[k];
  return nullptr;
}

int WallContactModels::parse(int narg, char **arg, int iarg)
{
  const int ntypes = atom->ntypes;
  if (per_type.empty()) {
    per_type.resize(ntypes + 1);
    type_set.assign(ntypes + 1, false);
  }
  const std::string key = arg[iarg];
  for (int k = 0; k < NUM_COEFFS; ++k) {
    if (key != ContactModel::COEFF_NAMES[k]) continue;
    if (iarg + 2 > narg) error->all(FLERR, "{}: missing value after keyword {}", style, key);
    // This coefficient beside the defaults of the others, checked alone.
    double values[NUM_COEFFS] = {};
    values[k] = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    check_contact_model(error, style, ContactModel::from_coeffs(values));
    all_set[k] = true;
    for (int t = 1; t <= ntypes; ++t) {
      if (type_set[t]) continue;
      double now[NUM_COEFFS];
      per_type[t].to_coeffs(now);
      now[k] = values[k];
      per_type[t] = ContactModel::from_coeffs(now);
    }
    return iarg + 2;
  }
  if (key == "type") {
    if (iarg + 2 + NUM_COEFFS > narg)
      error->all(FLERR, "{}: keyword type needs a type and values e mu", style);
    int lo, hi;
    utils::bounds(FLERR, arg[iarg + 1], 1, ntypes, lo, hi, error);
    const ContactModel model = parse_contact_model(lmp, style, arg + iarg + 2);
    for (int t = lo; t <= hi; ++t) {
      per_type[t] = model;
      type_set[t] = true;
    }
    return iarg + 2 + NUM_COEFFS;
  }
  return iarg;
}

void WallContactModels::check_complete() const
{
  if (per_type.empty()) error->all(FLERR, "{}: keywords e and mu are required", style);
  bool all_given = true;
  for (bool given : all_set) all_given = all_given && given;
  for (int t = 1; t < (int) per_type.size(); ++t)
    if (!type_set[t] && !all_given)
      error->all(FLERR, "{}: no restitution e and friction mu for atom type {} (use keywords e and mu, or type)",
                 style, t);
}
