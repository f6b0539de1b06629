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

   The cover's law policy for the shared pair loop (PairSaltdem::loop, saltdem_pair_loop.h):
   SaltDEM::cohesive_force (saltdem_contact_cohesive.h) with its shear history.  Only the style's .cpp
   files include it.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_COHESIVE_LAW_H
#define LMP_SALTDEM_COHESIVE_LAW_H

#include "pair_saltdem.h"
#include "saltdem_contact_cohesive.h"

namespace LAMMPS_NS {
namespace SaltDEM {

  struct CohesiveLaw {
    static constexpr bool HISTORY = true;      // the law keeps values per touching pair
    static constexpr bool PAIR_SUM = false;    // no per-atom sum
    const CohesiveParams *const *params;
    bool rolling;    // any pair with rolling resistance: 3 more history values
    double dt;

    template <int DIM, int EVFLAG>
    int force(const PairSaltdem::Atoms &a, int i, int j, int itype, int jtype, double r,
              double *hist, bool advance, double *f, double *ti, double *tj, double &evdwl,
              double *) const
    {
      Contact c;
      contact_kinematics<DIM>(a.x[i], a.x[j], a.v[i], a.v[j], a.omega[i], a.omega[j], a.radius[i],
                              a.radius[j], a.rmass[i], a.rmass[j], r, c, rolling);
      return cohesive_force<DIM, EVFLAG>(params[itype][jtype], c, hist, rolling, dt, advance, f, ti,
                                         tj, evdwl)
          ? (PairSaltdem::LAW_TOUCH | PairSaltdem::LAW_TORQUE)
          : 0;
    }
  };

}    // namespace SaltDEM
}    // namespace LAMMPS_NS

#endif
