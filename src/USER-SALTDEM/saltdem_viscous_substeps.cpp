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

   The viscous sub-steps of pair saltdem/viscous (SaltdemViscousSubsteps, see the header).
------------------------------------------------------------------------- */

#include "saltdem_viscous_substeps.h"

#include "pair_saltdem_viscous.h"
#include "saltdem_sph_fields.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "force.h"
#include "update.h"

using namespace LAMMPS_NS;

SaltdemViscousSubsteps::SaltdemViscousSubsteps(LAMMPS *lmp, PairSaltdemViscous *owner) :
    Pointers(lmp), pair(owner)
{
}

void SaltdemViscousSubsteps::grow(int n)
{
  if ((int) ksub.size() >= n) return;
  usub.resize(3 * (size_t) n);
  fsub.resize(3 * (size_t) n);
  ksub.resize(n);
  fother.resize(3 * (size_t) n);
}

double SaltdemViscousSubsteps::memory_usage() const
{
  return (double) (usub.capacity() + fsub.capacity() + ksub.capacity() + fother.capacity()) *
      sizeof(double);
}

void SaltdemViscousSubsteps::apply(int n)
{
  pair->comm_mode = PairSaltdemViscous::COMM_SUBSTEP;
  if (domain->dimension == 2)
    run<2>(n);
  else
    run<3>(n);
  pair->comm_mode = PairSaltdemViscous::COMM_PRESSURE;
}

/* the Morris viscosity of the stored pairs (SphFields::pairs) as n explicit steps of dt/n on
   copies of the velocities (positions, volumes and coefficients as in the force pass, the
   other forces of the step held constant), each pair's force -g_ij (u_i - u_j) at every
   sub-step; the mean force over the sub-steps is added to f, so that the integrator's step
   gives each particle the velocity change of the sub-steps.  Atoms that no fix integrates or
   whose motion is prescribed (walls) keep their velocity. */

template <int DIM> void SaltdemViscousSubsteps::run(int n)
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int newton_pair = force->newton_pair;
  const double *const *v = atom->v;
  const double *const *x = atom->x;
  double **f = atom->f;
  const int *mask = atom->mask;
  const double *m = atom->rmass;
  const double hdt = update->dt * force->ftm2v / n;
  const double inv_n = 1.0 / n;
  const bool evflag = pair->evflag;
  SaltDEM::SphFields &fields = *pair->fields;
  std::vector<SaltDEM::SubPair> &subpairs = fields.pairs;
  double *usub = this->usub.data(), *fsub = this->fsub.data();
  double *ksub = this->ksub.data(), *fother = this->fother.data();

  for (int i = 0; i < nall; i++)
    for (int k = 0; k < 3; k++) usub[3 * i + k] = v[i][k];
  // the other forces of the step, held constant over the sub-steps, and dt/N over the
  // inertial mass of the owned atoms (0 for walls)
  for (int i = 0; i < nlocal; i++) {
    for (int k = 0; k < 3; k++) fother[3 * i + k] = f[i][k];
    const double scale = PairSaltdemViscous::inertia_scale(mask[i], pair->integrators);
    ksub[i] = (scale > 0.0) ? hdt / (scale * m[i]) : 0.0;
  }

  // the pair weights g_ij = c V_i V_j (the volumes of the force pass, pair_weights), once
  const int *type = atom->type;
  const double *radius = atom->radius;
  for (auto &sp : subpairs) {
    const SaltDEM::Weights w = fields.pair_weights<DIM>(radius, sp.i, sp.j, type[sp.i], type[sp.j]);
    sp.c *= w.vi * w.vj;
  }
  // noslip surface: the boundary partners' offsets (of the step's start) add a force that
  // the sub-steps hold constant, as the other forces (its ghosts' parts go home once)
  if (fields.noslip) {
    for (int i = 0; i < 3 * (newton_pair ? nall : nlocal); i++) fsub[i] = 0.0;
    for (const auto &sp : subpairs) {
      // -c (v_i - v_j + o_i - o_j) less the plain -c (v_i - v_j)
      double ov[3] = {0.0, 0.0, 0.0}, fp[3] = {0.0, 0.0, 0.0};
      if (!fields.noslip_pair<DIM>(sp.i, sp.j, type[sp.i], type[sp.j], ov)) continue;
      for (int k = 0; k < DIM; k++) {
        fp[k] = -sp.c * ov[k];
        fsub[3 * sp.i + k] += fp[k];
        if (newton_pair || sp.j < nlocal) fsub[3 * sp.j + k] -= fp[k];
      }
      if (evflag)
        pair->ev_tally_xyz(sp.i, sp.j, nlocal, newton_pair, 0.0, 0.0, fp[0], fp[1], fp[2],
                           x[sp.i][0] - x[sp.j][0], x[sp.i][1] - x[sp.j][1],
                           (DIM == 3) ? x[sp.i][2] - x[sp.j][2] : 0.0);
    }
    if (newton_pair) comm->reverse_comm(pair);
    for (int i = 0; i < nlocal; i++)
      for (int k = 0; k < DIM; k++) {
        f[i][k] += fsub[3 * i + k];
        fother[3 * i + k] += fsub[3 * i + k];
      }
  }
  const SaltDEM::SubPair *begin = subpairs.data(), *end = begin + subpairs.size();
  for (int step = 0; step < n; step++) {
    for (int i = 0; i < 3 * (newton_pair ? nall : nlocal); i++) fsub[i] = 0.0;
    // the pairs come grouped by i (SphFields::kernel_moments): i's sum is kept in registers
    for (const SaltDEM::SubPair *sp = begin; sp < end;) {
      const int i = sp->i;
      const double ui[3] = {usub[3 * i], usub[3 * i + 1], usub[3 * i + 2]};
      double fi[3] = {0.0, 0.0, 0.0};
      for (; sp < end && sp->i == i; ++sp) {
        const int j = sp->j;
        double fp[3] = {0.0, 0.0, 0.0};
        for (int k = 0; k < DIM; k++) {
          fp[k] = -sp->c * (ui[k] - usub[3 * j + k]);
          fi[k] += fp[k];
        }
        if (newton_pair || j < nlocal)
          for (int k = 0; k < DIM; k++) fsub[3 * j + k] -= fp[k];
        if (evflag)
          pair->ev_tally_xyz(i, j, nlocal, newton_pair, 0.0, 0.0, fp[0] * inv_n, fp[1] * inv_n,
                             fp[2] * inv_n, x[i][0] - x[j][0], x[i][1] - x[j][1],
                             (DIM == 3) ? x[i][2] - x[j][2] : 0.0);
      }
      for (int k = 0; k < DIM; k++) fsub[3 * i + k] += fi[k];
    }
    if (newton_pair) comm->reverse_comm(pair);
    for (int i = 0; i < nlocal; i++)
      for (int k = 0; k < DIM; k++) {
        f[i][k] += fsub[3 * i + k] * inv_n;
        usub[3 * i + k] += ksub[i] * (fsub[3 * i + k] + fother[3 * i + k]);
      }
    if (step + 1 < n) comm->forward_comm(pair);
  }
}

int SaltdemViscousSubsteps::pack_forward_comm(int n, const int *list, double *buf) const
{
  int k = 0;
  for (int i = 0; i < n; i++)
    for (int c = 0; c < 3; c++) buf[k++] = usub[3 * list[i] + c];
  return k;
}

void SaltdemViscousSubsteps::unpack_forward_comm(int n, int first, const double *buf)
{
  int k = 0;
  for (int i = first; i < first + n; i++)
    for (int c = 0; c < 3; c++) usub[3 * i + c] = buf[k++];
}

int SaltdemViscousSubsteps::pack_reverse_comm(int n, int first, double *buf) const
{
  int k = 0;
  for (int i = first; i < first + n; i++)
    for (int c = 0; c < 3; c++) buf[k++] = fsub[3 * i + c];
  return k;
}

void SaltdemViscousSubsteps::unpack_reverse_comm(int n, const int *list, const double *buf)
{
  int k = 0;
  for (int i = 0; i < n; i++)
    for (int c = 0; c < 3; c++) fsub[3 * list[i] + c] += buf[k++];
}
