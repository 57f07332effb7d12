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

namespace {
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
  if (narg < 1) error->all(FLERR, "Rod_template: missing template ID");
  if (!domain->box_exist) error->all(FLERR, "Rod_template: must come after the box is defined");
  if (!atom->radius_flag || !atom->rmass_flag)
    error->all(FLERR, "Rod_template: needs an atom style with per-atom diameter and mass (sphere)");

  const std::string id = arg[0];
  RodParameters p;
  bool have[5] = {false, false, false, false, false};
  int types[3] = {1, 2, 3};
  std::string file;    // empty: a private temporary file, removed once read
  bool taper_check = false;

  int iarg = 1;
  auto value = [&](const char *key, int count) {
    if (iarg + count >= narg) error->all(FLERR, "Rod_template: keyword {} needs {} value(s)", key, count);
    return arg + iarg + 1;
  };
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (key == "length") {
      p.length = utils::numeric(FLERR, *value("length", 1), false, lmp);
      have[0] = true; iarg += 2;
    } else if (key == "tail") {
      p.tail_diameter = utils::numeric(FLERR, *value("tail", 1), false, lmp);
      have[1] = true; iarg += 2;
    } else if (key == "nose") {
      p.nose_diameter = utils::numeric(FLERR, *value("nose", 1), false, lmp);
      have[2] = true; iarg += 2;
    } else if (key == "spheres") {
      p.nspheres = utils::inumeric(FLERR, *value("spheres", 1), false, lmp);
      have[3] = true; iarg += 2;
    } else if (key == "density") {
      p.density = utils::numeric(FLERR, *value("density", 1), false, lmp);
      have[4] = true; iarg += 2;
    } else if (key == "types") {
      char **v = value("types", 3);
      for (int k = 0; k < 3; ++k) types[k] = utils::inumeric(FLERR, v[k], false, lmp);
      iarg += 4;
    } else if (key == "file") {
      file = *value("file", 1);
      iarg += 2;
    } else if (key == "taper_check") {
      taper_check = utils::logical(FLERR, *value("taper_check", 1), false, lmp);
      iarg += 2;
    } else {
      error->all(FLERR, "Rod_template: unknown keyword {}", key);
    }
  }
  const char *names[5] = {"length", "tail", "nose", "spheres", "density"};
  for (int k = 0; k < 5; ++k)
    if (!have[k]) error->all(FLERR, "Rod_template: keyword {} is required", names[k]);
  const std::string bad = ActiveGrain::rod_parameter_error(p);
  if (!bad.empty()) error->all(FLERR, "Rod_template: {}", bad);
  if (taper_check && p.nose_diameter > p.tail_diameter)
    error->all(FLERR, "Rod_template: taper_check: nose diameter {} is wider than tail diameter {}",
               p.nose_diameter, p.tail_diameter);
  for (int k = 0; k < 3; ++k)
    if (types[k] < 1 || types[k] > atom->ntypes)
      error->all(FLERR, "Rod_template: types: atom type {} is not between 1 and {}", types[k], atom->ntypes);
  if (types[0] == types[2] || types[0] == types[1] || types[2] == types[1])
    error->all(FLERR, "Rod_template: types: tail, body and nose types must differ so the ends are identifiable");

  ActiveGrain::RodGeometry g;
  try {
    g = ActiveGrain::make_rod_geometry(p);
  } catch (std::invalid_argument &e) {
    error->all(FLERR, "Rod_template: {} (spheres {})", e.what(), p.nspheres);
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
        error->one(FLERR, "Rod_template: no temporary directory ({}): use keyword file", e.what());
      }
      const int fd = mkstemp(pattern.data());
      if (fd < 0 || !(fp = fdopen(fd, "w")))
        error->one(FLERR, "Rod_template: cannot create a temporary file {}: {} (use keyword file)",
                   pattern, utils::getsyserror());
      temporary.path = file = pattern;
    } else {
      fp = fopen(file.c_str(), "w");
      if (!fp) error->one(FLERR, "Rod_template: cannot write {}: {}", file, utils::getsyserror());
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
      fmt::print(fp, "{} {}\n", i + 1, i == 0 ? types[0] : (i == n - 1 ? types[2] : types[1]));
    fmt::print(fp, "\nDiameters\n\n");
    for (int i = 0; i < n; ++i) fmt::print(fp, "{} {:.17g}\n", i + 1, 2.0 * g.spheres[i].radius);
    fmt::print(fp, "\nMasses\n\n");
    for (int i = 0; i < n; ++i) fmt::print(fp, "{} {:.17g}\n", i + 1, g.spheres[i].mass);
    fclose(fp);
    utils::logmesg(lmp,
                   "Rod_template {}: mass {:.6g}, COM {:.6g} from tail, inertia axial {:.6g} "
                   "transverse {:.6g}, {} spheres (envelope dip {:.3g}){}\n",
                   id, g.mass, g.com, g.inertia_axial, g.inertia_transverse, n, g.max_envelope_dip,
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
    utils::logmesg(lmp, "Rod_template {}: projected area {:.6g} in variable {}_area\n", id, area, id);
}
