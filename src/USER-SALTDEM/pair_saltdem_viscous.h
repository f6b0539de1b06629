/* -*- c++ -*- ----------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(saltdem/viscous,PairSaltdemViscous);
// clang-format on
#else

#ifndef LMP_PAIR_SALTDEM_VISCOUS_H
#define LMP_PAIR_SALTDEM_VISCOUS_H

#include "pair_saltdem.h"

#include <vector>

namespace LAMMPS_NS {

class PairSaltdemViscous : public PairSaltdem {
 public:
  PairSaltdemViscous(class LAMMPS *);
  ~PairSaltdemViscous() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  double init_one(int, int) override;
  void *extract(const char *, int &) override;
  void pre_loop() override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  double memory_usage() override;

  double *loop_sum(int tid, int nthreads) override;
  void post_loop(int nthreads) override;

  // what the density fix (FixSaltdemDensity) reads: some type pair is FLUID; per type, its
  // own pair is FLUID; the kernel h and bulk modulus K of a type's own pair; the kernel
  // density of the owned and ghost atoms
  bool any_fluid_pair() const { return any_fluid; }
  const int *fluid_types() const { return fluidself; }
  double fluid_h(int t) const { return params[t][t].h; }
  double fluid_K(int t) const { return params[t][t].K; }
  void kernel_density(double *out);

  // the force law, inlined into the shared pair loop (PairSaltdem::loop): FLUID pairs need
  // only positions and velocities of the centres and make no torque.  q: the pair's term
  // v_ij . grad_i W_ij of the continuity equation, summed in the same pass into the density
  // fix's d rho / dt
  static constexpr bool HISTORY = false;    // no values kept per pair
  static constexpr bool PAIR_SUM = true;
  template <int DIM, int EVFLAG>
  int law(const Atoms &a, int i, int j, int itype, int jtype, double r, double *, bool,
          double *f, double *ti, double *tj, double &evdwl, double &q) const
  {
    const SaltDEM::ViscousParams &p = params[itype][jtype];
    if (p.mode == SaltDEM::VISCOUS_FLUID) {
      const double d[3] = {a.x[i][0] - a.x[j][0], a.x[i][1] - a.x[j][1],
                           (DIM == 3) ? a.x[i][2] - a.x[j][2] : 0.0};
      const double vr[3] = {a.v[i][0] - a.v[j][0], a.v[i][1] - a.v[j][1],
                            (DIM == 3) ? a.v[i][2] - a.v[j][2] : 0.0};
      // SPH pressure m_i m_j (P_i/rho_i^2 + P_j/rho_j^2) with a_i = m_i P_i / rho_i^2;
      // a particle that is not fluid (wall, cover) mirrors the fluid's pressure
      const double pc = SaltDEM::pressure_pair(isfluid[itype], isfluid[jtype], a.rmass[i],
                                               a.rmass[j], apress[i], apress[j]);
      return SaltDEM::viscous_fluid_force<DIM, EVFLAG>(p, d, vr, r, a.radius[i] + a.radius[j],
                                                       vol[i], vol[j], pc, f, evdwl, q)
          ? LAW_TOUCH
          : 0;
    }
    SaltDEM::Contact c;
    SaltDEM::contact_kinematics<DIM>(a.x[i], a.x[j], a.v[i], a.v[j], a.omega[i], a.omega[j],
                                     a.radius[i], a.radius[j], a.rmass[i], a.rmass[j], r, c,
                                     false);
    return (SaltDEM::viscous_contact_force<DIM, EVFLAG>(p, c, f, ti, tj, evdwl) ? LAW_TOUCH : 0) |
        LAW_TORQUE;
  }

  // CONTACT mode: dashpot coefficient per unit viscosity, gamma = calibration * eta
  static constexpr double DEFAULT_CALIBRATION = 1.0;
  // FLUID mode: the Morris sum over a disordered polydisperse pack with volumes m/rho
  // returns eta_eff = 0.955 eta (channel flows, h = 1.45 spacings); this restores eta
  static constexpr double DEFAULT_CORRECTION = 1.047;

 protected:
  SaltDEM::ViscousParams **params;
  double **eta;       // requested viscosity per type pair (extract "eta": fix adapt, fixes)
  double *vol;        // FLUID: particle volume m / rho, owned and ghost atoms
  double *apress;     // FLUID: m P / rho^2 per atom (pressure term), owned and ghost atoms
  double *scratch;    // no FLUID pair: what the force pass sums the (zero) q into
  class FixSaltdemDensity *fix_density;    // FLUID: the density (state) and d rho / dt
  std::string density_id;                  // its ID
  int *fluidself;     // per type: its own pair is FLUID (continuity density, reference density)
  int *isfluid;       // per type: FLUID with K > 0 (carries pressure)
  int nmax;           // allocated length of vol
  bool any_fluid;     // some type pair uses the FLUID law
  double calibration;
  double correction;  // FLUID: Morris viscosity multiplied by this (measured, see above)
  double viscfactor;  // safety factor on the viscous stable dt
  bool dim2;          // 2D: discs
  double volfac;      // pi (2D) or 4 pi / 3 (3D)
  template <int DIM> void kernel_density(double *out);
  void grow_arrays();    // vol, apress (and scratch) for the owned and ghost atoms
  std::vector<double> rho_thr;    // -sf omp: per-thread partial sums of d rho / dt
  void allocate_params(int) override;
  void *pair_params(int i, int j) override { return &params[i][j]; }
  size_t params_size() const override { return sizeof(SaltDEM::ViscousParams); }
  void mix(int, int) override;
  void derive(int, int) override;
  double range(int i, int j) const override
  {
    return params[i][j].mode == SaltDEM::VISCOUS_CONTACT ? params[i][j].gap : 0.0;
  }
  double range_abs(int i, int j) const override
  {
    return params[i][j].mode == SaltDEM::VISCOUS_FLUID ? 2.0 * params[i][j].h : 0.0;
  }
  void init_style() override;
  void pair_limit(int, int, double, double, double &, std::string &) override;
  int restart_version() const override { return 1; }
  std::vector<std::string> setting_names() const override;
  void pack_settings(double *) const override;
  void unpack_settings(const double *) override;
  std::vector<std::string> coeff_names() const override;
  void pack_coeffs(int, int, double *) const override;
  void unpack_coeffs(int, int, const double *) override;
  double find_salt_inertia();
  // the time step check: the viscosities and calibration it saw (a change during the run,
  // e.g. by fix adapt, is checked again), and the inertial masses per disc volume it used
  void limits_checked() override;
  std::vector<std::vector<double>> eta_checked;
  double calibration_checked;
  double salt_inertia;    // extract("inertia"): the inertia factor of the salt's discs
};

}    // namespace LAMMPS_NS

#endif
#endif
