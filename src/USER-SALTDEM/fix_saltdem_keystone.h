/* -*- c++ -*- ----------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(saltdem/keystone,FixSaltdemKeystone);
// clang-format on
#else

#ifndef LMP_FIX_SALTDEM_KEYSTONE_H
#define LMP_FIX_SALTDEM_KEYSTONE_H

#include "fix_saltdem_motion.h"

namespace LAMMPS_NS {

class FixSaltdemKeystone : public FixSaltdemMotion {
 public:
  FixSaltdemKeystone(class LAMMPS *, int, char **);
  void init() override;
  double compute_vector(int) override;

 protected:
  double dip;       // dip of both faults (degrees)
  int ikeystone;    // group of the keystone block
  int parse_keyword(const std::string &, const std::string &) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
