/* -*- c++ -*- ----------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(saltdem/cohesive,PairSaltdemCohesive);
// clang-format on
#else

#ifndef LMP_PAIR_SALTDEM_COHESIVE_H
#define LMP_PAIR_SALTDEM_COHESIVE_H

#include "pair_saltdem.h"

namespace LAMMPS_NS {

class PairSaltdemCohesive : public PairSaltdem {
 public:
  PairSaltdemCohesive(class LAMMPS *);
  ~PairSaltdemCohesive() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  void *extract(const char *, int &) override;

  // the force law, inlined into the shared pair loop (PairSaltdem::loop); no per-atom sum
  static constexpr bool HISTORY = true;    // the law keeps values per touching pair
  static constexpr bool PAIR_SUM = false;
  template <int DIM, int EVFLAG>
  int law(const Atoms &a, int i, int j, int itype, int jtype, double r, double *hist,
          bool advance, double *f, double *ti, double *tj, double &evdwl, double &) const
  {
    SaltDEM::Contact c;
    SaltDEM::contact_kinematics<DIM>(a.x[i], a.x[j], a.v[i], a.v[j], a.omega[i], a.omega[j],
                                     a.radius[i], a.radius[j], a.rmass[i], a.rmass[j], r, c,
                                     rolling);
    return SaltDEM::cohesive_force<DIM, EVFLAG>(params[itype][jtype], c, hist, rolling, dt,
                                                advance, f, ti, tj, evdwl)
        ? (LAW_TOUCH | LAW_TORQUE)
        : 0;
  }

 protected:
  SaltDEM::CohesiveParams **params;
  bool rolling;    // any pair with rolling resistance: 3 more history values
  double dt;

  void allocate_params(int) override;
  void *pair_params(int i, int j) override { return &params[i][j]; }
  size_t params_size() const override { return sizeof(SaltDEM::CohesiveParams); }
  void mix(int, int) override;
  void derive(int, int) override;
  double range(int i, int j) const override { return params[i][j].tens > 0.0 ? params[i][j].range : 0.0; }
  void pair_limit(int, int, double, double, double &, std::string &) override;
  int restart_version() const override { return 1; }
  std::vector<std::string> setting_names() const override { return {"dtfactor"}; }
  void pack_settings(double *v) const override { v[0] = dtfactor; }
  void unpack_settings(const double *v) override { dtfactor = v[0]; }
  std::vector<std::string> coeff_names() const override;
  void pack_coeffs(int, int, double *) const override;
  void unpack_coeffs(int, int, const double *) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
