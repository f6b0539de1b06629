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

   The arguments of pair saltdem/viscous: its pair_style settings and the laws of its
   pair_coeff lines parsed into plain values, and the per type pair record its restart
   data holds.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_VISCOUS_ARGS_H
#define LMP_SALTDEM_VISCOUS_ARGS_H

#include <string>
#include <vector>

namespace LAMMPS_NS {
class LAMMPS;
namespace SaltDEM {
  struct ViscousParams;

  struct ViscousSettings {
    double correction, calibration, dtfactor, viscfactor, fill_max;
    int substeps;
    bool noslip_surface;
    bool implicit;       // the viscosity in an implicit (backward Euler) step
    double tolerance;    // implicit: residual over the residual at the start velocities
    int maxiter;         // implicit: the most iterations per step
  };

  // pair_style STYLE keywords onto s (what is not given keeps its value)
  void parse_viscous_settings(LAMMPS *lmp, const char *style, int narg, char **arg,
                              ViscousSettings &s, double dtfactor_max, int max_substeps);
  int parse_viscous_substeps(LAMMPS *lmp, const char *style, const char *str, int max_substeps);

  // pair_coeff I J eta kn LAW ... (arg as pair_coeff has it): the law's parameters and eta
  ViscousParams parse_viscous_coeff(LAMMPS *lmp, const char *style, int narg, char **arg,
                                    const char *usage, double &eta);

  // the restart record of the settings in layout `layout` (0: this version's; 1 had no fill
  // and substeps, 3 no noslip, 4 and 5 no implicit step)
  std::vector<std::string> viscous_setting_names(int layout);
  void pack_viscous_settings(const ViscousSettings &s, double *v);
  void unpack_viscous_settings(const double *v, int layout, double default_fill,
                               ViscousSettings &s);

  // the restart record of a type pair in layout `layout` (0: this version's)
  std::vector<std::string> viscous_coeff_names(int layout);
  void pack_viscous_coeff(const ViscousParams &p, double eta, double *v);
  void unpack_viscous_coeff(const double *v, int n, ViscousParams &p, double &eta);
}    // namespace SaltDEM
}    // namespace LAMMPS_NS

#endif
