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

   SaltdemViscousSubsteps: the viscous sub-steps of pair saltdem/viscous (substeps N > 1).
   The Morris viscosity is a linear operator on the velocities (a graph Laplacian weighted by
   g_ij = kvisc V_i V_j (1 - r/2h)^3).  With sub-steps the force pass leaves it out and this
   applies it once all forces of the step are in: N explicit steps of dt/N on the velocities
   at the frozen positions and coefficients, whose mean force is added to each particle.  The
   viscous stable limit grows N-fold for about the cost of one pass over the stored pairs per
   sub-step.  Owned by the pair style, which carries its communication.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_VISCOUS_SUBSTEPS_H
#define LMP_SALTDEM_VISCOUS_SUBSTEPS_H

#include "pointers.h"

namespace LAMMPS_NS {

class SaltdemViscousSubsteps : protected Pointers {
 public:
  SaltdemViscousSubsteps(class LAMMPS *, class PairSaltdemViscous *);
  void grow(int n);     // room for n atoms
  void apply(int n);    // n sub-steps of the present step
  double memory_usage() const;
  // the sub-step velocities to the ghosts, the ghosts' sub-step forces home
  int pack_forward_comm(int n, const int *list, double *buf) const;
  void unpack_forward_comm(int n, int first, const double *buf);
  int pack_reverse_comm(int n, int first, double *buf) const;
  void unpack_reverse_comm(int n, const int *list, const double *buf);

 private:
  class PairSaltdemViscous *pair;
  // sub-step velocities and forces (3 per atom, owned and ghost), dt/N over the inertial mass
  // and the step's other forces (owned atoms)
  std::vector<double> usub, fsub, ksub, fother;
  template <int DIM> void run(int n);
};

}    // namespace LAMMPS_NS

#endif
