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
  struct ViscousLaw;
  struct ViscousSettings;
  struct SphInput;
  class SphFields;
}    // namespace SaltDEM

class PairSaltdemViscous : public PairSaltdem {
  // the sub-steps and the implicit step read the fields, integrators and tallies of the style
  // and use its communication
  friend class SaltdemViscousSplit;

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
  bool set_implicit(bool on, double tol = -1.0, int niter = -1) override;
  void pre_loop() override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;

  double *loop_sum() override;

  // what the density fix (FixSaltdemDensity) reads: some type pair is FLUID; per type, its
  // own pair is FLUID; the kernel h and bulk modulus K of a type's own pair; the kernel
  // density of the owned atoms (SaltDEM::SphFields::kernel_density)
  bool any_fluid_pair() const { return any_fluid; }
  const int *fluid_types() const { return fluidself; }
  double fluid_h(int t) const;
  double fluid_K(int t) const;
  void kernel_density(double *out, double *interior);
  // the viscous sub-steps (substeps > 1) or implicit step (the density fix calls it once all
  // forces are in)
  void apply_substeps();
  // implicit: what it says at the end of a run (its iterations per step), and their count reset
  void implicit_report();
  // the inertia factor S of the viscous discs (what extract("inertia") gives as of the last
  // init).  Collective: every rank must call it
  double find_salt_inertia();

  // CONTACT mode: dashpot coefficient per unit viscosity, gamma = calibration * eta
  static constexpr double DEFAULT_CALIBRATION = 1.0;
  // FLUID mode: the Morris sum over a disordered polydisperse pack with volumes m/rho
  // returns eta_eff = 0.955 eta (channel flows, h = 1.45 spacings); this restores eta
  static constexpr double DEFAULT_CORRECTION = 1.047;
  // FLUID: the most viscous sub-steps per step (SaltdemViscousSplit)
  static constexpr int MAX_SUBSTEPS = 64;
  // FLUID, implicit: the residual the solve stops at, over the explicit step's, and the most
  // iterations
  static constexpr double DEFAULT_TOLERANCE = 1e-4;
  static constexpr int DEFAULT_MAXITER = 200;

 protected:
  SaltDEM::ViscousParams **params;
  double **eta;    // requested viscosity per type pair (extract "eta": fix adapt, fixes)
  SaltDEM::SphFields *fields;            // FLUID: the SPH field passes and their fields
  class SaltdemViscousSplit *substep;    // FLUID, substeps > 1 or implicit
  std::vector<int> influid;              // per type: in some FLUID pair (needs a radius)
  std::vector<double> scratch;    // no FLUID pair: what the force pass sums the (zero) q into
  class FixSaltdemDensity *fix_density;    // FLUID: the density (state) and d rho / dt
  std::string density_id;                  // its ID
  class FixSaltdemPlastic *fix_plastic;    // FLUID with yield: the plastic stress (state)
  std::string plastic_id;                  // its ID
  std::vector<int> isplastic;              // per type: FLUID with K > 0 and a plastic strength
  int *fluidself;    // per type: its own pair is FLUID (continuity density, reference density)
  int *isfluid;      // per type: FLUID with K > 0 (carries pressure)
  int nmax;          // the atoms the per-atom arrays have room for
  bool any_fluid;    // some type pair uses the FLUID law
  double calibration;
  double correction;    // FLUID: Morris viscosity multiplied by this (measured, see above)
  double viscfactor;    // safety factor on the viscous stable dt
  double fill_max;      // FLUID: the largest boundary fill (1: boundaries count as themselves)
  static constexpr double DEFAULT_FILL_MAX = 1.0;    // (off: see the pair's doc page)
  int substeps;               // FLUID: viscous sub-steps per time step (1: in the force pass)
  bool implicit;              // FLUID: the viscosity in an implicit step (SaltdemViscousSplit)
  double tolerance;           // implicit: residual over the explicit step's
  int maxiter;                // implicit: the most iterations per step
  bool noslip_surface;        // FLUID: boundary partners extrapolate the fluid's velocity (noslip)
  Integrators integrators;    // the time integrators at init (find_integrators)
  // what the forward and reverse communication carries: the fields of the force pass
  // (volume, fill, pressure matrix, no-slip offset; the ghosts' kernel sums) or the sub-steps'
  enum { COMM_PRESSURE, COMM_SUBSTEP };
  int comm_mode;

  SaltDEM::ViscousSettings settings_now() const;    // the settings, as one value
  void set_settings(const SaltDEM::ViscousSettings &);
  SaltDEM::ViscousLaw law() const;    // the law policy of the shared pair loop
  // the internal fix of style STYLE that keeps some of this style's state (its ID: STYLE, or
  // STYLE_N for the N-th saltdem/viscous sub-style of pair hybrid; the same for the same deck
  // after read_restart, so that it finds its data in a restart file)
  template <class F> F *internal_fix(const char *style, std::string &id, const char *what);
  void grow_arrays();         // the per-atom arrays for the owned and ghost atoms
  void material_density();    // (SphFields::material_density) or the error of a disc without size
  SaltDEM::SphInput sph_input() const;    // the atoms and list of the field passes
  void reverse_kernel_sums();             // (newton on) the ghosts' kernel sums home
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
  // 5: the plastic strength (yield, modulus); 6: implicit, tolerance, maxiter
  int restart_version() const override { return 6; }
  std::vector<int> restart_versions_read() const override { return {1, 3, 4, 5, 6}; }
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
