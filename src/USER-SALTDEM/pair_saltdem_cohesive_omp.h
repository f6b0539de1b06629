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
PairStyle(saltdem/cohesive/omp,PairSaltdemCohesiveOMP);
// clang-format on
#else

#ifndef LMP_PAIR_SALTDEM_COHESIVE_OMP_H
#define LMP_PAIR_SALTDEM_COHESIVE_OMP_H

#include "pair_saltdem_cohesive.h"
#include "pair_saltdem_omp.h"

namespace LAMMPS_NS {

class PairSaltdemCohesiveOMP : public PairSaltdemCohesive, public PairSaltdemOMP {
 public:
  PairSaltdemCohesiveOMP(class LAMMPS *);
  void compute(int, int) override;
  double memory_usage() override;
};

}    // namespace LAMMPS_NS

#endif
#endif
