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

#ifdef PAIR_CLASS
// clang-format off
PairStyle(saltdem/viscous,PairSaltdemViscous);
// clang-format on
#else

#ifndef LMP_PAIR_SALTDEM_VISCOUS_H
#define LMP_PAIR_SALTDEM_VISCOUS_H

#include "pair_saltdem.h"

namespace LAMMPS_NS {
namespace SaltDEM {
  struct ViscousParams;
}

class PairSaltdemViscous : public PairSaltdem {
 public:
  PairSaltdemViscous(class LAMMPS *);
  ~PairSaltdemViscous() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void *extract(const char *, int &) override;
  bool set_substeps(int n) override;
  void pre_loop() override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;

  double *loop_sum() override;

  // what the density fix (FixSaltdemDensity) reads: some type pair is FLUID; per type, its
  // own pair is FLUID; the kernel h and bulk modulus K of a type's own pair; the kernel
  // density of the owned and ghost atoms
  bool any_fluid_pair() const { return any_fluid; }
  const int *fluid_types() const { return fluidself; }
  double fluid_h(int t) const;
  double fluid_K(int t) const;
  void kernel_density(double *out, double *interior);
  // the viscous sub-steps (substeps > 1; the density fix calls it once all forces are in)
  void apply_substeps();
  // the inertia factor S of the viscous discs (what extract("inertia") gives as of the last
  // init).  Collective: every rank must call it
  double find_salt_inertia();

  // the force law, inlined into the shared pair loop (PairSaltdem::loop; defined in
  // saltdem_pair_loop.h): FLUID pairs need only positions and velocities of the centres and
  // make no torque.  q: i's and j's terms mu_ij v_ij . grad_i W_ij and mu_ji v_ij . grad_i W_ij
  // of the continuity equation, summed in the same pass into the density fix's d rho / dt
  static constexpr bool HISTORY = false;    // no values kept per pair
  static constexpr bool PAIR_SUM = true;
  template <int DIM, int EVFLAG>
  int law(const Atoms &a, int i, int j, int itype, int jtype, double r, double *, bool, double *f,
          double *ti, double *tj, double &evdwl, double *q) const;

  // FLUID: what a pair weighs in its two particles' sums (kernel moments and densities,
  // pressure, continuity): mj = mu_ij, the mass of j counted in i's sums, and mi = mu_ji, and
  // the volumes vi, vj of the pair's viscosity (see pair_weights)
  struct Weights {
    double mi, mj, vi, vj;
  };
  template <int DIM>
  Weights pair_weights(const double *radius, int i, int j, int itype, int jtype) const;
  template <int DIM> double partner_mass(const double *radius, int i, int j) const;    // mu_ij
  // noslip surface: what the viscosity adds to v_i - v_j, o_i - o_j of a fluid-boundary pair
  // (the boundary's offset, slip); false (ov untouched) for any other pair
  template <int DIM> bool noslip_pair(int i, int j, int itype, int jtype, double *ov) const;

  // CONTACT mode: dashpot coefficient per unit viscosity, gamma = calibration * eta
  static constexpr double DEFAULT_CALIBRATION = 1.0;
  // FLUID mode: the Morris sum over a disordered polydisperse pack with volumes m/rho
  // returns eta_eff = 0.955 eta (channel flows, h = 1.45 spacings); this restores eta
  static constexpr double DEFAULT_CORRECTION = 1.047;

  // FLUID: the Morris viscosity is a linear operator on the velocities (a graph Laplacian
  // weighted by g_ij = kvisc V_i V_j (1 - r/2h)^3).  With substeps N > 1 the force pass leaves
  // it out and viscous_substeps() applies it after that pass: N explicit steps of dt/N on
  // the velocities at the frozen positions and coefficients, whose mean force is added to
  // each particle.  N = 1 is the plain explicit force; the viscous stable limit grows N-fold
  // for about the cost of one pass over the stored pairs per sub-step.
  static constexpr int MAX_SUBSTEPS = 64;
  struct SubPair {
    int i, j;
    double c;    // kvisc (1 - r/2h)^3 of the pair, then its weight g_ij = c V_i V_j
  };

 protected:
  SaltDEM::ViscousParams **params;
  double **eta;      // requested viscosity per type pair (extract "eta": fix adapt, fixes)
  double *vol;       // FLUID: particle volume m / rho, owned and ghost atoms
  double *pmat;      // FLUID: pressure matrix A = m P / rho^2 L per atom (Layout::NS values,
                     // see SaltDEM::pressure_matrix), owned and ghost atoms
  double *moment;    // FLUID: its kernel sums, Layout::NMOM values per atom: the moments
                     // S = sum_j mu_ij w d d over its fluid and over its boundary partners
                     // (NS each), the kernel sums sum_j mu_ij W over both (see pre_loop)
  double *fill;      // FLUID: the boundary fill of each fluid particle (SaltDEM::boundary_fill)
  double *mdens;     // FLUID: material density m / r^dim of each atom, owned and ghost
  std::vector<double> irho0;    // FLUID: 1 / reference density per type (0: none)
  std::vector<int> influid;     // per type: in some FLUID pair (its discs need a radius)
  void material_density();      // mdens of the owned and ghost atoms
  // the per-atom layout of pmat and moment in DIM dimensions, packed so that the sums of a
  // 2D disc fill one cache line (8 values): a symmetric matrix has NS values; moment holds the
  // fluid moment at 0, the boundary moment at NS, the kernel sums over the fluid at WF and
  // over the boundary at WB
  template <int DIM> struct Layout {
    static constexpr int NS = (DIM == 2) ? 3 : 6;    // SaltDEM::nsym
    static constexpr int WF = 2 * NS, WB = 2 * NS + 1, NMOM = 2 * NS + 2;
  };
  static constexpr int NMOM_MAX = Layout<3>::NMOM;
  int nmom() const;    // Layout<dimension>::NMOM
  double *scratch;     // no FLUID pair: what the force pass sums the (zero) q into
  class FixSaltdemDensity *fix_density;    // FLUID: the density (state) and d rho / dt
  std::string density_id;                  // its ID
  int *fluidself;    // per type: its own pair is FLUID (continuity density, reference density)
  int *isfluid;      // per type: FLUID with K > 0 (carries pressure)
  int nmax;          // allocated length of vol
  bool any_fluid;    // some type pair uses the FLUID law
  double calibration;
  double correction;    // FLUID: Morris viscosity multiplied by this (measured, see above)
  double viscfactor;    // safety factor on the viscous stable dt
  double fill_max;      // FLUID: the largest boundary fill (1: boundaries count as themselves)
  static constexpr double DEFAULT_FILL_MAX = 1.0;    // (off: see the pair's doc page)
  int substeps;           // FLUID: viscous sub-steps per time step (1: in the force pass)
  bool noslip_surface;    // FLUID: boundary partners extrapolate the fluid's velocity (noslip)
  // noslip surface (else not allocated): each boundary particle's offset v_eff - v (3 per
  // atom, owned and ghost; 0 for fluid particles), SaltDEM::noslip_offset
  double *slip;
  std::vector<SubPair> subpairs;    // substeps > 1: the FLUID pairs within 2h (kernel_moments)
  double *usub, *fsub;              // substeps > 1: sub-step velocities and forces (3 per atom)
  double *ksub, *fother;      // substeps > 1: dt/N over the inertial mass; the step's other forces
  Integrators integrators;    // the time integrators at init (find_integrators)
  int comm_mode;              // COMM_PRESSURE or COMM_SUBSTEP
  template <int DIM> void viscous_substeps();
  int parse_substeps(const char *);
  template <int DIM> void kernel_density(double *out, double *interior);
  // pre_loop's work: the kernel sums (and no-slip offsets), then volume, fill and pressure
  // matrix of each owned atom
  template <int DIM> void pressure_matrices();
  template <int DIM> void kernel_moments();
  template <int DIM> void noslip_offsets();
  void grow_arrays();    // vol, pmat, moment (and scratch) for the owned and ghost atoms
  std::vector<PairSaltdemViscous *> substyles() const;    // this, or its hybrid siblings
  bool fluid_in_other_substyle(int) const;
  void allocate_params(int) override;
  void *pair_params(int i, int j) override;
  size_t params_size() const override;
  void mix(int, int) override;
  void derive(int, int) override;
  double range(int i, int j) const override;
  double range_abs(int i, int j) const override;
  void pair_limit(int, int, double, double, bool, double &, std::string &) override;
  // 2: the setting fill, 3: substeps, 4: noslip; layouts 1 and 3 are read (fill 1, substeps
  // 1, noslip centre); layout 2 was never released
  int restart_version() const override { return 4; }
  std::vector<int> restart_versions_read() const override { return {1, 3, 4}; }
  std::vector<std::string> setting_names() const override;
  void pack_settings(double *) const override;
  void unpack_settings(const double *) override;
  std::vector<std::string> coeff_names() const override;
  void pack_coeffs(int, int, double *) const override;
  void unpack_coeffs(int, int, const double *) override;
  // the time step check: the viscosities and calibration it saw (a change during the run,
  // e.g. by fix adapt, is checked again), and the inertial masses per disc volume it used
  void limits_checked() override;
  std::vector<std::vector<double>> eta_checked;
  double calibration_checked;
  double salt_inertia;    // extract("inertia"): find_salt_inertia() at the last init
};

}    // namespace LAMMPS_NS

#endif
#endif
