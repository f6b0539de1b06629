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

#ifdef FIX_CLASS
// clang-format off
FixStyle(saltdem/viscosity,FixSaltdemViscosity);
// clang-format on
#else

#ifndef LMP_FIX_SALTDEM_VISCOSITY_H
#define LMP_FIX_SALTDEM_VISCOSITY_H

#include "fix.h"

namespace LAMMPS_NS {

class FixSaltdemViscosity : public Fix {
 public:
  FixSaltdemViscosity(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

 protected:
  double lambda;    // viscosity scaling factor: eta_model = eta_natural / lambda
  double eta_model, eta_natural;
  double rate;        // driving velocity of the model (length/time)
  double length;      // length scale of the flow (m)
  double density;     // density of the viscous material (mass/volume)
  double contrast;    // density of the overburden minus the salt's (0: not given)
  double gravity;     // acceleration of gravity (deck's units; 9.81 under si)
  double inertia;     // inertia factor S of the salt's discs (fix saltdem/nve, through the pair)
  double inertia_given;    // the keyword 'inertia' (0: not given), which must agree with S
  double warn_re;          // warn when the model Reynolds number exceeds this
  double t0;               // model time when the fix was defined (natural time counts from it)
  int npairs;              // type pairs whose viscosity the fix set
  double reported;         // the S of the summary in the log (0: none yet)

  // S as the salt's pair styles have it (the largest of several): found now (collective; before
  // a run's init) or as of the run's init (extract "inertia")
  double salt_inertia(const std::vector<class PairSaltdem *> &, bool now);
  void check_finite();
  double model_time() const;
  std::string unit_label(const char *si) const;
  // the deck's units: force x time / mass to velocity, seconds per time unit, metres per
  // length unit (1, 1, 1 in SI)
  double ftm2v, second, metre;
  // what the fix reports, in SI: Reynolds numbers, natural rate (m/ka), strain rates (1/s)
  double reynolds_model() const { return density * inertia * rate * length / (eta_model * ftm2v); }
  double reynolds_natural() const
  {
    return density * (rate / lambda) * length / (eta_natural * ftm2v);
  }
  double natural_rate() const { return rate / lambda * metre / second * YEAR * 1000.0; }
  double strain_rate_model() const { return rate / length / second; }
  double strain_rate_natural() const { return rate / (lambda * length) / second; }
  // buoyancy: the stress drho g L against the viscous stress eta V / L (deck's pressure units),
  // the buoyancy time eta / (|drho| g L) (s) and Reynolds number S rho |drho| g L^3 / eta^2
  double buoyancy_stress() const { return contrast * gravity * length / ftm2v; }
  double viscous_stress() const { return eta_model * rate / length; }
  double buoyancy_time() const;
  double reynolds_buoyancy() const;
  static constexpr double YEAR = 365.25 * 24.0 * 3600.0;    // s
  static constexpr double RESTART_VERSION = 1.0;            // layout of the restart data
};

}    // namespace LAMMPS_NS

#endif
#endif
