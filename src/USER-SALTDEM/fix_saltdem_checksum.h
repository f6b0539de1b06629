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
FixStyle(saltdem/checksum,FixSaltdemChecksum);
// clang-format on
#else

#ifndef LMP_FIX_SALTDEM_CHECKSUM_H
#define LMP_FIX_SALTDEM_CHECKSUM_H

#include "fix.h"

namespace LAMMPS_NS {

class FixSaltdemChecksum : public Fix {
 public:
  FixSaltdemChecksum(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;
  void post_run() override;
  double compute_scalar() override;

 private:
  bigint seen;    // the step of the last restart output that has its checksum
  int nwritten;
  void check();
  void sum(const std::string &);
};

}    // namespace LAMMPS_NS

#endif
#endif
