#include "rod_template.h"

#include "ag_projected_area.h"
#include "ag_rod_geometry.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "input.h"
#include "utils.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <stdexcept>
#include <string>
#include <unistd.h>

using namespace LAMMPS_NS;
using ActiveGrain::RodParameters;

static const char *const STYLE = "Rod_template";

namespace {
// The keywords every rod_template command must give.
enum RequiredKeyword { LENGTH = 0, TAIL, NOSE, SPHERES, DENSITY, NREQUIRED };
const char *const REQUIRED_KEYWORDS[NREQUIRED] = {"length", "tail", "nose", "spheres", "density"};
// The atom types of keyword types, in its order.
enum RodAtomType { TAIL_TYPE = 0, BODY_TYPE, NOSE_TYPE, NROD_TYPES };

// Removes a file when it goes out of scope, also when an error unwinds past it.
struct RemovedAtExit {
  std::string path;
  ~RemovedAtExit()
  {
    if (!path.empty()) std::remove(path.c_str());
  }
};
}    // namespace

/* Syntax: rod_template ID length L tail Dt nose Dn spheres N density rho
             [types Ttail Tbody Tnose] [file NAME] [taper_check yes/no] */
void RodTemplate::command(int narg, char **arg)
{
  if (narg < 1) error->all(FLERR, "{}: missing template ID", STYLE);
  if (!domain->box_exist) error->all(FLERR, "{}: must come after the box is defined", STYLE);
  if (!atom->radius_flag || !atom->rmass_flag)
    error->all(FLERR, "{}: needs an atom style with per-atom diameter and mass (sphere)", STYLE);

  const std::string id = arg[0];
  RodParameters p;
  bool have[NREQUIRED] = {};
  int types[NROD_TYPES] = {1, 2, 3};
  std::string file;    // empty: a private temporary file, removed once read
  bool taper_check = false;

  int iarg = 1;
  auto value = [&](const char *key, int count) {
    if (iarg + count >= narg) error->all(FLERR, "{}: keyword {} needs {} value(s)", STYLE, key, count);
    return arg + iarg + 1;
  };
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (key == "length") {
      p.length = utils::numeric(FLERR, *value("length", 1), false, lmp);
      have[LENGTH] = true; iarg += 2;
    } else if (key == "tail") {
      p.tail_diameter = utils::numeric(FLERR, *value("tail", 1), false, lmp);
      have[TAIL] = true; iarg += 2;
    } else if (key == "nose") {
      p.nose_diameter = utils::numeric(FLERR, *value("nose", 1), false, lmp);
      have[NOSE] = true; iarg += 2;
    } else if (key == "spheres") {
      p.nspheres = utils::inumeric(FLERR, *value("spheres", 1), false, lmp);
      have[SPHERES] = true; iarg += 2;
    } else if (key == "density") {
      p.density = utils::numeric(FLERR, *value("density", 1), false, lmp);
      have[DENSITY] = true; iarg += 2;
    } else if (key == "types") {
      char **v = value("types", NROD_TYPES);
      for (int k = 0; k < NROD_TYPES; ++k) types[k] = utils::inumeric(FLERR, v[k], false, lmp);
      iarg += 1 + NROD_TYPES;
    } else if (key == "file") {
      file = *value("file", 1);
      iarg += 2;
    } else if (key == "taper_check") {
      taper_check = utils::logical(FLERR, *value("taper_check", 1), false, lmp);
      iarg += 2;
    } else {
      error->all(FLERR, "{}: unknown keyword {}", STYLE, key);
    }
  }
  for (int k = 0; k < NREQUIRED; ++k)
    if (!have[k]) error->all(FLERR, "{}: keyword {} is required", STYLE, REQUIRED_KEYWORDS[k]);
  const std::string bad = ActiveGrain::rod_parameter_error(p);
  if (!bad.empty()) error->all(FLERR, "{}: {}", STYLE, bad);
  if (taper_check && p.nose_diameter > p.tail_diameter)
    error->all(FLERR, "{}: taper_check: nose diameter {} is wider than tail diameter {}", STYLE,
               p.nose_diameter, p.tail_diameter);
  for (int k = 0; k < NROD_TYPES; ++k)
    if (types[k] < 1 || types[k] > atom->ntypes)
      error->all(FLERR, "{}: types: atom type {} is not between 1 and {}", STYLE, types[k], atom->ntypes);
  if (types[TAIL_TYPE] == types[NOSE_TYPE] || types[TAIL_TYPE] == types[BODY_TYPE] ||
      types[NOSE_TYPE] == types[BODY_TYPE])
    error->all(FLERR, "{}: types: tail, body and nose types must differ so the ends are identifiable", STYLE);

  ActiveGrain::RodGeometry g;
  try {
    g = ActiveGrain::make_rod_geometry(p);
  } catch (std::invalid_argument &e) {
    error->all(FLERR, "{}: {} (spheres {})", STYLE, e.what(), p.nspheres);
  }

  // Rod along +x (tail to nose), centre of mass at the origin. The header carries the solid's
  // mass, COM and inertia so that molecule-based insertion uses them; the per-sphere masses
  // already sum to the solid's mass and first moment. The molecule command reads a file (on
  // rank 0): without keyword file, one of a unique name in the temporary directory, so that
  // jobs sharing a working directory do not overwrite each other's template.
  RemovedAtExit temporary;
  if (comm->me == 0) {
    FILE *fp = nullptr;
    if (file.empty()) {
      std::string pattern;
      try {
        pattern = (std::filesystem::temp_directory_path() / ("rod_template-" + id + "-XXXXXX")).string();
      } catch (std::filesystem::filesystem_error &e) {
        error->one(FLERR, "{}: no temporary directory ({}): use keyword file", STYLE, e.what());
      }
      const int fd = mkstemp(pattern.data());
      if (fd < 0 || !(fp = fdopen(fd, "w")))
        error->one(FLERR, "{}: cannot create a temporary file {}: {} (use keyword file)", STYLE,
                   pattern, utils::getsyserror());
      temporary.path = file = pattern;
    } else {
      fp = fopen(file.c_str(), "w");
      if (!fp) error->one(FLERR, "{}: cannot write {}: {}", STYLE, file, utils::getsyserror());
    }
    const int n = p.nspheres;
    fmt::print(fp, "# rod_template {}: L {} tail {} nose {} spheres {} density {}\n\n", id, p.length,
               p.tail_diameter, p.nose_diameter, n, p.density);
    fmt::print(fp, "{} atoms\n{:.17g} mass\n0 0 0 com\n{:.17g} {:.17g} {:.17g} 0 0 0 inertia\n", n,
               g.mass, g.inertia_axial, g.inertia_transverse, g.inertia_transverse);
    fmt::print(fp, "\nCoords\n\n");
    for (int i = 0; i < n; ++i) fmt::print(fp, "{} {:.17g} 0 0\n", i + 1, g.spheres[i].x - g.com);
    fmt::print(fp, "\nTypes\n\n");
    for (int i = 0; i < n; ++i)
      fmt::print(fp, "{} {}\n", i + 1,
                 i == 0 ? types[TAIL_TYPE] : (i == n - 1 ? types[NOSE_TYPE] : types[BODY_TYPE]));
    fmt::print(fp, "\nDiameters\n\n");
    for (int i = 0; i < n; ++i) fmt::print(fp, "{} {:.17g}\n", i + 1, 2.0 * g.spheres[i].radius);
    fmt::print(fp, "\nMasses\n\n");
    for (int i = 0; i < n; ++i) fmt::print(fp, "{} {:.17g}\n", i + 1, g.spheres[i].mass);
    fclose(fp);
    utils::logmesg(lmp,
                   "{} {}: mass {:.6g}, COM {:.6g} from tail, inertia axial {:.6g} "
                   "transverse {:.6g}, {} spheres (envelope dip {:.3g}){}\n",
                   STYLE, id, g.mass, g.com, g.inertia_axial, g.inertia_transverse, n, g.max_envelope_dip,
                   temporary.path.empty() ? ", written to " + file : "");
  }
  // Only rank 0 opens the file; the others pass the same name to the molecule command.
  int length = static_cast<int>(file.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, world);
  file.resize(length);
  MPI_Bcast(file.data(), length, MPI_CHAR, 0, world);
  input->one(fmt::format("molecule {} \"{}\"", id, file));

  // The rod's projected area as simulated (the union of its spheres' discs, as compute
  // areafrac/chunk counts it), for decks that turn an area fraction into a number of rods.
  std::vector<double> centres, radii;
  for (const auto &sphere : g.spheres) {
    centres.push_back(sphere.x);
    radii.push_back(sphere.radius);
  }
  const auto shares = ActiveGrain::disc_chain_area_shares(centres, radii);
  const double area = std::accumulate(shares.begin(), shares.end(), 0.0);
  input->one(fmt::format("variable {}_area internal {:.17g}", id, area));
  if (comm->me == 0)
    utils::logmesg(lmp, "{} {}: projected area {:.6g} in variable {}_area\n", STYLE, id, area, id);
}
