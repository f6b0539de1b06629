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

   SphFields: the SPH field passes of pair saltdem/viscous (FLUID pairs) over a half
   neighbour list, before its force pass: the kernel density (for the reference density),
   the kernel moments, the boundary fill, the volumes and pressure matrices, the no-slip
   offsets of boundary particles and the list of pairs within 2h (viscous sub-steps).  It
   owns these per-atom fields (owned and ghost atoms) and reads what it is handed: no LAMMPS
   classes, so that it can be tested alone.  The caller communicates: reverse_comm sends the
   ghosts' kernel sums home (newton on), the fields of owned atoms go to the ghosts after.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_SPH_FIELDS_H
#define LMP_SALTDEM_SPH_FIELDS_H

#include <cstddef>
#include <cstdlib>
#include <functional>
#include <new>
#include <vector>

namespace LAMMPS_NS {
namespace SaltDEM {
  struct ViscousParams;

  // the per-atom layout of the pressure matrices and kernel sums in DIM dimensions, packed so
  // that the sums of a 2D disc fill one cache line (8 values): a symmetric matrix has NS
  // values (SaltDEM::nsym, checked in the .cpp); a moment row holds the fluid moment at 0, the boundary moment at
  // NS, the kernel sums over the fluid at WF and over the boundary at WB
  template <int DIM> struct SphLayout {
    static constexpr int NS = (DIM == 2) ? 3 : 6;
    static constexpr int WF = 2 * NS, WB = 2 * NS + 1, NMOM = 2 * NS + 2;
  };
  constexpr int SPH_NMOM_MAX = SphLayout<3>::NMOM;

  // what a pass reads: per-atom arrays of the owned atoms (0..nlocal) then the ghosts (..nall),
  // and a half neighbour list of the owned atoms (j & neighmask: the partner)
  struct SphInput {
    const double (*x)[3], (*v)[3];
    const double *rmass, *radius;
    const int *type;
    int nlocal, nall;
    bool newton;    // a pair with a ghost is summed into the ghost too (then sent home)
    int inum;
    const int *ilist, *numneigh;
    int *const *firstneigh;
    int neighmask;
  };

  // FLUID: what a pair weighs in its two particles' sums: mj = mu_ij, the mass of j counted
  // in i's sums, and mi = mu_ji, and the volumes vi, vj of the pair's viscosity
  struct Weights {
    double mi, mj, vi, vj;
  };

  // a FLUID pair within 2h and its kernel factor kvisc (1 - r/2h)^3 (viscous sub-steps)
  struct SubPair {
    int i, j;
    double c;
  };

  // a per-atom array grown in place as LAMMPS's Memory::grow grows one (realloc, contents
  // kept, new entries not initialized unless a value is given): with a std::vector here the
  // process's resident size grew each time the pair style was created anew
  class AtomArray {
   public:
    AtomArray() = default;
    AtomArray(const AtomArray &) = delete;
    AtomArray &operator=(const AtomArray &) = delete;
    ~AtomArray() { std::free(p); }
    void resize(std::size_t m)
    {
      if (m == n) return;
      void *q = std::realloc(p, (m ? m : 1) * sizeof(double));
      if (!q) throw std::bad_alloc();
      p = static_cast<double *>(q);
      n = m;
    }
    void resize(std::size_t m, double value)
    {
      const std::size_t old = n;
      resize(m);
      for (std::size_t k = old; k < m; k++) p[k] = value;
    }
    std::size_t size() const { return n; }
    std::size_t capacity() const { return n; }
    double *data() { return p; }
    const double *data() const { return p; }
    double &operator[](std::size_t k) { return p[k]; }
    const double &operator[](std::size_t k) const { return p[k]; }

   private:
    double *p = nullptr;
    std::size_t n = 0;
  };

  class SphFields {
   public:
    // per type pair and type (1..ntypes), set by the pair style at init: the coefficients,
    // whether a type's own pair is FLUID, and FLUID with K > 0 (carries pressure)
    const ViscousParams *const *params = nullptr;
    const int *fluidself = nullptr, *isfluid = nullptr;
    int ntypes = 0;
    double fill_max = 1.0;      // the largest boundary fill (1: off)
    bool noslip = false;        // noslip surface: the boundary particles' offsets (slip)
    bool keep_pairs = false;    // list the FLUID pairs within 2h (pairs)
    // frictional-viscous fluid (SaltDEM::PlasticLayout, saltdem_plastic.h): per type, its own
    // pair has a plastic strength; set: the velocity gradients are summed and the plastic
    // stress tau of the owned atoms (stride NSYM, FixSaltdemPlastic's) joins their pressure
    // matrices, and the pass writes its rate dtau and the strength ystress of each owned atom
    const int *isplastic = nullptr;
    bool plastic = false;
    const double *tau = nullptr;
    double *dtau = nullptr, *ystress = nullptr;

    // per atom, owned and ghost: volume m / rho, boundary fill, material density m / r^dim,
    // pressure matrix (NS values), kernel sums (NMOM values), no-slip offset (3 values)
    AtomArray vol, fill, mdens, pmat, moment, slip;
    AtomArray vgrad;              // plastic: the velocity-gradient sums (PlasticLayout::NVG values)
    std::vector<double> irho0;    // 1 / reference density per type (0: none)
    // keep_pairs: the FLUID pairs within 2h, one list per thread of the pass that found them
    // (in the order of the neighbour list, each grouped by i)
    std::vector<std::vector<SubPair>> pairs;

    // threads: run_threads(body) calls body(tid) on each of nthreads threads at once (set by
    // the OpenMP variant of the pair style; unset, or nthreads 1: one call with tid 0).  The
    // kernel sums then go into a slice per thread and are added after the pass
    int nthreads = 1;
    std::function<void(const std::function<void(int)> &)> run_threads;
    int threads() const { return (nthreads > 1 && run_threads) ? nthreads : 1; }
    void for_threads(const std::function<void(int)> &body) const
    {
      if (threads() > 1)
        run_threads(body);
      else
        body(0);
    }
    // the slices [from, to) of n items of thread tid of nt
    static void slice(int n, int tid, int nt, int &from, int &to)
    {
      from = (int) ((long long) n * tid / nt);
      to = (int) ((long long) n * (tid + 1) / nt);
    }
    // out[k] = sum over the nt slices (each of n values, stride n) of part, split between the
    // threads
    void add_slices(const double *part, int nt, std::size_t n, double *out) const;

    // room for n atoms (slip only with noslip)
    void grow(int n);
    double memory_usage() const;
    // mdens of the owned and ghost atoms; returns an atom of a type in a FLUID pair
    // (influid) without a positive radius, or -1
    int material_density(const SphInput &in, int dim, const int *influid);
    // the kernel density out[i] = sum_j mu_ij W_ij (j = i included) of each owned atom of a
    // type whose own pair is FLUID, over the FLUID pairs, and whether its kernel is full
    // (interior[i] 1: its neighbours surround it, SaltDEM::INTERIOR_MAX; else 0)
    void kernel_density(int dim, const SphInput &in, const std::function<void()> &reverse_comm,
                        double *out, double *interior);
    // before the force pass: the kernel sums (and no-slip offsets), then the volume, fill and
    // pressure matrix of each owned atom from its density rho and the reference density
    // rho0 of its type
    void pressure_matrices(int dim, const SphInput &in, const double *rho, const double *rho0,
                           const std::function<void()> &reverse_comm);
    // the communication of these fields: volume, fill, pressure matrix and no-slip offset of
    // the owned atoms to their ghosts; the ghosts' kernel sums home (added)
    int pack_forward_comm(int dim, int n, const int *list, double *buf) const;
    void unpack_forward_comm(int dim, int n, int first, const double *buf);
    int pack_reverse_comm(int dim, int n, int first, double *buf) const;
    void unpack_reverse_comm(int dim, int n, const int *list, const double *buf);

    /* what a FLUID pair weighs.  Sums over the partners j of a particle i count each j as i's
     own material, mu_ij = m_j rho_m,i / rho_m,j = mdens_i r_j^dim (rho_m = m / r^dim per disc
     or sphere), so that particles of two densities side by side see one continuous kernel
     density and pressure (the volume-weighted sums of multiphase SPH, Colagrossi & Landrini
     2003, Hu & Adams 2006); for one density mu_ij = m_j.  A boundary partner (its own pair is
     not FLUID) of a fluid particle counts with that particle's fill (SaltDEM::boundary_fill)
     and has the volume mu_ij / rho0_i of the fluid it stands for; between two boundary
     particles the volumes are their own (vol). */
    template <int DIM> double partner_mass(const double *radius, int i, int j) const
    {
      const double r = radius[j];
      return mdens[i] * ((DIM == 2) ? r * r : r * r * r);
    }
    template <int DIM>
    Weights pair_weights(const double *radius, int i, int j, int itype, int jtype) const
    {
      Weights w = {partner_mass<DIM>(radius, j, i), partner_mass<DIM>(radius, i, j), vol[i],
                   vol[j]};
      if (fluidself[itype] && !fluidself[jtype]) {
        w.mj *= fill[i];
        w.vj = w.mj * irho0[itype];
      } else if (fluidself[jtype] && !fluidself[itype]) {
        w.mi *= fill[j];
        w.vi = w.mi * irho0[jtype];
      }
      return w;
    }
    // noslip surface: what the viscosity adds to v_i - v_j of a fluid-boundary pair (the
    // boundary's offset); false (ov untouched) for any other pair
    template <int DIM> bool noslip_pair(int i, int j, int itype, int jtype, double *ov) const
    {
      if (!noslip || fluidself[itype] == fluidself[jtype]) return false;
      const double *o = fluidself[itype] ? &slip[3 * j] : &slip[3 * i];
      const double sign = fluidself[itype] ? -1.0 : 1.0;
      for (int k = 0; k < DIM; k++) ov[k] = sign * o[k];
      return true;
    }

   private:
    template <int DIM>
    void kernel_density(const SphInput &, const std::function<void()> &, double *, double *);
    template <int DIM, bool PLASTIC>
    void kernel_moments(const SphInput &, const std::function<void()> &);
    template <int DIM, bool PLASTIC>
    void kernel_moments_range(const SphInput &, int ii0, int ii1, double *moment, double *vg,
                              std::vector<SubPair> &plist);
    std::vector<double> moment_thr, vgrad_thr;    // threads > 1: the slices of the sums
    template <int DIM> void plastic_rates(const SphInput &, int i, const double *rho0);
    template <int DIM> void noslip_offsets(const SphInput &);
    template <int DIM>
    void pressure_matrices(const SphInput &, const double *, const double *,
                           const std::function<void()> &);
  };
}    // namespace SaltDEM
}    // namespace LAMMPS_NS

#endif
