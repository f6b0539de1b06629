/* ----------------------------------------------------------------------
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

   fix saltdem/nve/omp: fix saltdem/nve with its integration loops split
   between the OpenMP threads of the rank (-sf omp, package omp).  Every
   atom is integrated on its own, so the result is that of the serial fix.
------------------------------------------------------------------------- */

#include "fix_saltdem_nve_omp.h"

#include "atom.h"
#include "comm.h"

#include "omp_compat.h"
#if defined(_OPENMP)
#include <omp.h>
#endif

using namespace LAMMPS_NS;

FixSaltdemNVEOMP::FixSaltdemNVEOMP(LAMMPS *lmp, int narg, char **arg) :
    FixSaltdemNVE(lmp, narg, arg)
{
}

/* thread t of n integrates the owned atoms [t nlocal / n, (t+1) nlocal / n) (the atoms are
   independent: the serial numbers) */

void FixSaltdemNVEOMP::integrate_all(bool drift)
{
  const int nlocal = atom->nlocal;
  const int nthreads = comm->nthreads;
#if defined(_OPENMP)
#pragma omp parallel LMP_DEFAULT_NONE LMP_SHARED(drift, nlocal, nthreads) \
    num_threads(nthreads) if (nthreads > 1)
#endif
  {
#if defined(_OPENMP)
    const int tid = omp_get_thread_num();
    const int nth = omp_get_num_threads();    // (the threads the runtime gave)
#else
    const int tid = 0;
    const int nth = 1;
#endif
    const int ifrom = (int) ((bigint) nlocal * tid / nth);
    const int ito = (int) ((bigint) nlocal * (tid + 1) / nth);
    integrate_range(ifrom, ito, drift);
  }
}
