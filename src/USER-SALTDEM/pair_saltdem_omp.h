/* -*- c++ -*- ----------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.

   The OpenMP variants of the SaltDEM pair styles (-sf omp).  One template
   serves every style: each thread runs the style's own pair loop
   (PairSaltdem::loop, the same code as the serial style) over its slice of
   the neighbour list (PairSaltdem::thread_bounds: equal numbers of pairs)
   into thread-private force/torque arrays, which ThrOMP then reduces (and
   into the style's thread-private per-atom sums, which its post_loop()
   adds up: the continuity density of saltdem/viscous).  Needs the OPENMP
   package.
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(saltdem/cohesive/omp,PairSaltdemCohesiveOMP);
PairStyle(saltdem/viscous/omp,PairSaltdemViscousOMP);
// clang-format on
#else

#ifndef LMP_PAIR_SALTDEM_OMP_H
#define LMP_PAIR_SALTDEM_OMP_H

#include "pair_saltdem_cohesive.h"
#include "pair_saltdem_viscous.h"

#include "comm.h"
#include "fix_omp.h"
#include "suffix.h"
#include "thr_data.h"
#include "thr_omp.h"
#include "timer.h"

#include "omp_compat.h"
#if defined(_OPENMP)
#include <omp.h>
#endif

namespace LAMMPS_NS {

template <class Style> class PairSaltdemOMP : public Style, public ThrOMP {
 public:
  PairSaltdemOMP(class LAMMPS *lmp) : Style(lmp), ThrOMP(lmp, THR_PAIR)
  {
    this->suffix_flag |= Suffix::OMP;
    this->respa_enable = 0;
  }

  void compute(int eflag, int vflag) override
  {
    this->recheck_timestep();
    this->ev_init(eflag, vflag);
    this->pre_loop();
    const int nall = this->atom->nlocal + this->atom->nghost;
    const int nthreads = this->comm->nthreads;
    const int *bounds = this->thread_bounds(nthreads);

#if defined(_OPENMP)
#pragma omp parallel LMP_DEFAULT_NONE LMP_SHARED(eflag, vflag, bounds, nthreads)
#endif
    {
#if defined(_OPENMP)
      const int tid = omp_get_thread_num();
#else
      const int tid = 0;
#endif
      const int ifrom = bounds[tid], ito = bounds[tid + 1];
      ThrData *thr = fix->get_thr(tid);
      thr->timer(Timer::START);
      ev_setup_thr(eflag, vflag, nall, this->eatom, this->vatom, nullptr, thr);

      const int nlocal = this->atom->nlocal;
      const int newton_pair = this->force->newton_pair;
      auto tally = [&](int i, int j, double e, double fx, double fy, double fz, double dx,
                       double dy, double dz) {
        ev_tally_xyz_thr(this, i, j, nlocal, newton_pair, e, 0.0, fx, fy, fz, dx, dy, dz, thr);
      };
      this->dispatch_loop(this, ifrom, ito, thr->get_f(), thr->get_torque(),
                          this->loop_sum(tid, nthreads), tally);

      thr->timer(Timer::PAIR);
      reduce_thr(this, eflag, vflag, thr);
    }
    this->post_loop(nthreads);
  }

  double memory_usage() override { return Style::memory_usage() + memory_usage_thr(); }
};

using PairSaltdemCohesiveOMP = PairSaltdemOMP<PairSaltdemCohesive>;
using PairSaltdemViscousOMP = PairSaltdemOMP<PairSaltdemViscous>;

}    // namespace LAMMPS_NS

#endif
#endif
