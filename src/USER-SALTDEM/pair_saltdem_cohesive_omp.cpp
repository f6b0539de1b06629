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

   pair saltdem/cohesive/omp: pair saltdem/cohesive with its pair loop split between the
   OpenMP threads of the rank (-sf omp, package omp).  Each thread runs the serial style's
   loop over its slice of the neighbour list (PairSaltdemOMP::thread_bounds) into
   thread-private arrays, which ThrOMP reduces: the serial numbers up to the order of the
   sums.
------------------------------------------------------------------------- */

#include "pair_saltdem_cohesive_omp.h"

#include "saltdem_cohesive_law.h"
#include "saltdem_pair_loop.h"

#include "atom.h"
#include "comm.h"
#include "fix_omp.h"
#include "force.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "suffix.h"
#include "thr_data.h"
#include "timer.h"

#include "omp_compat.h"
#if defined(_OPENMP)
#include <omp.h>
#endif

using namespace LAMMPS_NS;

PairSaltdemCohesiveOMP::PairSaltdemCohesiveOMP(LAMMPS *lmp) :
    PairSaltdemCohesive(lmp), PairSaltdemOMP(lmp)
{
  suffix_flag |= Suffix::OMP;
  respa_enable = 0;
}

void PairSaltdemCohesiveOMP::compute(int eflag, int vflag)
{
  recheck_timestep();
  ev_init(eflag, vflag);
  pre_loop();
  const int nall = atom->nlocal + atom->nghost;
  const int nthreads = comm->nthreads;
  const int *bounds =
      thread_bounds(list->ilist, list->numneigh, list->inum, neighbor->lastcall, nthreads);
  const SaltDEM::CohesiveLaw cover = law();

#if defined(_OPENMP)
#pragma omp parallel LMP_DEFAULT_NONE LMP_SHARED(eflag, vflag, bounds, nthreads, cover)
#endif
  {
#if defined(_OPENMP)
    const int tid = omp_get_thread_num();
#else
    const int tid = 0;
#endif
    ThrData *thr = fix->get_thr(tid);
    thr->timer(Timer::START);
    ev_setup_thr(eflag, vflag, nall, eatom, vatom, nullptr, thr);

    const int nlocal = atom->nlocal;
    const int newton_pair = force->newton_pair;
    auto tally = [&](int i, int j, double e, double fx, double fy, double fz, double dx, double dy,
                     double dz) {
      ev_tally_xyz_thr(this, i, j, nlocal, newton_pair, e, 0.0, fx, fy, fz, dx, dy, dz, thr);
    };
    dispatch_loop(cover, bounds[tid], bounds[tid + 1], thr->get_f(), thr->get_torque(), nullptr,
                  tally);

    thr->timer(Timer::PAIR);
    reduce_thr(this, eflag, vflag, thr);
  }
}

double PairSaltdemCohesiveOMP::memory_usage()
{
  return PairSaltdemCohesive::memory_usage() + memory_usage_thr();
}
