/* ----------------------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.
------------------------------------------------------------------------- */

#include "pair_saltdem_cohesive_omp.h"

#include "saltdem_omp.h"

using namespace LAMMPS_NS;

PairSaltdemCohesiveOMP::PairSaltdemCohesiveOMP(LAMMPS *lmp) :
    PairSaltdemCohesive(lmp), ThrOMP(lmp, THR_PAIR)
{
  suffix_flag |= Suffix::OMP;
  respa_enable = 0;
}

void PairSaltdemCohesiveOMP::compute(int eflag, int vflag)
{
  saltdem_compute_omp(this, eflag, vflag);
}

double PairSaltdemCohesiveOMP::memory_usage()
{
  return PairSaltdemCohesive::memory_usage() + memory_usage_thr();
}
