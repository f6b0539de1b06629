/* -*- c++ -*- ----------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(saltdem/fault,FixSaltdemFault);
// clang-format on
#else

#ifndef LMP_FIX_SALTDEM_FAULT_H
#define LMP_FIX_SALTDEM_FAULT_H

#include "fix.h"

namespace LAMMPS_NS {

class FixSaltdemFault : public Fix {
 public:
  FixSaltdemFault(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void initial_integrate(int) override;
  double compute_vector(int) override;
  void *extract(const char *, int &) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

 protected:
  double dip;              // fault dip (degrees)
  double rate;             // displacement rate along the fault (m/s)
  double target;           // displacement at which the hanging wall stops (m)
  int end_run;             // 1: end the run when the target is reached
  double dir[3];           // unit down-dip direction
  double disp;             // displacement so far (m), kept in restart files
  void set_velocity(double speed);
};

}    // namespace LAMMPS_NS

#endif
#endif
