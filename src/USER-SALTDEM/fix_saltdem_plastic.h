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
FixStyle(SALTDEM_PLASTIC,FixSaltdemPlastic);
// clang-format on
#else

#ifndef LMP_FIX_SALTDEM_PLASTIC_H
#define LMP_FIX_SALTDEM_PLASTIC_H

#include "fix.h"

namespace LAMMPS_NS {

/* Internal fix of pair style saltdem/viscous (not for input scripts), created by the pair
   style when a fluid type has a plastic strength (fluid ... yield MU C), as it creates
   SALTDEM_DENSITY for the density: the pair style computes the rate of the plastic stress and
   the strength of each fluid particle before its force pass, this fix owns the state.
   - the per-atom plastic stress tau (SaltDEM::NSYM values, saltdem_plastic.h), which migrates
     with the atoms and goes to restart files; its rate and the strength (owned atoms);
   - the integrator's stage (final_integrate): tau += dt d tau / dt, then back onto the yield
     surface; minimization and run 0 leave it alone;
   - per-atom output: the plastic stress (the columns of the pressure matrices' layout) and
     its sqrt(J2) over the strength (1: at yield). */

class FixSaltdemPlastic : public Fix {
 public:
  FixSaltdemPlastic(class LAMMPS *, int, char **);
  ~FixSaltdemPlastic() override;
  int setmask() override;
  void init() override;
  void final_integrate() override;
  void end_of_step() override;

  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  double memory_usage() override;

  class PairSaltdemViscous *pair;    // the pair style that owns this fix (sets it at init)
  double **tau;                      // per-atom plastic stress (NSYM values)
  double **dtau;                     // per-atom rate of the last force pass (owned atoms)
  double *ystress;                   // per-atom strength of the last force pass (owned atoms)

 protected:
  double **out;    // per-atom output: tau, then sqrt(J2) / strength
  int nout;
};

}    // namespace LAMMPS_NS

#endif
#endif
