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
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(saltdem/nve,FixSaltdemNVE);
// clang-format on
#else

#ifndef LMP_FIX_SALTDEM_NVE_H
#define LMP_FIX_SALTDEM_NVE_H

#include "fix.h"

namespace LAMMPS_NS {

class FixSaltdemNVE : public Fix {
 public:
  FixSaltdemNVE(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void initial_integrate(int) override;
  void final_integrate() override;
  void reset_dt() override;
  void *extract(const char *, int &) override;

 protected:
  double inertia;                     // inertial mass = inertia * rmass (quasi-static mass scaling)
  int check_every;                    // steps between finite-value checks (0: never)
  double dtv, dtf, inertia_factor;    // moment of inertia = inertia_factor * m r^2
  void check_finite();
  // the half-kick (and with drift the drift) of the owned atoms [ifrom, ito): the serial fix
  // integrates all of them, its OpenMP variant each thread a range
  virtual void integrate_all(bool drift);
  void integrate_range(int ifrom, int ito, bool drift);
  template <int DIM, bool DRIFT> void integrate(int ifrom, int ito);
};

}    // namespace LAMMPS_NS

#endif
#endif
