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
PairStyle(saltdem/cohesive,PairSaltdemCohesive);
// clang-format on
#else

#ifndef LMP_PAIR_SALTDEM_COHESIVE_H
#define LMP_PAIR_SALTDEM_COHESIVE_H

#include "pair_saltdem.h"

namespace LAMMPS_NS {
namespace SaltDEM {
  struct CohesiveParams;
  struct CohesiveLaw;
}    // namespace SaltDEM

class PairSaltdemCohesive : public PairSaltdem {
 public:
  PairSaltdemCohesive(class LAMMPS *);
  ~PairSaltdemCohesive() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  void *extract(const char *, int &) override;

 protected:
  SaltDEM::CohesiveParams **params;    // per type pair coefficients (saltdem_contact_cohesive.h)
  bool rolling;                        // any pair with rolling resistance: 3 more history values
  double dt;

  // the law policy of the shared pair loop (saltdem_cohesive_law.h)
  SaltDEM::CohesiveLaw law() const;

  void allocate_params(int) override;
  void *pair_params(int i, int j) override;
  size_t params_size() const override;
  void mix(int, int) override;
  void derive(int, int) override;
  double range(int i, int j) const override;
  void pair_limit(int, int, double, double, bool, double &, std::string &) override;
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
