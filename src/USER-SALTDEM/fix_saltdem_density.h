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
FixStyle(SALTDEM_DENSITY,FixSaltdemDensity);
// clang-format on
#else

#ifndef LMP_FIX_SALTDEM_DENSITY_H
#define LMP_FIX_SALTDEM_DENSITY_H

#include "fix.h"

namespace LAMMPS_NS {

/* Internal fix of pair style saltdem/viscous (not for input scripts), created by the pair
   style as LAMMPS's SPH package splits the work: the pair style computes d rho / dt of the
   fluid particles in its force pass, this fix owns the state.
   - the per-atom continuity density rho of the fluid particles (0 until set), which
     migrates with the atoms and goes to restart files, and its rate d rho / dt (owned and
     ghost atoms; the pair style sums into it);
   - the reference density rho0 of each fluid type (0 until measured) and the kernel h it was
     measured with;
   - setup: the reference density of a fluid type that has none (or whose h changed) is
     measured, the mean kernel density of its particles; particles without a density start
     at it;
   - the integrator's stage (final_integrate): rho += dt d rho / dt; minimization and run 0
     leave it alone;
   - restart: rho0 and h per type (global) and rho per atom. */

class FixSaltdemDensity : public Fix {
 public:
  FixSaltdemDensity(class LAMMPS *, int, char **);
  ~FixSaltdemDensity() override;
  int setmask() override;
  void init() override;
  void setup_pre_force(int) override;
  void setup(int) override;
  void post_force(int) override;
  void post_run() override;
  void final_integrate() override;

  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;

  class PairSaltdemViscous *pair;    // the pair style that owns this fix (sets it at init)
  double *rho;                       // per-atom continuity density (0: not set)
  double *drho;                      // per-atom d rho / dt of the last force pass, owned + ghost
  std::vector<double> rho0;          // per type: reference density (0: not measured)
  std::vector<double> h0;            // per type: the kernel h rho0 was measured with

  // the restart layout of this fix (its global data begins with it)
  static constexpr double RESTART_VERSION = 1.0;

 protected:
  int restored;    // the reference densities came from a restart file (for the log)
  void measure();
};

}    // namespace LAMMPS_NS

#endif
#endif
