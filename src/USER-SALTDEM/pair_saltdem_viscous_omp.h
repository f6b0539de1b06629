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

#ifdef PAIR_CLASS
// clang-format off
PairStyle(saltdem/viscous/omp,PairSaltdemViscousOMP);
// clang-format on
#else

#ifndef LMP_PAIR_SALTDEM_VISCOUS_OMP_H
#define LMP_PAIR_SALTDEM_VISCOUS_OMP_H

#include "pair_saltdem_omp.h"
#include "pair_saltdem_viscous.h"

namespace LAMMPS_NS {

class PairSaltdemViscousOMP : public PairSaltdemViscous, public PairSaltdemOMP {
 public:
  PairSaltdemViscousOMP(class LAMMPS *);
  void compute(int, int) override;
  double memory_usage() override;

 protected:
  std::vector<double> sum_thr;    // per-thread partial sums of d rho / dt (nthreads x nmax)
};

}    // namespace LAMMPS_NS

#endif
#endif
