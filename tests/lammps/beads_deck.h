// The example deck (bead monolayer between vibrating plates) set up in-process, and what the
// dense-packing tests read from it.
#pragma once

#include "lammps_fixture.h"

#include "force.h"
#include "pair_gran_impulse.h"

#include <algorithm>
#include <stdexcept>
#include <string>

class BeadMonolayer : public LammpsTest {
 protected:
  // The deck with its defaults (360 beads, area fraction 0.75), set up but not run; flat plates
  // unless extra_variables set the roughness (the deck's default is calibrated roughness).
  void load_deck(const std::string &extra_variables = "")
  {
    command("variable steps index 0\n" + extra_variables + "\nvariable rough index 0");
    command("include " ACTIVEGRAIN_SOURCE_DIR "/examples/beads-vibrated/in.beads-vibrated");
  }

  // Largest overlap of any contact (bead-bead or bead-plate) since the last run's setup, over
  // all ranks.
  double largest_overlap()
  {
    return solver_output(LAMMPS_NS::PairGranImpulse::LARGEST_OVERLAP);
  }

  // A global output of pair gran/impulse, as compute pair gran/impulse gives it (the sum of
  // its pvector over ranks).
  double solver_output(int index)
  {
    double all = 0;
    MPI_Allreduce(&lmp->force->pair->pvector[index], &all, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    return all;
  }
};
