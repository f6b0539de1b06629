/* -*- c++ -*- ----------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.
------------------------------------------------------------------------- */

#ifdef COMMAND_CLASS
// clang-format off
CommandStyle(saltdem/timestep,SaltdemTimestep);
// clang-format on
#else

#ifndef LMP_SALTDEM_TIMESTEP_H
#define LMP_SALTDEM_TIMESTEP_H

#include "command.h"

namespace LAMMPS_NS {

class SaltdemTimestep : public Command {
 public:
  SaltdemTimestep(class LAMMPS *lmp) : Command(lmp) {}
  void command(int, char **) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
