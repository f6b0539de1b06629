/* -*- c++ -*- ----------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/, Sandia National Laboratories
   LAMMPS development team: developers@lammps.org

   Copyright (2003) Sandia Corporation.  Under the terms of Contract
   DE-AC04-94AL85000 with Sandia Corporation, the U.S. Government retains
   certain rights in this software.  This software is distributed under
   the GNU General Public License.

   See the README file in the top-level LAMMPS directory.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing authors: the SaltDEM developers (USER-SALTDEM package, SaltDEM
   repository: discrete-element salt tectonics)
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
  double tilt;               // tilt of the model (degrees); sense +1: it dips toward +x and
                             // the right wall moves out
  double g;                  // gravitational acceleration (length/time^2; default 9.81 m/s^2 in SI)
  int g_given;               // the keyword g was given
  int igravity;              // group that feels gravity, -1: none (the deck applies it)
  std::string gravity_id;    // internal fix gravity
  int parse_keyword(const std::string &, const std::string &) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
