/* -*- c++ -*- ----------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.

   The threaded compute() shared by every SaltDEM /omp pair style: each
   thread runs the style's own pair loop (PairSaltdem::loop) over its slice
   of the neighbour list into thread-private force/torque arrays, which
   ThrOMP then reduces.  Needs the OPENMP package.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_OMP_H
#define LMP_SALTDEM_OMP_H

#include "comm.h"
#include "fix_omp.h"
#include "suffix.h"
#include "thr_data.h"
#include "thr_omp.h"
#include "timer.h"

#include "omp_compat.h"

namespace LAMMPS_NS {

template <class Style> void saltdem_compute_omp(Style *style, int eflag, int vflag)
{
  style->ev_init(eflag, vflag);
  const int nall = style->atom->nlocal + style->atom->nghost;
  const int nthreads = style->comm->nthreads;
  const int inum = style->list->inum;

#if defined(_OPENMP)
#pragma omp parallel LMP_DEFAULT_NONE LMP_SHARED(eflag, vflag, style)
#endif
  {
    int ifrom, ito, tid;
    loop_setup_thr(ifrom, ito, tid, inum, nthreads);
    ThrData *thr = style->fix->get_thr(tid);
    thr->timer(Timer::START);
    style->ev_setup_thr(eflag, vflag, nall, style->eatom, style->vatom, nullptr, thr);

    const int nlocal = style->atom->nlocal;
    const int newton_pair = style->force->newton_pair;
    auto tally = [&](int i, int j, double e, double fx, double fy, double fz, double dx, double dy,
                     double dz) {
      style->ev_tally_xyz_thr(style, i, j, nlocal, newton_pair, e, 0.0, fx, fy, fz, dx, dy, dz,
                              thr);
    };
    if (style->evflag)
      style->template loop<Style, 1>(style, ifrom, ito, thr->get_f(), thr->get_torque(), tally);
    else
      style->template loop<Style, 0>(style, ifrom, ito, thr->get_f(), thr->get_torque(), tally);

    thr->timer(Timer::PAIR);
    style->reduce_thr(style, eflag, vflag, thr);
  }
}

}    // namespace LAMMPS_NS

#endif
