/* -*- c++ -*- ----------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.
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
  double lambda;        // viscosity scaling factor: eta_model = eta_natural / lambda
  double eta_model, eta_natural;
  double rate;          // driving velocity of the model (m/s)
  double length;        // length scale of the flow (m)
  double density;       // density of the viscous material (kg/m^3)
  double inertia;       // inertia factor S of the salt's discs (fix saltdem/nve, through the pair)
  double inertia_given; // the keyword 'inertia' (0: not given), which must agree with S
  double warn_re;       // warn when the model Reynolds number exceeds this
  double t0;            // model time when the fix was defined (natural time counts from it)
  int npairs;           // type pairs whose viscosity the fix set
  double reported;      // the S of the summary in the log (0: none yet)

  std::vector<class Pair *> viscous_pairs();
  double salt_inertia(const std::vector<class Pair *> &);
  void check_finite();
  double model_time() const;
  double reynolds_model() const { return density * inertia * rate * length / eta_model; }
};

}    // namespace LAMMPS_NS

#endif
#endif
