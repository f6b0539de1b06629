/* -*- c++ -*- ----------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(saltdem/tiltwall,FixSaltdemTiltwall);
// clang-format on
#else

#ifndef LMP_FIX_SALTDEM_TILTWALL_H
#define LMP_FIX_SALTDEM_TILTWALL_H

#include "fix_saltdem_motion.h"

namespace LAMMPS_NS {

class FixSaltdemTiltwall : public FixSaltdemMotion {
 public:
  FixSaltdemTiltwall(class LAMMPS *, int, char **);
  ~FixSaltdemTiltwall() override;
  void post_constructor() override;
  double compute_vector(int) override;

 protected:
  double tilt;                // tilt of the model (degrees); sense +1: it dips toward +x and
                              // the right wall moves out
  double g;                   // gravitational acceleration (length/time^2; default 9.81 m/s^2 in SI)
  int g_given;                // the keyword g was given
  int igravity;               // group that feels gravity, -1: none (the deck applies it)
  std::string gravity_id;     // internal fix gravity
  int parse_keyword(const std::string &, const std::string &) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
