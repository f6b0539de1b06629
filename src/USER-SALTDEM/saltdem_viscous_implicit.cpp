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

/* Backward Euler for the viscosity.  The force pass computed the Morris force -L v at the
   step's velocities, so f is the explicit step's net force.  The end velocities u = v + d of
   the integrated atoms solve
     d_i / k_i + sum_j g_ij (d_i - d_j) = f_i,    k_i = dt / (S m_i),
   with d = 0 for the atoms that are not integrated (walls): (M / dt + L) u = M v / dt + F_other.
   The matrix is symmetric positive definite (a weighted graph Laplacian plus a positive
   diagonal), so conjugate gradients with the diagonal as preconditioner solve it from d = 0.
   The correction -L d is added to f (its rows for the walls too), so that f holds the viscous
   force at the end velocities: the integrator's kicks then give each particle d over the step.
   -L d comes from the products of the iterations (-L d = sum_k alpha_k (-L p_k)), so a solve
   costs one pass over the stored pairs per iteration.  A velocity mode that the explicit step
   would amplify by 1 - k lambda decays by 1 / (1 + k lambda), for any dt, and a steady flow
   (d = 0) keeps its viscous stress exactly.  Every pair's part is equal and opposite, so
   momentum is kept pairwise. */

template <int DIM> void SaltdemViscousSplit::run_implicit(double tol, int maxiter)
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int newton_pair = force->newton_pair;
  double **f = atom->f;
  const int *mask = atom->mask;
  const double *m = atom->rmass;
  const int *type = atom->type;
  const double *radius = atom->radius;
  SaltDEM::SphFields &fields = *pair->fields;
  double *del = usub.data(), *q = fsub.data(), *r = res.data(), *p = dir.data();
  double *z = pres.data(), *d = diag.data(), *k = ksub.data(), *corr = fother.data();

  // dt over the inertial mass (0: not integrated), owned and ghost
  const double kdt = update->dt * force->ftm2v;
  for (int i = 0; i < nall; i++) {
    const double scale = PairSaltdemViscous::inertia_scale(mask[i], pair->integrators);
    k[i] = (scale > 0.0) ? kdt / (scale * m[i]) : 0.0;
  }
  // the pair weights g_ij = c V_i V_j (the force pass's) and the diagonal 1 / k_i + sum_j g_ij
  // (its ghosts' parts home in the first slot of p)
  for (int i = 0; i < 3 * (newton_pair ? nall : nlocal); i++) p[i] = 0.0;
  for (auto &list : fields.pairs)
    for (auto &sp : list) {
      const SaltDEM::Weights w =
          fields.pair_weights<DIM>(radius, sp.i, sp.j, type[sp.i], type[sp.j]);
      sp.c *= w.vi * w.vj;
      p[3 * sp.i] += sp.c;
      if (newton_pair || sp.j < nlocal) p[3 * sp.j] += sp.c;
    }
  rev = p;
  if (newton_pair) comm->reverse_comm(pair);
  for (int i = 0; i < nlocal; i++) d[i] = (k[i] > 0.0) ? 1.0 / k[i] + p[3 * i] : 0.0;

  auto dots = [&](double *out) {
    double local[2] = {0.0, 0.0};
    for (int i = 0; i < nlocal; i++)
      for (int c3 = 0; c3 < DIM; c3++) {
        local[0] += r[3 * i + c3] * r[3 * i + c3];
        local[1] += r[3 * i + c3] * z[3 * i + c3];
      }
    MPI_Allreduce(local, out, 2, MPI_DOUBLE, MPI_SUM, world);
  };
  for (int i = 0; i < 3 * nall; i++) p[i] = del[i] = 0.0;
  for (int i = 0; i < 3 * nlocal; i++) corr[i] = 0.0;
  for (int i = 0; i < nlocal; i++)
    for (int c3 = 0; c3 < DIM; c3++) {
      const bool free = k[i] > 0.0;
      r[3 * i + c3] = free ? f[i][c3] : 0.0;
      z[3 * i + c3] = free ? r[3 * i + c3] / d[i] : 0.0;
      p[3 * i + c3] = z[3 * i + c3];
    }
  double sums[2];
  dots(sums);
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
    laplacian<DIM>(p, q, false, 1.0);    // q = -L p
    double pq = 0.0, pqall = 0.0;
    for (int i = 0; i < nlocal; i++)
      if (k[i] > 0.0)
        for (int c3 = 0; c3 < DIM; c3++)
          pq += p[3 * i + c3] * (p[3 * i + c3] / k[i] - q[3 * i + c3]);
    MPI_Allreduce(&pq, &pqall, 1, MPI_DOUBLE, MPI_SUM, world);
    if (!(pqall > 0.0) || !std::isfinite(pqall))
      error->all(FLERR,
                 "Pair style {}: the implicit viscous step broke down at step {} (p.Ap = {:.3g}, "
                 "not positive): a non-finite velocity or force; shorten the time step",
                 pair->name_of(), update->ntimestep, pqall);
    const double alpha = rz / pqall;
    for (int i = 0; i < nlocal; i++)
      for (int c3 = 0; c3 < DIM; c3++) {
        corr[3 * i + c3] += alpha * q[3 * i + c3];
        if (k[i] > 0.0) {
          del[3 * i + c3] += alpha * p[3 * i + c3];
          r[3 * i + c3] -= alpha * (p[3 * i + c3] / k[i] - q[3 * i + c3]);
          z[3 * i + c3] = r[3 * i + c3] / d[i];
        }
      }
    dots(sums);
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

  for (int i = 0; i < nlocal; i++)
    for (int c3 = 0; c3 < DIM; c3++) f[i][c3] += corr[3 * i + c3];
  // the correction's pair forces into the virial (the force pass tallied the explicit ones)
  if (pair->evflag && iter > 0) {
    fwd = del;
    comm->forward_comm(pair);
    laplacian<DIM>(del, q, true, 1.0);
  }
}
