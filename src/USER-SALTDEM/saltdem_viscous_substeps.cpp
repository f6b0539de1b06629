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

   The viscosity of pair saltdem/viscous outside its force pass (SaltdemViscousSplit, see the
   header): what the sub-steps and the implicit step share, and the sub-steps.
------------------------------------------------------------------------- */

#include "saltdem_viscous_split.h"

#include "pair_saltdem_viscous.h"
#include "saltdem_sph_fields.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "force.h"
#include "update.h"

#include <algorithm>

using namespace LAMMPS_NS;

SaltdemViscousSplit::SaltdemViscousSplit(LAMMPS *lmp, PairSaltdemViscous *owner) :
    Pointers(lmp), pair(owner)
{
}

void SaltdemViscousSplit::grow(int n)
{
  if ((int) ksub.size() >= n) return;
  for (auto *a : {&usub, &fsub, &fother, &res, &dir, &pres}) a->resize(3 * (size_t) n);
  out_thr.clear();
  ksub.resize(n);
  diag.resize(n);
}

double SaltdemViscousSplit::memory_usage() const
{
  double n = 0.0;
  for (const auto *a : {&usub, &fsub, &ksub, &fother, &res, &dir, &pres, &diag, &out_thr})
    n += (double) a->capacity();
  return n * sizeof(double);
}

void SaltdemViscousSplit::substeps(int n)
{
  pair->comm_mode = PairSaltdemViscous::COMM_SUBSTEP;
  if (domain->dimension == 2)
    run_substeps<2>(n);
  else
    run_substeps<3>(n);
  pair->comm_mode = PairSaltdemViscous::COMM_PRESSURE;
}

namespace {
/* body(list, acc) for each pair list of the moment pass (SphFields::pairs), summing n values
   into acc, which starts at 0: out gets the sums.  Several threads (one list each): each sums
   into a slice of its own and the slices are added into out after; serial (e.g. for the
   virial tallies, which are not thread safe): every list into out. */
template <class Body>
void sum_over_pairs(SaltDEM::SphFields &fields, std::vector<double> &slices, std::size_t n,
                    double *out, bool serial, Body body)
{
  const int nt = (int) fields.pairs.size();
  if (nt <= 1 || serial || fields.threads() != nt) {
    std::fill_n(out, n, 0.0);
    for (auto &list : fields.pairs) body(list, out);
    return;
  }
  if (slices.size() < nt * n) slices.resize(nt * n);
  fields.for_threads([&](int tid) {
    double *acc = &slices[tid * n];
    std::fill_n(acc, n, 0.0);
    body(fields.pairs[tid], acc);
  });
  fields.add_slices(slices.data(), nt, n, out);
}
}    // namespace

/* dt (or dt/N) over the inertial mass of each atom, owned and ghost (0 for atoms that no fix
   integrates or whose motion is prescribed: they keep their velocity) */

void SaltdemViscousSplit::step_over_mass(double kdt)
{
  const int nall = atom->nlocal + atom->nghost;
  const int *mask = atom->mask;
  const double *m = atom->rmass;
  for (int i = 0; i < nall; i++) {
    const double scale = PairSaltdemViscous::inertia_scale(mask[i], pair->integrators);
    ksub[i] = (scale > 0.0) ? kdt / (scale * m[i]) : 0.0;
  }
}

/* the pair weights g_ij = c V_i V_j (the volumes of the force pass, pair_weights) of the stored
   pairs, and each atom's sum of its pairs' weights into sums (owned atoms, and the ghosts with
   newton on, whose parts the caller sends home) */

template <int DIM> void SaltdemViscousSplit::weigh_pairs(double *sums)
{
  const int nlocal = atom->nlocal;
  const int newton_pair = force->newton_pair;
  const int *type = atom->type;
  const double *radius = atom->radius;
  SaltDEM::SphFields &fields = *pair->fields;
  const std::size_t nrow = newton_pair ? nlocal + atom->nghost : nlocal;
  sum_over_pairs(fields, out_thr, nrow, sums, false,
                 [&](std::vector<SaltDEM::SubPair> &list, double *acc) {
                   for (auto &sp : list) {
                     const SaltDEM::Weights w =
                         fields.pair_weights<DIM>(radius, sp.i, sp.j, type[sp.i], type[sp.j]);
                     sp.c *= w.vi * w.vj;
                     acc[sp.i] += sp.c;
                     if (newton_pair || sp.j < nlocal) acc[sp.j] += sp.c;
                   }
                 });
}

/* what the sub-steps start from: the velocities usub = v (owned and ghost), dt/N over the
   inertial masses, the other forces of the step (owned) and the pair weights.  noslip surface:
   the boundary partners' offsets (of the step's start) add a force that is held constant, as
   the other forces (its ghosts' parts go home once). */

template <int DIM> void SaltdemViscousSplit::prepare(double kdt)
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int newton_pair = force->newton_pair;
  const double *const *v = atom->v;
  const double *const *x = atom->x;
  double **f = atom->f;
  const int *type = atom->type;
  SaltDEM::SphFields &fields = *pair->fields;

  for (int i = 0; i < nall; i++)
    for (int k = 0; k < 3; k++) usub[3 * i + k] = v[i][k];
  step_over_mass(kdt);
  for (int i = 0; i < nlocal; i++)
    for (int k = 0; k < 3; k++) fother[3 * i + k] = f[i][k];
  weigh_pairs<DIM>(fsub.data());    // (the sums are not needed: fsub is free here)
  if (!fields.noslip) return;
  for (int i = 0; i < 3 * (newton_pair ? nall : nlocal); i++) fsub[i] = 0.0;
  for (const auto &list : fields.pairs)
    for (const auto &sp : list) {
      // -c (v_i - v_j + o_i - o_j) less the plain -c (v_i - v_j)
      double ov[3] = {0.0, 0.0, 0.0}, fp[3] = {0.0, 0.0, 0.0};
      if (!fields.noslip_pair<DIM>(sp.i, sp.j, type[sp.i], type[sp.j], ov)) continue;
      for (int k = 0; k < DIM; k++) {
        fp[k] = -sp.c * ov[k];
        fsub[3 * sp.i + k] += fp[k];
        if (newton_pair || sp.j < nlocal) fsub[3 * sp.j + k] -= fp[k];
      }
      if (pair->evflag)
        pair->ev_tally_xyz(sp.i, sp.j, nlocal, newton_pair, 0.0, 0.0, fp[0], fp[1], fp[2],
                           x[sp.i][0] - x[sp.j][0], x[sp.i][1] - x[sp.j][1],
                           (DIM == 3) ? x[sp.i][2] - x[sp.j][2] : 0.0);
    }
  rev = fsub.data();
  if (newton_pair) comm->reverse_comm(pair);
  for (int i = 0; i < nlocal; i++)
    for (int k = 0; k < DIM; k++) {
      f[i][k] += fsub[3 * i + k];
      fother[3 * i + k] += fsub[3 * i + k];
    }
}

/* out = the viscous force -sum_j g_ij (u_i - u_j) of the stored pairs on each owned atom (u
   of the ghosts current), its ghosts' parts sent home; tally: each pair's force times scale
   into the virial (in one thread: the tallies are not thread safe). */

template <int DIM>
void SaltdemViscousSplit::laplacian(const double *u, double *out, bool tally, double scale)
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int newton_pair = force->newton_pair;
  const double *const *x = atom->x;
  SaltDEM::SphFields &fields = *pair->fields;
  const std::size_t nrow = 3 * (std::size_t)(newton_pair ? nall : nlocal);
  auto sum_list = [&](const std::vector<SaltDEM::SubPair> &list, double *acc, bool tl) {
    // the pairs come grouped by i (SphFields::kernel_moments): i's sum is kept in registers
    const SaltDEM::SubPair *begin = list.data(), *end = begin + list.size();
    for (const SaltDEM::SubPair *sp = begin; sp < end;) {
      const int i = sp->i;
      const double ui[3] = {u[3 * i], u[3 * i + 1], u[3 * i + 2]};
      double fi[3] = {0.0, 0.0, 0.0};
      for (; sp < end && sp->i == i; ++sp) {
        const int j = sp->j;
        double fp[3] = {0.0, 0.0, 0.0};
        for (int k = 0; k < DIM; k++) {
          fp[k] = -sp->c * (ui[k] - u[3 * j + k]);
          fi[k] += fp[k];
        }
        if (newton_pair || j < nlocal)
          for (int k = 0; k < DIM; k++) acc[3 * j + k] -= fp[k];
        if (tl)
          pair->ev_tally_xyz(i, j, nlocal, newton_pair, 0.0, 0.0, fp[0] * scale, fp[1] * scale,
                             fp[2] * scale, x[i][0] - x[j][0], x[i][1] - x[j][1],
                             (DIM == 3) ? x[i][2] - x[j][2] : 0.0);
      }
      for (int k = 0; k < DIM; k++) acc[3 * i + k] += fi[k];
    }
  };
  sum_over_pairs(fields, out_thr, nrow, out, tally,
                 [&](std::vector<SaltDEM::SubPair> &list, double *acc) {
                   sum_list(list, acc, tally);
                 });
  rev = out;
  if (newton_pair) comm->reverse_comm(pair);
}

/* n explicit steps of dt/n on the velocities, each pair's force -g_ij (u_i - u_j) at every
   sub-step; the mean force over the sub-steps is added to f, so that the integrator's step
   gives each particle the velocity change of the sub-steps */

template <int DIM> void SaltdemViscousSplit::run_substeps(int n)
{
  const int nlocal = atom->nlocal;
  double **f = atom->f;
  const double inv_n = 1.0 / n;
  prepare<DIM>(update->dt * force->ftm2v / n);
  double *usub = this->usub.data(), *fsub = this->fsub.data();
  const double *ksub = this->ksub.data(), *fother = this->fother.data();
  for (int step = 0; step < n; step++) {
    laplacian<DIM>(usub, fsub, pair->evflag, inv_n);
    for (int i = 0; i < nlocal; i++)
      for (int k = 0; k < DIM; k++) {
        f[i][k] += fsub[3 * i + k] * inv_n;
        usub[3 * i + k] += ksub[i] * (fsub[3 * i + k] + fother[3 * i + k]);
      }
    fwd = usub;
    if (step + 1 < n) comm->forward_comm(pair);
  }
}

int SaltdemViscousSplit::pack_forward_comm(int n, const int *list, double *buf) const
{
  int k = 0;
  for (int i = 0; i < n; i++)
    for (int c = 0; c < 3; c++) buf[k++] = fwd[3 * list[i] + c];
  return k;
}

void SaltdemViscousSplit::unpack_forward_comm(int n, int first, const double *buf)
{
  int k = 0;
  for (int i = first; i < first + n; i++)
    for (int c = 0; c < 3; c++) fwd[3 * i + c] = buf[k++];
}

int SaltdemViscousSplit::pack_reverse_comm(int n, int first, double *buf) const
{
  int k = 0;
  for (int i = first; i < first + n; i++)
    for (int c = 0; c < 3; c++) buf[k++] = rev[3 * i + c];
  return k;
}

void SaltdemViscousSplit::unpack_reverse_comm(int n, const int *list, const double *buf)
{
  int k = 0;
  for (int i = 0; i < n; i++)
    for (int c = 0; c < 3; c++) rev[3 * list[i] + c] += buf[k++];
}

// the implicit step's instances (saltdem_viscous_implicit.cpp)
template void SaltdemViscousSplit::weigh_pairs<2>(double *);
template void SaltdemViscousSplit::weigh_pairs<3>(double *);
template void SaltdemViscousSplit::laplacian<2>(const double *, double *, bool, double);
template void SaltdemViscousSplit::laplacian<3>(const double *, double *, bool, double);
