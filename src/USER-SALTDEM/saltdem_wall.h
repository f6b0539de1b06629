/* -*- c++ -*- ----------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.
------------------------------------------------------------------------- */

#ifdef COMMAND_CLASS
// clang-format off
CommandStyle(saltdem/wall,SaltdemWall);
// clang-format on
#else

#ifndef LMP_SALTDEM_WALL_H
#define LMP_SALTDEM_WALL_H

#include "command.h"

namespace LAMMPS_NS {

class SaltdemWall : public Command {
 public:
  SaltdemWall(class LAMMPS *lmp) : Command(lmp) {}
  void command(int, char **) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
