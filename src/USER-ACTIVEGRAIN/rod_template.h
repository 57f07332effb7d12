// rod_template: build a LAMMPS molecule template for a tapered polar rod from its physical
// parameters (see docs/rod_template.rst).
#pragma once

#include "command.h"

namespace LAMMPS_NS {

class RodTemplate : public Command {
 public:
  RodTemplate(class LAMMPS *lmp) : Command(lmp) {}
  void command(int, char **) override;
};

}    // namespace LAMMPS_NS
