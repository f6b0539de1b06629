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

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

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
  SaltDEM::SphFields &fields = *pair->fields;
  double *del = usub.data(), *q = fsub.data(), *r = res.data(), *p = dir.data();
  double *z = pres.data(), *d = diag.data(), *k = ksub.data(), *corr = fother.data();

  step_over_mass(update->dt * force->ftm2v);
  // the pair weights and the diagonal 1 / k_i + sum_j g_ij (the sums' ghost parts home in the
  // first slot of p)
  weigh_pairs<DIM>(z);
  const std::size_t nrow = newton_pair ? nall : nlocal;
  for (std::size_t i = 0; i < nrow; i++) {
    p[3 * i] = z[i];
    p[3 * i + 1] = p[3 * i + 2] = 0.0;
  }
  rev = p;
  if (newton_pair) comm->reverse_comm(pair);

  // the vector operations over the owned atoms, split between the threads: body(i0, i1, part)
  // with part[0..1] the thread's share of two sums
  const int n = fields.threads();
  std::vector<double> parts(2 * (std::size_t) n);
  auto over_atoms = [&](const std::function<void(int, int, double *)> &body, double *sums) {
    for (auto &x : parts) x = 0.0;
    fields.for_threads([&](int tid) {
      int i0, i1;
      SaltDEM::SphFields::slice(nlocal, tid, n, i0, i1);
      body(i0, i1, &parts[2 * tid]);
    });
    if (!sums) return;
    double local[2] = {0.0, 0.0};
    for (int t = 0; t < n; t++)
      for (int c = 0; c < 2; c++) local[c] += parts[2 * t + c];
    MPI_Allreduce(local, sums, 2, MPI_DOUBLE, MPI_SUM, world);
  };

  // start at d = 0: the residual is the net force of the integrated atoms
  double sums[2];
  over_atoms(
      [&](int i0, int i1, double *part) {
        for (int i = i0; i < i1; i++) {
          const bool free = k[i] > 0.0;
          d[i] = free ? 1.0 / k[i] + p[3 * i] : 0.0;
          for (int c3 = 0; c3 < 3; c3++) {
            const bool use = free && c3 < DIM;
            r[3 * i + c3] = use ? f[i][c3] : 0.0;
            z[3 * i + c3] = use ? r[3 * i + c3] / d[i] : 0.0;
            p[3 * i + c3] = z[3 * i + c3];
            del[3 * i + c3] = corr[3 * i + c3] = 0.0;
            part[0] += r[3 * i + c3] * r[3 * i + c3];
            part[1] += r[3 * i + c3] * z[3 * i + c3];
          }
        }
      },
      sums);
  for (int i = 3 * nlocal; i < 3 * nall; i++) p[i] = del[i] = 0.0;
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
    double pq[2];
    over_atoms(
        [&](int i0, int i1, double *part) {
          for (int i = i0; i < i1; i++)
            if (k[i] > 0.0)
              for (int c3 = 0; c3 < DIM; c3++)
                part[0] += p[3 * i + c3] * (p[3 * i + c3] / k[i] - q[3 * i + c3]);
        },
        pq);
    if (!(pq[0] > 0.0) || !std::isfinite(pq[0]))
      error->all(FLERR,
                 "Pair style {}: the implicit viscous step broke down at step {} (p.Ap = {:.3g}, "
                 "not positive): a non-finite velocity or force; shorten the time step",
                 pair->name_of(), update->ntimestep, pq[0]);
    const double alpha = rz / pq[0];
    over_atoms(
        [&](int i0, int i1, double *part) {
          for (int i = i0; i < i1; i++)
            for (int c3 = 0; c3 < DIM; c3++) {
              const int n = 3 * i + c3;
              corr[n] += alpha * q[n];
              if (k[i] > 0.0) {
                del[n] += alpha * p[n];
                r[n] -= alpha * (p[n] / k[i] - q[n]);
                z[n] = r[n] / d[i];
                part[0] += r[n] * r[n];
                part[1] += r[n] * z[n];
              }
            }
        },
        sums);
    rnorm = sqrt(sums[0]);
    const double beta = sums[1] / rz;
    rz = sums[1];
    over_atoms(
        [&](int i0, int i1, double *) {
          for (int i = i0; i < i1; i++)
            for (int c3 = 0; c3 < DIM; c3++) p[3 * i + c3] = z[3 * i + c3] + beta * p[3 * i + c3];
        },
        nullptr);
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
