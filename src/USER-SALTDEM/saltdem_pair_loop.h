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

   The pair loop of the SaltDEM pair styles and the laws it inlines, written once for the
   serial styles and their OpenMP variants.  Not a style header: only the styles' .cpp files
   include it (the style headers declare these templates).
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_PAIR_LOOP_H
#define LMP_SALTDEM_PAIR_LOOP_H

#include "pair_saltdem.h"
#include "pair_saltdem_cohesive.h"
#include "pair_saltdem_viscous.h"
#include "saltdem_contact_cohesive.h"
#include "saltdem_contact_viscous.h"

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

template <class Derived, class Tally>
void PairSaltdem::dispatch_loop(Derived *self, int ifrom, int ito, double **f, double **torque,
                                double *sum, Tally &&tally)
{
  if (domain->dimension == 2) {
    if (evflag)
      loop<Derived, 1, 2>(self, ifrom, ito, f, torque, sum, tally);
    else
      loop<Derived, 0, 2>(self, ifrom, ito, f, torque, sum, tally);
  } else {
    if (evflag)
      loop<Derived, 1, 3>(self, ifrom, ito, f, torque, sum, tally);
    else
      loop<Derived, 0, 3>(self, ifrom, ito, f, torque, sum, tally);
  }
}

/* the serial compute() of a style: pre_loop(), the loop over all pairs */

template <class Derived> void PairSaltdem::compute_serial(Derived *self, int eflag, int vflag)
{
  recheck_timestep();
  ev_init(eflag, vflag);
  pre_loop();
  auto tally = [this](int i, int j, double e, double fx, double fy, double fz, double dx, double dy,
                      double dz) {
    ev_tally_xyz(i, j, atom->nlocal, force->newton_pair, e, 0.0, fx, fy, fz, dx, dy, dz);
  };
  dispatch_loop(self, 0, list->inum, atom->f, atom->torque, loop_sum(), tally);
}

/* the one pair loop (see pair_saltdem.h) */

template <class Derived, int EVFLAG, int DIM, class Tally>
void PairSaltdem::loop(Derived *self, int ifrom, int ito, double **f, double **torque, double *sum,
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
  // a law without history (Derived::HISTORY false): nhist is the constant 0, and the history
  // bookkeeping compiles away
  const int nhist = Derived::HISTORY ? size_history : 0;

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
      const int flags = self->template law<DIM, EVFLAG>(a, i, j, itype, jtype, std::sqrt(rsq), hist,
                                                        advance, fij, ti, tj, evdwl, q);
      if (Derived::PAIR_SUM) {
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
    if (Derived::PAIR_SUM) sum[i] += sumi;
  }
}

/* the cover law (SaltDEM::cohesive_force) */

template <int DIM, int EVFLAG>
int PairSaltdemCohesive::law(const Atoms &a, int i, int j, int itype, int jtype, double r,
                             double *hist, bool advance, double *f, double *ti, double *tj,
                             double &evdwl, double *) const
{
  SaltDEM::Contact c;
  SaltDEM::contact_kinematics<DIM>(a.x[i], a.x[j], a.v[i], a.v[j], a.omega[i], a.omega[j],
                                   a.radius[i], a.radius[j], a.rmass[i], a.rmass[j], r, c, rolling);
  return SaltDEM::cohesive_force<DIM, EVFLAG>(params[itype][jtype], c, hist, rolling, dt, advance,
                                              f, ti, tj, evdwl)
      ? (LAW_TOUCH | LAW_TORQUE)
      : 0;
}

/* what a FLUID pair weighs.  Sums over the partners j of a particle i count each j as i's own
   material, mu_ij = m_j rho_m,i / rho_m,j = mdens_i r_j^dim (rho_m = m / r^dim per disc or
   sphere: its material density), so that particles of two densities side by side see one
   continuous kernel density and pressure (the volume-weighted sums of multiphase SPH,
   Colagrossi & Landrini 2003, Hu & Adams 2006); for one density mu_ij = m_j.  A boundary
   partner (its own pair is not FLUID) of a fluid particle counts with that particle's fill
   (SaltDEM::boundary_fill) and has the volume mu_ij / rho0_i of the fluid it stands for;
   between two boundary particles the volumes are their own (vol). */

template <int DIM>
inline double PairSaltdemViscous::partner_mass(const double *radius, int i, int j) const
{
  const double r = radius[j];
  return mdens[i] * ((DIM == 2) ? r * r : r * r * r);
}

template <int DIM>
inline PairSaltdemViscous::Weights
PairSaltdemViscous::pair_weights(const double *radius, int i, int j, int itype, int jtype) const
{
  Weights w = {partner_mass<DIM>(radius, j, i), partner_mass<DIM>(radius, i, j), vol[i], vol[j]};
  if (fluidself[itype] && !fluidself[jtype]) {
    w.mj *= fill[i];
    w.vj = w.mj * irho0[itype];
  } else if (fluidself[jtype] && !fluidself[itype]) {
    w.mi *= fill[j];
    w.vi = w.mi * irho0[jtype];
  }
  return w;
}

template <int DIM>
inline bool PairSaltdemViscous::noslip_pair(int i, int j, int itype, int jtype, double *ov) const
{
  if (!noslip_surface || fluidself[itype] == fluidself[jtype]) return false;
  const double *o = fluidself[itype] ? &slip[3 * j] : &slip[3 * i];
  const double sign = fluidself[itype] ? -1.0 : 1.0;
  for (int k = 0; k < DIM; k++) ov[k] = sign * o[k];
  return true;
}

/* the salt laws: FLUID pairs need only positions and velocities of the centres and make no
   torque; q: the pair's terms of the continuity equation for i and j, mu_ij v_ij . grad_i W_ij
   and mu_ji v_ij . grad_i W_ij (pair_weights) */

template <int DIM, int EVFLAG>
int PairSaltdemViscous::law(const Atoms &a, int i, int j, int itype, int jtype, double r, double *,
                            bool, double *f, double *ti, double *tj, double &evdwl, double *q) const
{
  const SaltDEM::ViscousParams &p = params[itype][jtype];
  if (p.mode == SaltDEM::VISCOUS_FLUID) {
    const double d[3] = {a.x[i][0] - a.x[j][0], a.x[i][1] - a.x[j][1],
                         (DIM == 3) ? a.x[i][2] - a.x[j][2] : 0.0};
    const double vr[3] = {a.v[i][0] - a.v[j][0], a.v[i][1] - a.v[j][1],
                          (DIM == 3) ? a.v[i][2] - a.v[j][2] : 0.0};
    const Weights w = pair_weights<DIM>(a.radius, i, j, itype, jtype);
    // SPH pressure mu_ij A_i + mu_ji A_j with the corrected pressure matrices A (pre_loop); a
    // particle that is not fluid (wall, cover) mirrors the fluid's
    double pm[SaltDEM::NSYM];
    SaltDEM::pressure_pair<DIM>(isfluid[itype], isfluid[jtype], w.mi, w.mj,
                                &pmat[Layout<DIM>::NS * i], &pmat[Layout<DIM>::NS * j], pm);
    // noslip surface: a boundary partner shows the fluid its extrapolated velocity
    double ov[3] = {0.0, 0.0, 0.0};
    noslip_pair<DIM>(i, j, itype, jtype, ov);
    double divw = 0.0;
    const bool touch = SaltDEM::viscous_fluid_force<DIM, EVFLAG>(
        p, d, vr, ov, r, a.radius[i] + a.radius[j], w.vi, w.vj, pm, f, evdwl, divw);
    q[0] = w.mj * divw;
    q[1] = w.mi * divw;
    return touch ? LAW_TOUCH : 0;
  }
  SaltDEM::Contact c;
  SaltDEM::contact_kinematics<DIM>(a.x[i], a.x[j], a.v[i], a.v[j], a.omega[i], a.omega[j],
                                   a.radius[i], a.radius[j], a.rmass[i], a.rmass[j], r, c, false);
  return (SaltDEM::viscous_contact_force<DIM, EVFLAG>(p, c, f, ti, tj, evdwl) ? LAW_TOUCH : 0) |
      LAW_TORQUE;
}

}    // namespace LAMMPS_NS

#endif
