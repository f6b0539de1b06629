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

   fix saltdem/sediment: syn-tectonic sedimentation and erosion
   (docs/fix_saltdem_sediment.rst).
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(saltdem/sediment,FixSaltdemSediment);
// clang-format on
#else

#ifndef LMP_FIX_SALTDEM_SEDIMENT_H
#define LMP_FIX_SALTDEM_SEDIMENT_H

#include "fix.h"

namespace LAMMPS_NS {

class FixSaltdemSediment : public Fix {
 public:
  FixSaltdemSediment(class LAMMPS *, int, char **);
  ~FixSaltdemSediment() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;
  void pre_exchange() override;
  void post_force(int) override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

 private:
  enum { MODE_NONE, MODE_FILL, MODE_RATE };
  enum { DRIVE_STEPS, DRIVE_VARIABLE, DRIVE_FIX };

  int mode;         // none (erosion only), fill (to the base level) or rate
  double rate;      // rate mode: disc area per unit length and time (m^2 / (m s))
  double length;    // rate mode: length the rate is given per (default: the window's)
  int length_given;

  // interval: every nsteps steps, or every 'every' of drive displacement
  int drive_kind;
  double every;
  bigint nsteps;
  std::string drive_name;    // variable name, or fix ID
  int drive_index;           // fix: 0 scalar, >= 1 vector element
  int drive_ivar;
  class Fix *drive_fix;

  int erode_igroup, erode_groupbit;
  std::string epoch_name;    // per-atom integer (fix property/atom i_NAME) for the epoch

  class SaltdemSedimentLevels *levels;      // frame of gravity, base and erosion levels, window
  class SaltdemSedimentDeposit *deposit;    // the new discs
  class SaltdemSedimentSettle *settle;      // their damped settling

  // state, written to restart files
  int epoch;            // deposition intervals so far
  double ndep, nero;    // discs deposited, eroded (counts, exact in a double)
  double adep, aero;    // their area
  double abyp;          // rate mode: area that found no room below the base level
  double carry;         // rate mode: requested minus deposited area of the last interval (<= 0)
  double t_last;        // rate mode: time of the last interval
  int t_last_set;
  double next_drive;    // drive displacement of the next interval
  int next_set;
  double last_level;            // base level at the last interval
  double last_n, last_area;     // deposited in the last interval
  double last_xlo, last_xhi;    // the window at the last interval

  // decided at the end of a step (or at setup): deposit at the next step
  int pending;
  double drive_at_decision;

  std::string usage;

  double drive_value();
  void decide();
  bool has_cover_law(int itype);
  double now() const;
  void deposition(double level, double time);
};

}    // namespace LAMMPS_NS

#endif
#endif
