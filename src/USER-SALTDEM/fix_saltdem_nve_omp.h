/* -*- c++ -*- ----------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.

   fix saltdem/nve/omp: fix saltdem/nve with its integration loops split
   between the OpenMP threads of the rank (-sf omp, package omp).  Every
   atom is integrated on its own, so the result is that of the serial fix.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(saltdem/nve/omp,FixSaltdemNVEOMP);
// clang-format on
#else

#ifndef LMP_FIX_SALTDEM_NVE_OMP_H
#define LMP_FIX_SALTDEM_NVE_OMP_H

#include "comm.h"
#include "fix_saltdem_nve.h"

namespace LAMMPS_NS {

class FixSaltdemNVEOMP : public FixSaltdemNVE {
 public:
  FixSaltdemNVEOMP(class LAMMPS *lmp, int narg, char **arg) : FixSaltdemNVE(lmp, narg, arg) {}
  void init() override
  {
    FixSaltdemNVE::init();
    nthreads = comm->nthreads;
  }
};

}    // namespace LAMMPS_NS

#endif
#endif
