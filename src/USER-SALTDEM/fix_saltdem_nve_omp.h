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
FixStyle(saltdem/nve/omp,FixSaltdemNVEOMP);
// clang-format on
#else

#ifndef LMP_FIX_SALTDEM_NVE_OMP_H
#define LMP_FIX_SALTDEM_NVE_OMP_H

#include "fix_saltdem_nve.h"

namespace LAMMPS_NS {

class FixSaltdemNVEOMP : public FixSaltdemNVE {
 public:
  FixSaltdemNVEOMP(class LAMMPS *, int, char **);

 protected:
  void integrate_all(bool) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
