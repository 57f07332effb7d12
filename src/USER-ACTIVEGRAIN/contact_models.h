// The contact models (ag_contact_model.h) of pair gran/impulse's type pairs and of a wall fix's
// atom types: parsed from pair_coeff and the wall fixes' keywords, checked, stored and written
// to restart files in one place. The coefficients come in ContactModel's order (e mu).
#pragma once

#include "ag_contact_model.h"
#include "pointers.h"

#include <cstdio>
#include <string>
#include <vector>

namespace LAMMPS_NS {

// pair_coeff's "e mu [tangential stick|compliant R]" (arg: after the types), or an ERROR naming
// the style and what is wrong.
ActiveGrain::ContactModel parse_contact_model(LAMMPS *lmp, const std::string &style, int narg, char **arg);
// "tangential stick" or "tangential compliant R" at arg[iarg] (the keyword): into law; returns
// the next index.
int parse_tangential_law(LAMMPS *lmp, const std::string &style, int narg, char **arg, int iarg,
                         ActiveGrain::TangentialModel &law);

// The models of pair_coeff I J, one array per coefficient (fix adapt reaches them through the
// pair style's extract(), by the coefficient's name).
class PairContactModels : protected Pointers {
 public:
  PairContactModels(LAMMPS *lmp) : Pointers(lmp) {}
  ~PairContactModels() override;
  void allocate(int ntypes);
  void set(int i, int j, const ActiveGrain::ContactModel &model);
  // Types i and j without a pair_coeff of their own: mixed from i,i and j,j. Then j,i as i,j.
  void mix(int i, int j);
  ActiveGrain::ContactModel of(int i, int j) const;
  void write_restart(FILE *fp, int i, int j) const;
  // Rank 0 reads the first `stored` coefficients (older files have fewer), every rank gets them.
  void read_restart(FILE *fp, int i, int j, int stored);
  double **extract(const char *name) const;     // one coefficient's array, or nullptr

 private:
  double **coeffs[ActiveGrain::ContactModel::NUM_COEFFS] = {};
};

// A wall's model against each atom type: "e E" and "mu MU" for all types, then "type T E MU" (T
// may be a range like 2*3) to override some; "tangential stick|compliant R" for all. Parsed by
// both wall fixes.
class WallContactModels : protected Pointers {
 public:
  WallContactModels(LAMMPS *lmp, const std::string &style_name) : Pointers(lmp), style(style_name) {}
  // Consume a model keyword at arg[iarg]; returns the next index, or iarg if not one.
  int parse(int narg, char **arg, int iarg);
  // Errors unless every type has its coefficients; then the tangential law joins them.
  void check_complete();
  const ActiveGrain::ContactModel &of_type(int type) const { return per_type[type]; }

 private:
  std::string style;
  std::vector<ActiveGrain::ContactModel> per_type;
  ActiveGrain::TangentialModel tangential;    // the law of keyword tangential (mu apart)
  std::vector<bool> type_set;    // per type: set by keyword type
  // Per coefficient: given for all types by its keyword.
  std::vector<bool> all_set = std::vector<bool>(2, false);    // e, mu
};

}    // namespace LAMMPS_NS
