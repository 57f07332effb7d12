// rod_template: build a LAMMPS molecule template for a tapered polar rod from its physical
// parameters (see docs/rod_template.rst).
#ifdef COMMAND_CLASS
// clang-format off
CommandStyle(rod_template,RodTemplate);
// clang-format on
#else

#ifndef LMP_ROD_TEMPLATE_H
#define LMP_ROD_TEMPLATE_H

#include "command.h"

namespace LAMMPS_NS {

class RodTemplate : public Command {
 public:
  RodTemplate(class LAMMPS *lmp) : Command(lmp) {}
  void command(int, char **) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
