/* -*- c++ -*- ----------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(saltdem/cohesive/omp,PairSaltdemCohesiveOMP);
// clang-format on
#else

#ifndef LMP_PAIR_SALTDEM_COHESIVE_OMP_H
#define LMP_PAIR_SALTDEM_COHESIVE_OMP_H

#include "pair_saltdem_cohesive.h"
#include "thr_omp.h"

namespace LAMMPS_NS {

class PairSaltdemCohesiveOMP : public PairSaltdemCohesive, public ThrOMP {
  template <class Style> friend void saltdem_compute_omp(Style *, int, int);

 public:
  PairSaltdemCohesiveOMP(class LAMMPS *);
  void compute(int, int) override;
  double memory_usage() override;
};

}    // namespace LAMMPS_NS

#endif
#endif
