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

   The salt's law policy for the shared pair loop (PairSaltdem::loop, saltdem_pair_loop.h):
   FLUID pairs need only positions and velocities of the centres and make no torque, and feed
   the continuity sum; CONTACT pairs are dashpots at the contact point.  The math is in
   saltdem_contact_viscous.h; the fields it reads (volumes, pressure matrices, no-slip offsets) are
   the pair style's SphFields.  Only the style's .cpp files include it.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_VISCOUS_LAW_H
#define LMP_SALTDEM_VISCOUS_LAW_H

#include "pair_saltdem.h"
#include "saltdem_contact_viscous.h"
#include "saltdem_sph_fields.h"

namespace LAMMPS_NS {
namespace SaltDEM {

  struct ViscousLaw {
    static constexpr bool HISTORY = false;    // no values kept per pair
    static constexpr bool PAIR_SUM = true;    // d rho / dt of the continuity equation
    const ViscousParams *const *params;
    const int *isfluid;    // per type: FLUID with K > 0 (carries pressure)
    const SphFields *fields;

    // q: i's and j's terms mu_ij v_ij . grad_i W_ij and mu_ji v_ij . grad_i W_ij of the
    // continuity equation (SphFields::pair_weights)
    template <int DIM, int EVFLAG>
    int force(const PairSaltdem::Atoms &a, int i, int j, int itype, int jtype, double r, double *,
              bool, double *f, double *ti, double *tj, double &evdwl, double *q) const
    {
      const ViscousParams &p = params[itype][jtype];
      if (p.mode == VISCOUS_FLUID) {
        const double d[3] = {a.x[i][0] - a.x[j][0], a.x[i][1] - a.x[j][1],
                             (DIM == 3) ? a.x[i][2] - a.x[j][2] : 0.0};
        const double vr[3] = {a.v[i][0] - a.v[j][0], a.v[i][1] - a.v[j][1],
                              (DIM == 3) ? a.v[i][2] - a.v[j][2] : 0.0};
        const Weights w = fields->pair_weights<DIM>(a.radius, i, j, itype, jtype);
        // SPH pressure mu_ij A_i + mu_ji A_j with the corrected pressure matrices A; a
        // particle that is not fluid (wall, cover) mirrors the fluid's
        double pm[NSYM];
        const double *pmat = fields->pmat.data();
        pressure_pair<DIM>(isfluid[itype], isfluid[jtype], w.mi, w.mj,
                           &pmat[SphLayout<DIM>::NS * i], &pmat[SphLayout<DIM>::NS * j], pm);
        // noslip surface: a boundary partner shows the fluid its extrapolated velocity
        double ov[3] = {0.0, 0.0, 0.0};
        fields->noslip_pair<DIM>(i, j, itype, jtype, ov);
        double divw = 0.0;
        const bool touch = viscous_fluid_force<DIM, EVFLAG>(
            p, d, vr, ov, r, a.radius[i] + a.radius[j], w.vi, w.vj, pm, f, evdwl, divw);
        q[0] = w.mj * divw;
        q[1] = w.mi * divw;
        return touch ? PairSaltdem::LAW_TOUCH : 0;
      }
      Contact c;
      contact_kinematics<DIM>(a.x[i], a.x[j], a.v[i], a.v[j], a.omega[i], a.omega[j], a.radius[i],
                              a.radius[j], a.rmass[i], a.rmass[j], r, c, false);
      return (viscous_contact_force<DIM, EVFLAG>(p, c, f, ti, tj, evdwl) ? PairSaltdem::LAW_TOUCH
                                                                         : 0) |
          PairSaltdem::LAW_TORQUE;
    }
  };

}    // namespace SaltDEM
}    // namespace LAMMPS_NS

#endif
