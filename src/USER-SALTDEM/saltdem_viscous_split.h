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

   SaltdemViscousSplit: the Morris viscosity of pair saltdem/viscous beyond its explicit limit,
   applied once all other forces of the step are in.  The viscosity is a linear operator on
   the velocities (a graph Laplacian L weighted by g_ij = kvisc V_i V_j (1 - r/2h)^3 over the
   FLUID pairs), taken at the step's frozen positions and coefficients:
   - sub-steps (substeps N > 1, saltdem_viscous_substeps.cpp): the force pass leaves it out;
     N explicit steps of dt/N with the other forces held constant, whose mean force is added;
     the stable limit grows N-fold;
   - implicit (saltdem_viscous_implicit.cpp): the force pass keeps it; a backward-Euler
     correction, solved by preconditioned conjugate gradients, is added; no viscous limit, and
     a steady flow keeps its exact stress.
   Owned by the pair style, which carries its communication.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_VISCOUS_SPLIT_H
#define LMP_SALTDEM_VISCOUS_SPLIT_H

#include "pointers.h"

#include <vector>

namespace LAMMPS_NS {

class SaltdemViscousSplit : protected Pointers {
 public:
  SaltdemViscousSplit(class LAMMPS *, class PairSaltdemViscous *);
  void grow(int n);                          // room for n atoms
  void substeps(int n);                      // n explicit sub-steps of the present step
  void implicit(double tol, int maxiter);    // one implicit step
  double memory_usage() const;
  // a vector (3 per atom) to the ghosts, the ghosts' part of another home (added)
  int pack_forward_comm(int n, const int *list, double *buf) const;
  void unpack_forward_comm(int n, int first, const double *buf);
  int pack_reverse_comm(int n, int first, double *buf) const;
  void unpack_reverse_comm(int n, const int *list, const double *buf);

  // implicit: iterations of the last step, their sum and the steps solved since the last
  // reset, and the last step's residual over the residual at the start velocities
  int iter_last = 0;
  double iter_sum = 0.0, solves = 0.0, resid_last = 0.0;

 private:
  class PairSaltdemViscous *pair;
  // per atom (3 values; owned and ghost): the velocities being solved for and the viscous
  // force of a pass; dt (or dt/N) over the inertial mass (0: not integrated, e.g. walls);
  // the other forces of the step (owned)
  std::vector<double> usub, fsub, ksub, fother;
  // implicit: residual, search direction, preconditioned residual, diagonal
  std::vector<double> res, dir, pres, diag;
  std::vector<double> out_thr;    // several threads: their slices of a pass's forces
  double *fwd = nullptr;          // what forward communication sends (3 per atom)
  double *rev = nullptr;          // what reverse communication adds to (3 per atom)

  void step_over_mass(double kdt);                      // ksub of the owned and ghost atoms
  template <int DIM> void weigh_pairs(double *sums);    // the stored pairs' g_ij, per-atom sums
  template <int DIM> void prepare(double kdt);
  template <int DIM> void laplacian(const double *u, double *out, bool tally, double scale);
  template <int DIM> void run_substeps(int n);
  template <int DIM> void run_implicit(double tol, int maxiter);
};

}    // namespace LAMMPS_NS

#endif
