/* ----------------------------------------------------------------------
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

   The implicit viscous step of pair saltdem/viscous (implicit yes; SaltdemViscousSplit, see
   the header).
------------------------------------------------------------------------- */

#include "saltdem_viscous_split.h"

#include "pair_saltdem_viscous.h"
#include "saltdem_sph_fields.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;

void SaltdemViscousSplit::implicit(double tol, int maxiter)
{
  pair->comm_mode = PairSaltdemViscous::COMM_SUBSTEP;
  if (domain->dimension == 2)
    run_implicit<2>(tol, maxiter);
  else
    run_implicit<3>(tol, maxiter);
  pair->comm_mode = PairSaltdemViscous::COMM_PRESSURE;
}

/* Backward Euler for the viscosity: the end velocities u of the integrated atoms solve
     u_i / k_i + sum_j g_ij (u_i - u_j) = v_i / k_i + F_i,    k_i = dt / (S m_i),
   with F_i the step's other forces and u = v for the atoms that are not integrated (walls).
   The matrix is symmetric positive definite (a weighted graph Laplacian plus a positive
   diagonal), so conjugate gradients with the diagonal as preconditioner solve it, starting at
   u = v, where the residual is the net force of the explicit step.  The viscous force
   -sum_j g_ij (u_i - u_j) at the solution is added to f: the integrator's kicks then give
   each particle u - v over the step.  A velocity mode that the explicit step would amplify
   by 1 - k lambda decays by 1 / (1 + k lambda), for any dt, and a steady flow (u = v) keeps
   its viscous stress exactly.  Every pair's force is equal and opposite, so momentum is
   kept pairwise. */

template <int DIM> void SaltdemViscousSplit::run_implicit(double tol, int maxiter)
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int newton_pair = force->newton_pair;
  double **f = atom->f;
  prepare<DIM>(update->dt * force->ftm2v);
  double *u = usub.data(), *q = fsub.data(), *r = res.data(), *p = dir.data(), *z = pres.data();
  double *d = diag.data();
  const double *k = ksub.data(), *fo = fother.data();

  // the diagonal: 1 / k_i + sum_j g_ij (its ghosts' parts home in the first slot of p)
  for (int i = 0; i < 3 * (newton_pair ? nall : nlocal); i++) p[i] = 0.0;
  for (const auto &list : pair->fields->pairs)
    for (const auto &sp : list) {
      p[3 * sp.i] += sp.c;
      if (newton_pair || sp.j < nlocal) p[3 * sp.j] += sp.c;
    }
  rev = p;
  if (newton_pair) comm->reverse_comm(pair);
  for (int i = 0; i < nlocal; i++) d[i] = (k[i] > 0.0) ? 1.0 / k[i] + p[3 * i] : 0.0;

  // start at u = v: the residual is the net force of the integrated atoms
  laplacian<DIM>(u, q, false, 1.0);
  auto dots = [&](const double *a, const double *b, const double *c, const double *e, double *out) {
    double local[2] = {0.0, 0.0};
    for (int i = 0; i < nlocal; i++)
      for (int c3 = 0; c3 < DIM; c3++) {
        local[0] += a[3 * i + c3] * b[3 * i + c3];
        local[1] += c[3 * i + c3] * e[3 * i + c3];
      }
    MPI_Allreduce(local, out, 2, MPI_DOUBLE, MPI_SUM, world);
  };
  for (int i = 0; i < nall; i++)
    for (int c3 = 0; c3 < 3; c3++) p[3 * i + c3] = 0.0;
  for (int i = 0; i < nlocal; i++)
    for (int c3 = 0; c3 < 3; c3++) {
      const bool free = k[i] > 0.0 && c3 < DIM;
      r[3 * i + c3] = free ? fo[3 * i + c3] + q[3 * i + c3] : 0.0;
      z[3 * i + c3] = free ? r[3 * i + c3] / d[i] : 0.0;
      p[3 * i + c3] = z[3 * i + c3];
    }
  double sums[2];
  dots(r, r, r, z, sums);
  const double ref = sqrt(sums[0]);
  if (!std::isfinite(ref))
    error->all(FLERR,
               "Pair style {}: the implicit viscous step at step {} starts from a non-finite "
               "force or velocity; shorten the time step",
               pair->name_of(), update->ntimestep);
  double rz = sums[1], rnorm = ref;
  int iter = 0;
  while (rnorm > tol * ref) {
    if (iter == maxiter)
      error->all(FLERR,
                 "Pair style {}: the implicit viscous step did not converge at step {}: residual "
                 "{:.3g} of the start's after maxiter {} iterations (tolerance {:.3g}). Raise "
                 "maxiter or tolerance, or shorten the time step",
                 pair->name_of(), update->ntimestep, rnorm / ref, maxiter, tol);
    fwd = p;
    comm->forward_comm(pair);
    laplacian<DIM>(p, q, false, 1.0);
    double pq = 0.0, pqall = 0.0;
    for (int i = 0; i < nlocal; i++)
      if (k[i] > 0.0)
        for (int c3 = 0; c3 < DIM; c3++) {
          q[3 * i + c3] = p[3 * i + c3] / k[i] - q[3 * i + c3];
          pq += p[3 * i + c3] * q[3 * i + c3];
        }
    MPI_Allreduce(&pq, &pqall, 1, MPI_DOUBLE, MPI_SUM, world);
    if (!(pqall > 0.0) || !std::isfinite(pqall))
      error->all(FLERR,
                 "Pair style {}: the implicit viscous step broke down at step {} (p.Ap = {:.3g}, "
                 "not positive): a non-finite velocity or force; shorten the time step",
                 pair->name_of(), update->ntimestep, pqall);
    const double alpha = rz / pqall;
    for (int i = 0; i < nlocal; i++)
      if (k[i] > 0.0)
        for (int c3 = 0; c3 < DIM; c3++) {
          u[3 * i + c3] += alpha * p[3 * i + c3];
          r[3 * i + c3] -= alpha * q[3 * i + c3];
          z[3 * i + c3] = r[3 * i + c3] / d[i];
        }
    dots(r, r, r, z, sums);
    rnorm = sqrt(sums[0]);
    const double beta = sums[1] / rz;
    rz = sums[1];
    for (int i = 0; i < nlocal; i++)
      for (int c3 = 0; c3 < DIM; c3++) p[3 * i + c3] = z[3 * i + c3] + beta * p[3 * i + c3];
    iter++;
  }
  iter_last = iter;
  iter_sum += iter;
  solves += 1.0;
  resid_last = ref > 0.0 ? rnorm / ref : 0.0;

  // the viscous force at the end velocities, tallied once
  if (iter > 0) {
    fwd = u;
    comm->forward_comm(pair);
  }
  laplacian<DIM>(u, q, pair->evflag, 1.0);
  for (int i = 0; i < nlocal; i++)
    for (int c3 = 0; c3 < DIM; c3++) f[i][c3] += q[3 * i + c3];
}
