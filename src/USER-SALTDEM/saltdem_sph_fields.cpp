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

   The SPH field passes of pair saltdem/viscous (SphFields, see the header).
------------------------------------------------------------------------- */

#include "saltdem_sph_fields.h"

#include "saltdem_contact_viscous.h"
#include "saltdem_plastic.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;
using namespace SaltDEM;

static_assert(SphLayout<2>::NS == nsym<2>() && SphLayout<3>::NS == nsym<3>(),
              "SphLayout::NS must be SaltDEM::nsym");

void SphFields::grow(int n)
{
  if ((int) vol.size() < n) {
    vol.resize(n);
    fill.resize(n);
    mdens.resize(n);
    pmat.resize((size_t) NSYM * n);
    moment.resize((size_t) SPH_NMOM_MAX * n);
  }
  if (noslip && (int) slip.size() < 3 * (int) vol.size()) slip.resize(3 * vol.size(), 0.0);
  if (plastic && vgrad.size() < (size_t) PLASTIC_NVG_MAX * vol.size())
    vgrad.resize((size_t) PLASTIC_NVG_MAX * vol.size(), 0.0);
}

double SphFields::memory_usage() const
{
  return (double) (vol.capacity() + fill.capacity() + mdens.capacity() + pmat.capacity() +
                   moment.capacity() + slip.capacity() + vgrad.capacity()) *
      sizeof(double) +
      (double) (moment_thr.capacity() + vgrad_thr.capacity()) * sizeof(double) + [this] {
        double n = 0.0;
        for (const auto &p : pairs) n += (double) p.capacity() * sizeof(SubPair);
        return n;
      }();
}

void SphFields::add_slices(const double *part, int nt, std::size_t n, double *out) const
{
  for_threads([&](int tid) {
    int from, to;
    slice((int) n, tid, threads(), from, to);
    for (int k = from; k < to; k++) {
      double sum = 0.0;
      for (int t = 0; t < nt; t++) sum += part[(std::size_t) t * n + k];
      out[k] = sum;
    }
  });
}

/* the material density m / r^dim of the owned and ghost atoms, which weighs a partner as
   the particle's own material (pair_weights); a disc in a FLUID pair needs a radius */

int SphFields::material_density(const SphInput &in, int dim, const int *influid)
{
  for (int i = 0; i < in.nall; i++) {
    const double r = in.radius[i];
    const double a = (dim == 2) ? r * r : r * r * r;
    if (!(a > 0.0) && influid[in.type[i]]) return i;
    mdens[i] = (a > 0.0) ? in.rmass[i] / a : 0.0;
  }
  return -1;
}

void SphFields::kernel_density(int dim, const SphInput &in,
                               const std::function<void()> &reverse_comm, double *out,
                               double *interior)
{
  if (dim == 2)
    kernel_density<2>(in, reverse_comm, out, interior);
  else
    kernel_density<3>(in, reverse_comm, out, interior);
}

/* The sums use the moment array: the density in the slot WF, the first moment in the slots
   of the fluid moment, its norm in WB (SphLayout) */

template <int DIM>
void SphFields::kernel_density(const SphInput &in, const std::function<void()> &reverse_comm,
                               double *out, double *interior)
{
  using L = SphLayout<DIM>;
  const auto x = in.x;
  const double *m = in.rmass;
  const double *radius = in.radius;
  const int *type = in.type;
  const int nlocal = in.nlocal;
  double *moment = this->moment.data();
  std::fill_n(moment, L::NMOM * in.nall, 0.0);
  for (int i = 0; i < nlocal; i++) {
    const int t = type[i];
    if (fluidself[t]) moment[L::NMOM * i + L::WF] = m[i] * wendland_c2(DIM, params[t][t].h, 0.0);
  }
  for (int ii = 0; ii < in.inum; ii++) {
    const int i = in.ilist[ii];
    const int *jlist = in.firstneigh[i];
    const ViscousParams *prow = params[type[i]];
    for (int jj = 0; jj < in.numneigh[i]; jj++) {
      const int j = jlist[jj] & in.neighmask;
      const ViscousParams &p = prow[type[j]];
      if (p.mode != VISCOUS_FLUID) continue;
      double d[3] = {0.0, 0.0, 0.0}, rsq = 0.0;
      for (int k = 0; k < DIM; k++) {
        d[k] = x[i][k] - x[j][k];
        rsq += d[k] * d[k];
      }
      const double r = sqrt(rsq);
      const double w = wendland_c2(DIM, p.h, r);
      const double s = (r < 2.0 * p.h) ? 1.0 - 0.5 * r / p.h : 0.0;
      const double g = s * s * s;    // |W'|/r up to a constant
      const double mij = partner_mass<DIM>(radius, i, j), mji = partner_mass<DIM>(radius, j, i);
      double *Mi = &moment[L::NMOM * i];
      Mi[L::WF] += mij * w;
      Mi[L::WB] += mij * g * r;
      for (int k = 0; k < DIM; k++) Mi[k] += mij * g * d[k];
      if (in.newton || j < nlocal) {
        double *Mj = &moment[L::NMOM * j];
        Mj[L::WF] += mji * w;
        Mj[L::WB] += mji * g * r;
        for (int k = 0; k < DIM; k++) Mj[k] -= mji * g * d[k];
      }
    }
  }
  if (in.newton) reverse_comm();
  for (int i = 0; i < nlocal; i++) {
    const double *Mi = &moment[L::NMOM * i];
    const int t = type[i];
    out[i] = fluidself[t] ? Mi[L::WF] : 0.0;
    double g2 = 0.0;
    for (int k = 0; k < DIM; k++) g2 += Mi[k] * Mi[k];
    interior[i] = (fluidself[t] && Mi[L::WB] > 0.0 && sqrt(g2) < INTERIOR_MAX * Mi[L::WB]) ? 1.0
                                                                                           : 0.0;
  }
}

void SphFields::pressure_matrices(int dim, const SphInput &in, const double *rho,
                                  const double *rho0, const std::function<void()> &reverse_comm)
{
  if (dim == 2)
    pressure_matrices<2>(in, rho, rho0, reverse_comm);
  else
    pressure_matrices<3>(in, rho, rho0, reverse_comm);
}

/* FLUID volume and pressure.  The density of a fluid particle is the state of the internal
   fix FixSaltdemDensity (it migrates and restarts with the atom) and follows the continuity
   equation
     d rho_i / dt = sum_j m_j (v_i - v_j) . grad_i W_ij
   over the FLUID pairs (walls and cover included: moving boundaries compress the fluid),
   summed in the force pass into the fix's d rho / dt and integrated by the fix after it, as
   LAMMPS's SPH styles do: the pressure of a step is that of the density at the end of the
   step before.  It starts at the reference rho0 of its type, the mean kernel density
   sum_j m_j W_ij of the particles of that type whose kernel is full (away from free surfaces
   and boundaries) at the setup of the first run (the fix measures it), so the fluid starts
   free of pressure.  A summed kernel density would instead drift upwards as particles pair up
   (the mean of sum_j W grows while the volume does not).  Here, before the force pass: the
   kernel sums of the present positions (kernel_moments), each fluid particle's boundary fill
   (SaltDEM::boundary_fill), its volume m / rho and its pressure matrix A = m P / rho^2 L with
   the equation of state and the kernel-gradient correction L, whose moment counts the
   boundary partners with the fill (SaltDEM::particle_volume, pressure_term, pressure_matrix);
   the caller sends them to the ghosts. */

template <int DIM>
void SphFields::pressure_matrices(const SphInput &in, const double *rho, const double *rho0,
                                  const std::function<void()> &reverse_comm)
{
  using L = SphLayout<DIM>;
  const int nlocal = in.nlocal;
  const double *m = in.rmass;
  const int *type = in.type;
  const int nt = ntypes;

  if (plastic)
    kernel_moments<DIM, true>(in, reverse_comm);
  else
    kernel_moments<DIM, false>(in, reverse_comm);
  if (noslip) noslip_offsets<DIM>(in);

  // a boundary particle (wall, cover) has, beside a fluid particle, the volume of the fluid it
  // stands for (pair_weights: its mass as that fluid's over the fluid's reference density);
  // between boundary particles, its own at the densest fluid's reference density.  A fluid
  // particle created during the run starts at its reference density
  double rhob = 0.0;
  irho0.assign(nt + 1, 0.0);
  for (int t = 1; t <= nt; t++)
    if (fluidself[t] && rho0[t] > 0.0) {
      rhob = std::max(rhob, rho0[t]);
      irho0[t] = 1.0 / rho0[t];
    }
  for (int i = 0; i < nlocal; i++) {
    const int t = type[i];
    const double r = fluidself[t] ? (rho[i] > 0.0 ? rho[i] : rho0[t]) : rhob;
    vol[i] = particle_volume(m[i], r);
    const double *M = &moment[L::NMOM * i];
    fill[i] = fluidself[t] ? boundary_fill(M[L::WF], M[L::WB], r, rho0[t], fill_max) : 1.0;
    double *A = &pmat[L::NS * i];
    if (isfluid[t]) {
      const double a = pressure_term(m[i], params[t][t].K, r, rho0[t]);
      for (int k = 0; k < L::NS; k++) A[k] = M[k] + fill[i] * M[L::NS + k];
      // the plastic stress, sigma = -P I + tau: its pair force (mu_ij T_i + mu_ji T_j) grad W
      // with T = -m tau / rho^2, corrected as the pressure is (symmetrized)
      double T[L::NS] = {};
      if (plastic && isplastic[t]) {
        plastic_rates<DIM>(in, i, rho0);
        corrected_stress<DIM>(&tau[NSYM * i], A, r, CORRECTION_DET_MIN, T);
      }
      pressure_matrix<DIM>(a, r, A);
      if (plastic && isplastic[t])
        for (int k = 0; k < L::NS; k++) A[k] -= m[i] / (r * r) * T[k];
    } else
      for (int k = 0; k < L::NS; k++) A[k] = 0.0;
    if (plastic && !(isfluid[t] && isplastic[t])) {
      for (int k = 0; k < NSYM; k++) dtau[NSYM * i + k] = 0.0;
      ystress[i] = 0.0;
    }
  }
}

/* plastic: the velocity gradient of owned fluid particle i from its sums (fluid and boundary
   partners, the latter with the fill, over the moment of its pressure matrix: pmat holds that
   moment when this is called), the rate of its plastic stress and its strength from the
   pressure of its density */

template <int DIM> void SphFields::plastic_rates(const SphInput &in, int i, const double *rho0)
{
  using L = SphLayout<DIM>;
  using PL = PlasticLayout<DIM>;
  const int t = in.type[i];
  const ViscousParams &p = params[t][t];
  const double *VG = &vgrad[PLASTIC_NVG_MAX * i];
  double G[PL::NG], gv[PL::NG];
  for (int k = 0; k < PL::NG; k++) G[k] = VG[k] + fill[i] * VG[PL::NG + k];
  const double rho = vol[i] > 0.0 ? in.rmass[i] / vol[i] : rho0[t];
  velocity_gradient<DIM>(G, &pmat[L::NS * i], rho, CORRECTION_DET_MIN, gv);
  plastic_stress_rate<DIM>(p.G, gv, &tau[NSYM * i], &dtau[NSYM * i]);
  ystress[i] = plastic_yield(p.mu_y, p.coh_y, eos_pressure(p.K, rho, rho0[t]));
}

/* the kernel sums of the owned particles of the types whose own pair is FLUID, over the FLUID
   pairs of the list, split into their fluid and their boundary partners (a partner whose own
   pair is not FLUID): the moments S = sum_j m_j w_ij d_ij d_ij and the kernel sums
   sum_j m_j W_ij (i itself among the fluid's); with noslip surface, in the same slots of a
   boundary particle b (whose own sums are not needed), its fluid partners' kernel sums
   sum_f m_f W_bf in WF, sum_f m_f W_bf (x_f - x_b) in slots 0.. and sum_f m_f W_bf v_f in
   slots NS.. (SphLayout; noslip_offsets); with newton on the ghosts' parts go home; with
   keep_pairs also the list of the FLUID pairs within 2h and their kernel factors */

template <int DIM, bool PLASTIC>
void SphFields::kernel_moments(const SphInput &in, const std::function<void()> &reverse_comm)
{
  using L = SphLayout<DIM>;
  const std::size_t nrow = in.newton ? in.nall : in.nlocal;
  const int nt = threads();
  pairs.resize(nt);
  if (nt == 1) {
    kernel_moments_range<DIM, PLASTIC>(in, 0, in.inum, moment.data(),
                                       PLASTIC ? vgrad.data() : nullptr, pairs[0]);
  } else {
    // each thread sums into a slice of its own, the slices are added after
    const std::size_t nm = L::NMOM * nrow, ng = PLASTIC ? PLASTIC_NVG_MAX * nrow : 0;
    if (moment_thr.size() < nt * nm) moment_thr.resize(nt * nm);
    if (vgrad_thr.size() < nt * ng) vgrad_thr.resize(nt * ng);
    for_threads([&](int tid) {
      int ii0, ii1;
      slice(in.inum, tid, nt, ii0, ii1);
      kernel_moments_range<DIM, PLASTIC>(in, ii0, ii1, &moment_thr[tid * nm],
                                         PLASTIC ? &vgrad_thr[tid * ng] : nullptr, pairs[tid]);
    });
    add_slices(moment_thr.data(), nt, nm, moment.data());
    if (PLASTIC) add_slices(vgrad_thr.data(), nt, ng, vgrad.data());
  }
  if (in.newton) reverse_comm();
}

/* the sums of the atoms ilist[ii0..ii1) and their partners into moment and vg (zeroed here:
   every owned atom, and the ghosts with newton on), the pairs within 2h into plist */

template <int DIM, bool PLASTIC>
void SphFields::kernel_moments_range(const SphInput &in, int ii0, int ii1, double *moment,
                                     double *vg, std::vector<SubPair> &plist)
{
  using L = SphLayout<DIM>;
  constexpr int NS = L::NS;
  constexpr int NG = PlasticLayout<DIM>::NG;
  const auto x = in.x;
  const auto v = in.v;
  const double *m = in.rmass;
  const double *radius = in.radius;
  const int *type = in.type;
  const int nlocal = in.nlocal;
  const bool newton_pair = in.newton;
  std::fill_n(moment, L::NMOM * (newton_pair ? in.nall : nlocal), 0.0);
  if (PLASTIC) std::fill_n(vg, PLASTIC_NVG_MAX * (newton_pair ? in.nall : nlocal), 0.0);
  const bool sub = keep_pairs;
  const bool ext = noslip;
  // a boundary particle b's sums of a fluid partner f at d = x_f - x_b (sign: +1) or x_b - x_f
  auto add_fluid = [&](double *Mb, int f, double mw, const double *d, double sign) {
    Mb[L::WF] += mw;
    for (int k = 0; k < DIM; k++) {
      Mb[k] += sign * mw * d[k];
      Mb[NS + k] += mw * v[f][k];
    }
  };
  plist.clear();
  for (int ii = ii0; ii < ii1; ii++) {
    const int i = in.ilist[ii];
    const int itype = type[i];
    const bool fi = fluidself[itype];
    const double xi0 = x[i][0], xi1 = x[i][1], xi2 = (DIM == 3) ? x[i][2] : 0.0;
    const int *jlist = in.firstneigh[i];
    const ViscousParams *prow = params[itype];
    double Mi[L::NMOM] = {};    // i's sums, stored once
    double Gi[PLASTIC ? 2 * NG : 1] = {};
    if (fi) Mi[L::WF] = m[i] * wendland_c2(DIM, prow[itype].h, 0.0);
    for (int jj = 0; jj < in.numneigh[i]; jj++) {
      const int j = jlist[jj] & in.neighmask;
      const int jtype = type[j];
      const ViscousParams &p = prow[jtype];
      const bool fj = fluidself[jtype];
      if (p.mode != VISCOUS_FLUID || !(fi || fj || sub)) continue;
      const double d[3] = {xi0 - x[j][0], xi1 - x[j][1], (DIM == 3) ? xi2 - x[j][2] : 0.0};
      const double rsq = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      if (rsq * p.ih2 * p.ih2 >= 1.0 || rsq == 0.0) continue;    // beyond 2h (the list has a skin)
      const double r = sqrt(rsq);
      const double s = 1.0 - r * p.ih2;
      if (sub) plist.push_back({i, j, p.kvisc * s * s * s});
      const double w = p.cw * s * s * s;
      const double W = wendland_c2_s(p.cW, s);
      // i's partner j goes into i's fluid or boundary sums, and i into j's
      double dv[3] = {0.0, 0.0, 0.0};
      if (PLASTIC)
        for (int k = 0; k < DIM; k++) dv[k] = v[i][k] - v[j][k];
      if (fi) {
        const double mij = partner_mass<DIM>(radius, i, j);
        add_moment<DIM>(mij * w, d, fj ? Mi : Mi + NS);
        Mi[fj ? L::WF : L::WB] += mij * W;
        if (PLASTIC) add_velocity_gradient<DIM>(mij * w, dv, d, fj ? Gi : Gi + NG);
      }
      if (fj && (newton_pair || j < nlocal)) {
        const double mji = partner_mass<DIM>(radius, j, i);
        double *Mj = &moment[L::NMOM * j];
        add_moment<DIM>(mji * w, d, fi ? Mj : Mj + NS);
        Mj[fi ? L::WF : L::WB] += mji * W;
        if (PLASTIC)
          add_velocity_gradient<DIM>(mji * w, dv, d, &vg[PLASTIC_NVG_MAX * j + (fi ? 0 : NG)]);
      }
      if (ext && fi != fj) {
        if (fj)
          add_fluid(Mi, j, m[j] * W, d, -1.0);
        else if (newton_pair || j < nlocal)
          add_fluid(&moment[L::NMOM * j], i, m[i] * W, d, 1.0);
      }
    }
    if (fi || ext)
      for (int k = 0; k < L::NMOM; k++) moment[L::NMOM * i + k] += Mi[k];
    if (PLASTIC && fi)
      for (int k = 0; k < 2 * NG; k++) vg[PLASTIC_NVG_MAX * i + k] += Gi[k];
  }
}

/* noslip surface: the offset v_eff - v of each owned boundary particle from its fluid
   partners' sums (kernel_moments; SaltDEM::noslip_offset), 0 for the fluid's own particles
   and for boundary particles without a fluid partner */

template <int DIM> void SphFields::noslip_offsets(const SphInput &in)
{
  using L = SphLayout<DIM>;
  for (int i = 0; i < in.nlocal; i++) {
    double *o = &slip[3 * i];
    const double *M = &moment[L::NMOM * i];
    if (fluidself[in.type[i]])
      o[0] = o[1] = o[2] = 0.0;
    else
      noslip_offset<DIM>(M[L::WF], M, M + L::NS, in.v[i], in.radius[i], o);
  }
}

/* the fields of the force pass to the ghosts (volume, fill, pressure matrix, no-slip offset),
   the ghosts' kernel sums home */

int SphFields::pack_forward_comm(int dim, int n, const int *list, double *buf) const
{
  const int ns = (dim == 2) ? nsym<2>() : nsym<3>();
  const int nd = noslip ? dim : 0;
  int k = 0;
  for (int i = 0; i < n; i++) {
    const int j = list[i];
    buf[k++] = vol[j];
    buf[k++] = fill[j];
    for (int c = 0; c < ns; c++) buf[k++] = pmat[ns * j + c];
    for (int c = 0; c < nd; c++) buf[k++] = slip[3 * j + c];
  }
  return k;
}

void SphFields::unpack_forward_comm(int dim, int n, int first, const double *buf)
{
  const int ns = (dim == 2) ? nsym<2>() : nsym<3>();
  const int nd = noslip ? dim : 0;
  int k = 0;
  for (int i = first; i < first + n; i++) {
    vol[i] = buf[k++];
    fill[i] = buf[k++];
    for (int c = 0; c < ns; c++) pmat[ns * i + c] = buf[k++];
    for (int c = 0; c < nd; c++) slip[3 * i + c] = buf[k++];
  }
}

int SphFields::pack_reverse_comm(int dim, int n, int first, double *buf) const
{
  const int nm = (dim == 2) ? SphLayout<2>::NMOM : SphLayout<3>::NMOM;
  const int ng = plastic ? ((dim == 2) ? PlasticLayout<2>::NVG : PlasticLayout<3>::NVG) : 0;
  int k = 0;
  for (int i = first; i < first + n; i++) {
    for (int c = 0; c < nm; c++) buf[k++] = moment[nm * i + c];
    for (int c = 0; c < ng; c++) buf[k++] = vgrad[PLASTIC_NVG_MAX * i + c];
  }
  return k;
}

void SphFields::unpack_reverse_comm(int dim, int n, const int *list, const double *buf)
{
  const int nm = (dim == 2) ? SphLayout<2>::NMOM : SphLayout<3>::NMOM;
  const int ng = plastic ? ((dim == 2) ? PlasticLayout<2>::NVG : PlasticLayout<3>::NVG) : 0;
  int k = 0;
  for (int i = 0; i < n; i++) {
    for (int c = 0; c < nm; c++) moment[nm * list[i] + c] += buf[k++];
    for (int c = 0; c < ng; c++) vgrad[PLASTIC_NVG_MAX * list[i] + c] += buf[k++];
  }
}
