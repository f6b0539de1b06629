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

   The pair loop of the SaltDEM pair styles, written once for the serial styles and their
   OpenMP variants, and inlining the law policy it is handed (see PairSaltdem::loop).  Not a
   style header: only the styles' .cpp files include it (the style headers declare these
   templates).
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_PAIR_LOOP_H
#define LMP_SALTDEM_PAIR_LOOP_H

#include "pair_saltdem.h"

#include "atom.h"
#include "domain.h"
#include "fix_neigh_history.h"
#include "force.h"
#include "neigh_list.h"
#include "update.h"

#include <cmath>

namespace LAMMPS_NS {

/* keep the smaller limit: best/why hold the smallest so far (why empty: none yet); a limit
   that is not a finite positive number is kept in preference (the check stops on it) */

template <class Reason>
void PairSaltdem::consider_limit(double lim, double &best, std::string &why, Reason &&reason)
{
  auto bad = [](double v) {
    return !(v > 0.0) || !std::isfinite(v);
  };
  if (!why.empty() && bad(best)) return;
  if (why.empty() || bad(lim) || lim < best) {
    best = lim;
    why = reason();
  }
}

/* loop() for the run's energy/virial flag and dimension */

template <class Law, class Tally>
void PairSaltdem::dispatch_loop(const Law &law, int ifrom, int ito, double **f, double **torque,
                                double *sum, Tally &&tally)
{
  if (domain->dimension == 2) {
    if (evflag)
      loop<Law, 1, 2>(law, ifrom, ito, f, torque, sum, tally);
    else
      loop<Law, 0, 2>(law, ifrom, ito, f, torque, sum, tally);
  } else {
    if (evflag)
      loop<Law, 1, 3>(law, ifrom, ito, f, torque, sum, tally);
    else
      loop<Law, 0, 3>(law, ifrom, ito, f, torque, sum, tally);
  }
}

/* the serial compute() of a style: pre_loop(), the loop over all pairs */

template <class Law> void PairSaltdem::compute_serial(const Law &law, int eflag, int vflag)
{
  recheck_timestep();
  ev_init(eflag, vflag);
  pre_loop();
  auto tally = [this](int i, int j, double e, double fx, double fy, double fz, double dx, double dy,
                      double dz) {
    ev_tally_xyz(i, j, atom->nlocal, force->newton_pair, e, 0.0, fx, fy, fz, dx, dy, dz);
  };
  dispatch_loop(law, 0, list->inum, atom->f, atom->torque, loop_sum(), tally);
}

/* the one pair loop (see pair_saltdem.h) */

template <class Law, int EVFLAG, int DIM, class Tally>
void PairSaltdem::loop(const Law &law, int ifrom, int ito, double **f, double **torque, double *sum,
                       Tally &&tally)
{
  using row = const double(*)[3];
  const Atoms a = {atom->x ? (row) atom->x[0] : nullptr, atom->v ? (row) atom->v[0] : nullptr,
                   atom->omega ? (row) atom->omega[0] : nullptr, atom->radius, atom->rmass};
  const auto x = a.x;
  const double *radius = atom->radius;
  const int *type = atom->type;
  const int nlocal = atom->nlocal;
  const int newton_pair = force->newton_pair;
  const bool advance = (update->setupflag == 0);    // history is not advanced in setup
  // a law without history (Law::HISTORY false): nhist is the constant 0, and the history
  // bookkeeping compiles away
  const int nhist = Law::HISTORY ? size_history : 0;

  const int *ilist = list->ilist;
  const int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  int **firsttouch = nhist ? fix_history->firstflag : nullptr;
  double **firsthist = nhist ? fix_history->firstvalue : nullptr;

  double fij[3], ti[3], tj[3];

  for (int ii = ifrom; ii < ito; ii++) {
    const int i = ilist[ii];
    const int itype = type[i];
    const double radi = radius[i];
    const double xi0 = x[i][0], xi1 = x[i][1], xi2 = (DIM == 3) ? x[i][2] : 0.0;
    const double *extra_i = extra[itype];
    const double *reach_i = reach_abs[itype];
    const int *jlist = firstneigh[i];
    const int jnum = numneigh[i];
    int *touch = nhist ? firsttouch[i] : nullptr;
    double *allhist = nhist ? firsthist[i] : nullptr;
    // what i receives is summed here and added once after its neighbours: in memory, each
    // pair would wait for the previous pair's store to f[i]
    double fi0 = 0.0, fi1 = 0.0, fi2 = 0.0, ti0 = 0.0, ti1 = 0.0, ti2 = 0.0, sumi = 0.0;

    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const int jtype = type[j];
      const double delx = xi0 - x[j][0];
      const double dely = xi1 - x[j][1];
      const double delz = (DIM == 3) ? xi2 - x[j][2] : 0.0;
      const double rsq = (DIM == 3) ? delx * delx + dely * dely + delz * delz
                                    : delx * delx + dely * dely;
      const double reach = MAX(radi + radius[j] + extra_i[jtype], reach_i[jtype]);
      double *hist = nhist ? &allhist[nhist * jj] : nullptr;

      // out of reach: a pair that is not flagged touching has a zero history
      // already (FixNeighHistory zeroes new pairs, this loop ended ones)
      if (rsq >= reach * reach || rsq == 0.0) {
        if (nhist && touch[jj]) {
          touch[jj] = 0;
          for (int k = 0; k < nhist; k++) hist[k] = 0.0;
        }
        continue;
      }
      double evdwl = 0.0, q[2] = {0.0, 0.0};
      const int flags = law.template force<DIM, EVFLAG>(a, i, j, itype, jtype, std::sqrt(rsq), hist,
                                                        advance, fij, ti, tj, evdwl, q);
      if (Law::PAIR_SUM) {
        sumi += q[0];
        if (newton_pair || j < nlocal) sum[j] += q[1];
      }
      if (nhist) {
        if (flags & LAW_TOUCH)
          touch[jj] = 1;
        else if (touch[jj]) {
          touch[jj] = 0;
          for (int k = 0; k < nhist; k++) hist[k] = 0.0;
        }
      }

      fi0 += fij[0];
      fi1 += fij[1];
      if (DIM == 3) fi2 += fij[2];
      if (flags & LAW_TORQUE) {
        if (DIM == 3) {
          ti0 += ti[0];
          ti1 += ti[1];
        }
        ti2 += ti[2];
      }
      if (newton_pair || j < nlocal) {
        f[j][0] -= fij[0];
        f[j][1] -= fij[1];
        if (DIM == 3) f[j][2] -= fij[2];
        if (flags & LAW_TORQUE) {
          if (DIM == 3) {
            torque[j][0] += tj[0];
            torque[j][1] += tj[1];
          }
          torque[j][2] += tj[2];
        }
      }
      if (EVFLAG) tally(i, j, evdwl, fij[0], fij[1], (DIM == 3) ? fij[2] : 0.0, delx, dely, delz);
    }
    f[i][0] += fi0;
    f[i][1] += fi1;
    if (DIM == 3) {
      f[i][2] += fi2;
      torque[i][0] += ti0;
      torque[i][1] += ti1;
    }
    torque[i][2] += ti2;
    if (Law::PAIR_SUM) sum[i] += sumi;
  }
}

}    // namespace LAMMPS_NS

#endif
