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

   pair saltdem/viscous/omp: pair saltdem/viscous with its pair loop split between the
   OpenMP threads of the rank (-sf omp, package omp), as pair saltdem/cohesive/omp; the
   continuity sum d rho / dt is summed per thread into slices of its own and the slices are
   added into the density fix's array after the loop.  The SPH field passes before it (kernel
   moments) and the viscosity's sub-steps or implicit step after it run on the same threads
   (SphFields::run_threads).
------------------------------------------------------------------------- */

#include "pair_saltdem_viscous_omp.h"

#include "fix_saltdem_density.h"
#include "saltdem_pair_loop.h"
#include "saltdem_viscous_law.h"

#include "atom.h"
#include "comm.h"
#include "fix_omp.h"
#include "force.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "suffix.h"
#include "thr_data.h"
#include "timer.h"
#include "update.h"

#include <functional>

#include "omp_compat.h"
#if defined(_OPENMP)
#include <omp.h>
#endif

using namespace LAMMPS_NS;

PairSaltdemViscousOMP::PairSaltdemViscousOMP(LAMMPS *lmp) :
    PairSaltdemViscous(lmp), PairSaltdemOMP(lmp)
{
  suffix_flag |= Suffix::OMP;
  respa_enable = 0;
  fields->run_threads = [this](const std::function<void(int)> &body) {
    const int n = fields->nthreads;
#if defined(_OPENMP)
#pragma omp parallel num_threads(n)
    body(omp_get_thread_num());
#else
    (void) n;
    body(0);
#endif
  };
}

void PairSaltdemViscousOMP::compute(int eflag, int vflag)
{
  recheck_timestep();
  ev_init(eflag, vflag);
  fields->nthreads = comm->nthreads;
  pre_loop();
  const int nall = atom->nlocal + atom->nghost;
  const int nthreads = comm->nthreads;
  const int *bounds =
      thread_bounds(list->ilist, list->numneigh, list->inum, neighbor->lastcall, nthreads);

  // one thread sums into the serial array; several each into a slice of sum_thr
  const size_t stride = nmax;
  if (nthreads > 1 && nthreads * stride > sum_thr.size()) sum_thr.resize(nthreads * stride);
  double *serial = (nthreads > 1) ? nullptr : loop_sum();
  double *part = sum_thr.data();
  const SaltDEM::ViscousLaw salt = law();

#if defined(_OPENMP)
#pragma omp parallel LMP_DEFAULT_NONE LMP_SHARED(eflag, vflag, bounds, nthreads, serial, part, salt)
#endif
  {
#if defined(_OPENMP)
    const int tid = omp_get_thread_num();
#else
    const int tid = 0;
#endif
    double *sum = serial;
    if (nthreads > 1) {
      sum = part + (size_t) tid * stride;
      for (int i = 0; i < nall; i++) sum[i] = 0.0;
    }
    ThrData *thr = fix->get_thr(tid);
    thr->timer(Timer::START);
    ev_setup_thr(eflag, vflag, nall, eatom, vatom, nullptr, thr);

    const int nlocal = atom->nlocal;
    const int newton_pair = force->newton_pair;
    auto tally = [&](int i, int j, double e, double fx, double fy, double fz, double dx, double dy,
                     double dz) {
      ev_tally_xyz_thr(this, i, j, nlocal, newton_pair, e, 0.0, fx, fy, fz, dx, dy, dz, thr);
    };
    dispatch_loop(salt, bounds[tid], bounds[tid + 1], thr->get_f(), thr->get_torque(), sum, tally);

    thr->timer(Timer::PAIR);
    reduce_thr(this, eflag, vflag, thr);
  }

  // the threads' sums of d rho / dt into the density fix (not during setup, whose rate the
  // fix does not integrate)
  if (nthreads > 1 && any_fluid && !update->setupflag) {
    double *drho = fix_density->drho;
#if defined(_OPENMP)
#pragma omp parallel for num_threads(nthreads) schedule(static) LMP_DEFAULT_NONE LMP_SHARED( \
    part, nthreads, drho)
#endif
    for (int i = 0; i < nall; i++) {
      double add = 0.0;
      for (int t = 0; t < nthreads; t++) add += part[(size_t) t * stride + i];
      drho[i] = add;
    }
  }
}

double PairSaltdemViscousOMP::memory_usage()
{
  return PairSaltdemViscous::memory_usage() + memory_usage_thr() +
      (double) sum_thr.size() * sizeof(double);
}
