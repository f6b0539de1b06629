/* -*- c++ -*- ----------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(saltdem/nve,FixSaltdemNVE);
// clang-format on
#else

#ifndef LMP_FIX_SALTDEM_NVE_H
#define LMP_FIX_SALTDEM_NVE_H

#include "fix.h"

namespace LAMMPS_NS {

class FixSaltdemNVE : public Fix {
 public:
  FixSaltdemNVE(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void initial_integrate(int) override;
  void final_integrate() override;
  void reset_dt() override;
  void *extract(const char *, int &) override;

 protected:
  double inertia;       // inertial mass = inertia * rmass (quasi-static mass scaling)
  int check_every;      // steps between finite-value checks (0: never)
  double dtv, dtf, inertia_factor;    // moment of inertia = inertia_factor * m r^2
  int nthreads;         // OpenMP threads of the integration loops (saltdem/nve/omp)
  void check_finite();
  template <int DIM, bool DRIFT> void integrate();
};

}    // namespace LAMMPS_NS

#endif
#endif
