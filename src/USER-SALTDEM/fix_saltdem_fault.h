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

#include "fix_saltdem_motion.h"

namespace LAMMPS_NS {

class FixSaltdemFault : public FixSaltdemMotion {
 public:
  FixSaltdemFault(class LAMMPS *, int, char **);
  double compute_vector(int) override;

 protected:
  double dip;    // fault dip (degrees); sense: +1 the fault dips toward +x, -1 toward -x
  int parse_keyword(const std::string &, const std::string &) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
