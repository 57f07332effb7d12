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
// e and mu, the first coefficients: pair_coeff's numbers, and the wall fixes' keywords of that name.
static constexpr int NUM_NUMBERED_COEFFS = 2;

static void check_contact_model(Error *error, const std::string &style, const ContactModel &model)
{
  const std::string invalid = model.invalid();
  if (!invalid.empty()) error->all(FLERR, "{}: {}", style, invalid);
}

ContactModel LAMMPS_NS::parse_contact_model(LAMMPS *lmp, const std::string &style, int narg, char **arg)
{
  if (narg < 2) lmp->error->all(FLERR, "{}: pair_coeff needs I J e mu", style);
  ContactModel model;
  model.normal.e = utils::numeric(FLERR, arg[0], false, lmp);
  model.tangential.mu = utils::numeric(FLERR, arg[1], false, lmp);
  for (int iarg = 2; iarg < narg;) {
    if (strcmp(arg[iarg], "tangential") != 0)
      lmp->error->all(FLERR, "{}: unknown pair_coeff keyword {} (after I J e mu: tangential)", style, arg[iarg]);
    iarg = parse_tangential_law(lmp, style, narg, arg, iarg, model.tangential);
  }
  check_contact_model(lmp->error, style, model);
  return model;
}

int LAMMPS_NS::parse_tangential_law(LAMMPS *lmp, const std::string &style, int narg, char **arg, int iarg,
                                    ActiveGrain::TangentialModel &law)
{
  const std::string name = iarg + 1 < narg ? arg[iarg + 1] : "";
  if (name == "stick") {
    law.law = ActiveGrain::TangentialLaw::STICK;
    law.stiffness_ratio = 0.0;
    return iarg + 2;
  }
  if (name == "compliant") {
    if (iarg + 3 > narg) lmp->error->all(FLERR, "{}: tangential compliant needs its stiffness ratio", style);
    law.law = ActiveGrain::TangentialLaw::COMPLIANT;
    law.stiffness_ratio = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
    return iarg + 3;
  }
  lmp->error->all(FLERR, "{}: tangential must be stick or compliant R, not '{}'", style, name);
  return narg;
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

void PairContactModels::read_restart(FILE *fp, int i, int j, int stored)
{
  double values[NUM_COEFFS];
  ContactModel().to_coeffs(values);
  if (comm->me == 0) utils::sfread(FLERR, values, sizeof(double), stored, fp, nullptr, error);
  MPI_Bcast(values, NUM_COEFFS, MPI_DOUBLE, 0, world);
  set(i, j, ContactModel::from_coeffs(values));
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
  for (int k = 0; k < NUM_NUMBERED_COEFFS; ++k) {
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
    if (iarg + 4 > narg) error->all(FLERR, "{}: keyword type needs a type and values e mu", style);
    int lo, hi;
    utils::bounds(FLERR, arg[iarg + 1], 1, ntypes, lo, hi, error);
    const ContactModel model = parse_contact_model(lmp, style, 2, arg + iarg + 2);
    for (int t = lo; t <= hi; ++t) {
      per_type[t] = model;
      type_set[t] = true;
    }
    return iarg + 4;
  }
  if (key == "tangential") return parse_tangential_law(lmp, style, narg, arg, iarg, tangential);
  return iarg;
}

void WallContactModels::check_complete()
{
  if (per_type.empty()) error->all(FLERR, "{}: keywords e and mu are required", style);
  bool all_given = true;
  for (bool given : all_set) all_given = all_given && given;
  for (int t = 1; t < (int) per_type.size(); ++t)
    if (!type_set[t] && !all_given)
      error->all(FLERR, "{}: no restitution e and friction mu for atom type {} (use keywords e and mu, or type)",
                 style, t);
  for (ContactModel &model : per_type) {
    model.tangential.law = tangential.law;
    model.tangential.stiffness_ratio = tangential.stiffness_ratio;
    check_contact_model(error, style, model);
  }
}
